// EmbreeScene's coherent ray streams (the reference casts each pixel's light samples as one) answer
// exactly what one occluded() call per ray answers: on boxes, from floor points under and beside the
// casters, toward cones of directions around the sun, with the receiver's triangle skipped and
// segments that start off the surface.
#include "reference/EmbreeScene.h"

#include <penumbra/SceneIO.h>

#include <glm/glm.hpp>
#include <gtest/gtest.h>

#include <random>

using namespace penumbra;

TEST(EmbreeBundle, StreamAnswersAsOneRayAtATime) {
  const Scene scene = makeBuiltinScene("boxes");
  const reference::EmbreeScene embree(scene);
  constexpr int kOrigins = 400, kRaysPerOrigin = 64;
  constexpr float kConeSpread = 0.3f;  // around the sun's direction: penumbrae and umbrae both
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> across(-3.0f, 3.0f), spread(-kConeSpread, kConeSpread), near(0.0f, 0.01f);
  const glm::vec3 toSun = -glm::normalize(scene.light().direction);
  reference::EmbreeScene::Bundle bundle;
  size_t blocked = 0, total = 0, mismatches = 0;
  for (int o = 0; o < kOrigins; ++o) {
    const glm::vec3 origin(across(rng), 0.0f, across(rng));  // on the floor (object 0)
    const reference::TriangleId skip{0, 0};
    bundle.clear();
    std::vector<glm::vec3> dirs;
    std::vector<float> tNear;
    for (int k = 0; k < kRaysPerOrigin; ++k) {
      dirs.push_back(glm::normalize(toSun + glm::vec3(spread(rng), spread(rng), spread(rng))));
      tNear.push_back(near(rng));
      bundle.add(origin, dirs.back(), tNear.back(), 1e30f);
    }
    embree.occluded(bundle, skip);
    for (int k = 0; k < kRaysPerOrigin; ++k) {
      const bool single = embree.occluded(origin, dirs[static_cast<size_t>(k)], tNear[static_cast<size_t>(k)], 1e30f, skip);
      mismatches += single != bundle.blocked(static_cast<size_t>(k));
      blocked += single;
      ++total;
    }
  }
  EXPECT_EQ(mismatches, 0u);
  // Both answers occur: the rays pass the casters and miss them.
  EXPECT_GT(blocked, total / 50);
  EXPECT_LT(blocked, total - total / 50);
}
