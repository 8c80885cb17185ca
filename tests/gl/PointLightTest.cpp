// Point lights: six cube faces as views of one map array, filtered across face edges without a
// seam. A ring of posts around a lamp casts shadows on the floor that cross the edges of the
// downward face (|x| or |z| = the lamp's height), where a kernel or a blocker search that clamped
// at the face's border would read the wrong depths.
#include "GlFixture.h"

#include <penumbra/Metrics.h>
#include <penumbra/Reference.h>

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

using namespace penumbra;
using namespace penumbra::test;

namespace {

constexpr float kLampHeightM = 1.5f;
constexpr int kW = 200, kH = 150, kMap = 256;
constexpr int kPosts = 10;

Scene postsAroundALamp() {
  Scene s;
  s.name = "posts";
  addObject(s, "floor", makePlane(12.0f, 12.0f), {0.7f, 0.7f, 0.7f});
  constexpr float kRingM = 1.0f, kPostHeightM = 0.7f;
  for (int i = 0; i < kPosts; ++i) {
    const float a = 6.2831853f * (static_cast<float>(i) + 0.3f) / kPosts;
    addObject(s, "post", makeBox({0.12f, kPostHeightM, 0.12f}), {0.8f, 0.4f, 0.3f},
              glm::translate(glm::mat4(1.0f), {kRingM * std::cos(a), 0.5f * kPostHeightM, kRingM * std::sin(a)}));
  }
  Light lamp;
  lamp.type = LightType::Point;
  lamp.position = {0.0f, kLampHeightM, 0.0f};
  lamp.size = 0.1f;
  lamp.intensity = 10.0f;
  s.lights.push_back(lamp);
  s.camera.position = {0.0f, 5.5f, 3.5f};
  s.camera.target = {0.0f, 0.0f, 0.0f};
  s.camera.fovYRad = 1.0f;
  return s;
}

// Texels from the edge of the cube face that a lookup from the lamp toward ws falls on: the
// face spans mapSize − 2·guard texels (UniformProjection's guard band lies beyond its edge).
float texelsFromFaceEdge(const glm::vec3& ws, const glm::vec3& lamp, int mapSize, float guardTexels) {
  const glm::vec3 d = glm::abs(ws - lamp);
  const float major = std::max({d.x, d.y, d.z});
  const float minor = d.x == major ? std::max(d.y, d.z) : d.y == major ? std::max(d.x, d.z) : std::max(d.x, d.y);
  return (1.0f - minor / major) * 0.5f * (static_cast<float>(mapSize) - 2.0f * guardTexels);
}

struct SeamErrors {
  double seamRmse = 0.0, elsewhereRmse = 0.0;
  size_t seamPixels = 0, elsewherePixels = 0;
};

// RMSE of V against the reference on the pixels in or near a shadow (either V below 0.98), split
// by whether their lookup falls within two texels of a face edge.
SeamErrors seamErrors(const Scene& scene, const std::string& filter, float guardTexels) {
  const RenderResult r = renderScene(scene, "uniform", filter, {{"uniform.cubeGuardTexels", std::to_string(guardTexels)}},
                                     kW, kH, kMap);
  ReferenceOptions o;
  o.useCache = false;
  o.progress = false;
  o.samples = 64;
  const ReferenceResult ref = ReferenceTracer(scene).trace(r.gbuffer, scene.light(), o);
  constexpr float kShadowed = 0.98f, kSeamTexels = 2.0f;
  double seamSq = 0.0, elseSq = 0.0;
  SeamErrors e;
  for (size_t i = 0; i < r.visibility.size(); ++i) {
    if (!ref.litMask[i] || (r.visibility[i] >= kShadowed && ref.visibility[i] >= kShadowed)) continue;
    const double d = static_cast<double>(r.visibility[i]) - ref.visibility[i];
    if (texelsFromFaceEdge(glm::vec3(r.gbuffer.position[i]), scene.light().position, kMap, guardTexels) <= kSeamTexels) {
      seamSq += d * d;
      ++e.seamPixels;
    } else {
      elseSq += d * d;
      ++e.elsewherePixels;
    }
  }
  e.seamRmse = std::sqrt(seamSq / std::max<size_t>(e.seamPixels, 1));
  e.elsewhereRmse = std::sqrt(elseSq / std::max<size_t>(e.elsewherePixels, 1));
  std::printf("%-4s guard %3.0f texels: RMSE %.4f on %zu seam pixels, %.4f on %zu others (x%.2f)\n", filter.c_str(),
              guardTexels, e.seamRmse, e.seamPixels, e.elsewhereRmse, e.elsewherePixels, e.seamRmse / e.elsewhereRmse);
  return e;
}

}  // namespace

// Within two texels of a face edge, pcf's kernel and pcss's blocker search read the guard band
// (the scene beyond the edge) and the error stays within 1.5× of the error elsewhere.
TEST(PointLight, FilteringAcrossCubeFaceEdgesLeavesNoSeam) {
  const Scene scene = postsAroundALamp();
  constexpr float kGuardTexels = 32.0f;  // UniformProjection's default
  constexpr double kMaxSeamRatio = 1.5;
  for (const std::string filter : {"pcf", "pcss"}) {
    const SeamErrors e = seamErrors(scene, filter, kGuardTexels);
    ASSERT_GE(e.seamPixels, 40u) << filter << ": the shadows must cross the face edges";
    ASSERT_GE(e.elsewherePixels, 400u) << filter;
    EXPECT_LE(e.seamRmse, kMaxSeamRatio * e.elsewhereRmse) << filter;
  }
  // The measure sees a seam where there is one: without the guard band pcss's blocker search
  // clamps at the face's border (measured x1.89 against x0.80 with it; pcf's small kernel barely
  // notices, x1.02).
  const SeamErrors clamped = seamErrors(scene, "pcss", 0.0f);
  EXPECT_GT(clamped.seamRmse, kMaxSeamRatio * clamped.elsewhereRmse);
}
