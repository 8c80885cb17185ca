// One texel budget for every light's maps (core::allocateMapSizes, core::lightImportance): sizes
// follow importance, never exceed a light's request, and fill the budget without passing it.
#include "core/ShadowBudget.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

using namespace penumbra;
using core::BudgetRequest;

namespace {

int64_t texels(const std::vector<BudgetRequest>& requests, const std::vector<int>& sizes) {
  int64_t sum = 0;
  for (size_t i = 0; i < requests.size(); ++i) sum += int64_t{requests[i].views} * sizes[i] * sizes[i];
  return sum;
}

Camera cameraAtOriginLookingDownZ() {
  Camera c;
  c.position = {0.0f, 0.0f, 0.0f};
  c.target = {0.0f, 0.0f, -1.0f};
  c.fovYRad = 1.0f;
  return c;
}

Light pointAt(glm::vec3 position, float rangeM) {
  Light l;
  l.type = LightType::Point;
  l.position = position;
  l.rangeM = rangeM;
  return l;
}

}  // namespace

TEST(ShadowBudget, NoBudgetOrEnoughBudgetGivesEveryLightItsRequest) {
  const std::vector<BudgetRequest> requests{{2048, 1, 1.0}, {1024, 6, 0.1}, {512, 4, 0.5}};
  const std::vector<int> asked{2048, 1024, 512};
  EXPECT_EQ(core::allocateMapSizes(requests, 0), asked);
  EXPECT_EQ(core::allocateMapSizes(requests, texels(requests, asked)), asked);
  EXPECT_EQ(core::allocateMapSizes(requests, int64_t{1} << 40), asked);
}

TEST(ShadowBudget, ATightBudgetIsFilledWithoutBeingPassedAndFollowsImportance) {
  // Two spots and a point light (six faces) asking 2048² each: 29.4 M texels against 8 M.
  const std::vector<BudgetRequest> requests{{2048, 1, 1.0}, {2048, 1, 0.25}, {2048, 6, 0.25}};
  const int64_t budget = 8 << 20;
  const std::vector<int> sizes = core::allocateMapSizes(requests, budget);
  ASSERT_EQ(sizes.size(), 3u);
  EXPECT_LE(texels(requests, sizes), budget);
  // Filled, up to rounding each side down to a multiple of kMinBudgetMapSize.
  EXPECT_GT(texels(requests, sizes), budget * 9 / 10);
  for (int s : sizes) {
    EXPECT_LE(s, 2048);
    EXPECT_EQ(s % core::kMinBudgetMapSize, 0);
  }
  // side² ∝ importance: a quarter of the importance gets half the side (within one rounding step),
  // whatever the number of faces.
  EXPECT_NEAR(sizes[1], sizes[0] / 2, core::kMinBudgetMapSize);
  EXPECT_EQ(sizes[1], sizes[2]);
}

TEST(ShadowBudget, ALightIsNeverGivenMoreThanItAsked) {
  // The small light's share would be 1448² on its own; it asked for 256², the rest goes to the others.
  const std::vector<BudgetRequest> requests{{256, 1, 1.0}, {4096, 1, 1.0}};
  const int64_t budget = int64_t{2048} * 2048 * 2;
  const std::vector<int> sizes = core::allocateMapSizes(requests, budget);
  EXPECT_EQ(sizes[0], 256);
  EXPECT_GT(sizes[1], 2048);
  EXPECT_LE(texels(requests, sizes), budget);
}

TEST(ShadowBudget, ABudgetBelowTheSmallestMapsGivesEveryLightTheSmallest) {
  const std::vector<BudgetRequest> requests{{1024, 6, 1.0}, {1024, 1, 0.5}};
  const std::vector<int> sizes = core::allocateMapSizes(requests, 100);
  EXPECT_EQ(sizes, (std::vector<int>{core::kMinBudgetMapSize, core::kMinBudgetMapSize}));
}

TEST(ShadowBudget, ImportanceIsTheImageShareOfTheLightsReach) {
  const Camera camera = cameraAtOriginLookingDownZ();
  const Aabb bounds{glm::vec3(-100.0f), glm::vec3(100.0f)};
  Light sun;
  EXPECT_EQ(core::lightImportance(sun, camera, 1.0f, bounds), 1.0);
  // The camera inside the light's range: the whole image.
  EXPECT_EQ(core::lightImportance(pointAt({0, 0, -2}, 5.0f), camera, 1.0f, bounds), 1.0);
  // A sphere of range r at distance d ahead covers (tan R / tan(fov/2))² of a square image.
  const float d = 40.0f, r = 4.0f;
  const double tanR = std::tan(std::asin(r / d)), tanHalf = std::tan(0.5);
  EXPECT_NEAR(core::lightImportance(pointAt({0, 0, -d}, r), camera, 1.0f, bounds), (tanR / tanHalf) * (tanR / tanHalf), 1e-6);
  // Farther is less important; wholly behind the camera keeps the least.
  EXPECT_LT(core::lightImportance(pointAt({0, 0, -2 * d}, r), camera, 1.0f, bounds),
            core::lightImportance(pointAt({0, 0, -d}, r), camera, 1.0f, bounds));
  EXPECT_EQ(core::lightImportance(pointAt({0, 0, d}, r), camera, 1.0f, bounds), core::kMinImportance);
  // Without a range, its reach is the scene: a light inside the bounds covers the image.
  EXPECT_EQ(core::lightImportance(pointAt({0, 0, -d}, 0.0f), camera, 1.0f, bounds), 1.0);
}
