// PCF under cascades: pcf.radiusTexels counts texels of cascade 0 and is held in metres in the
// others, so the width of the blurred edge does not jump at each split (issue: "every filter
// works per cascade"). A wall's straight shadow edge runs away from the camera through every
// cascade; the band of fractional V across it is measured in metres on the floor. The wall's foot
// is measured apart: the default bias ('plane', one texel of world size along the normal and one
// more per texel a tap is carried) lifts the receiver off the floor by about two texels of each
// cascade, so the shadow there starts that far from the wall (contact detachment, not blur).
#include "GlFixture.h"

#include <penumbra/Scene.h>

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

namespace penumbra::test {
namespace {

// A 2 m wall (0.2 m thick) along −z at x = 0 under a sun at 45° from +x: its shadow covers the
// floor from its foot at x = 0.1 to the edge x = 2.1, from the camera's feet to 120 m away.
Scene wallScene() {
  Scene s;
  s.name = "wall edge";
  addObject(s, "floor", makePlane(300.0f, 300.0f), {0.7f, 0.7f, 0.7f});
  addObject(s, "wall", makeBox({0.2f, 2.0f, 120.0f}), {0.8f, 0.3f, 0.3f},
            glm::translate(glm::mat4(1.0f), {0.0f, 1.0f, -60.0f}));
  Light sun;
  sun.direction = glm::normalize(glm::vec3(1.0f, -1.0f, 0.0f));
  s.lights.push_back(sun);
  s.camera.position = {3.5f, 2.5f, 4.0f};
  s.camera.target = {2.0f, 0.0f, -30.0f};
  s.camera.fovYRad = 0.7f;
  s.camera.farM = 120.0f;
  return s;
}

constexpr float kWallFaceX = 0.1f;  // the wall's shadowed face; its shadow on the floor runs to x = 2.1
constexpr float kEdgeSideX = 1.0f;  // the floor beside the edge: x > this (the foot is ~1 m away)

// Per camera-depth bin of the floor (bins between binEdgesM), the median over rows of: the width
// (m, across the edge) of the fractional-V band beside the shadow edge, and the foot's detachment
// (m from the wall's face to the farthest pixel under the wall with V > 0.02; 0 when none).
struct EdgeAndFoot {
  std::map<int, double> bandM, footM;
};
EdgeAndFoot measureByDepth(const RenderResult& r, const Scene& s, const std::vector<float>& binEdgesM) {
  std::map<int, std::vector<double>> widths, feet;  // bin -> per-row values
  const glm::vec3 forward = glm::normalize(s.camera.target - s.camera.position);
  for (int y = 0; y < r.height; ++y) {
    float lo = 1e9f, hi = -1e9f, foot = kWallFaceX, depth = 0.0f;
    int n = 0;
    for (int x = 0; x < r.width; ++x) {
      const size_t i = static_cast<size_t>(y) * static_cast<size_t>(r.width) + static_cast<size_t>(x);
      const glm::vec4 p = r.gbuffer.position[i];
      if (p.w < 0.5f || std::abs(p.y) > 1e-3f || p.x < kWallFaceX) continue;  // the floor on the shadow's side
      const float v = r.visibility[i];
      if (p.x < kEdgeSideX) {
        if (v > 0.02f) foot = std::max(foot, p.x);
        continue;
      }
      if (v <= 0.02f || v >= 0.98f) continue;
      lo = std::min(lo, p.x);
      hi = std::max(hi, p.x);
      depth += glm::dot(glm::vec3(p) - s.camera.position, forward);
      ++n;
    }
    if (n < 2) continue;
    depth /= static_cast<float>(n);
    for (size_t b = 0; b + 1 < binEdgesM.size(); ++b)
      if (depth >= binEdgesM[b] && depth < binEdgesM[b + 1]) {
        widths[static_cast<int>(b)].push_back(hi - lo);
        feet[static_cast<int>(b)].push_back(foot - kWallFaceX);
      }
  }
  const auto median = [](std::map<int, std::vector<double>>& byBin) {
    std::map<int, double> m;
    for (auto& [b, w] : byBin) {
      std::nth_element(w.begin(), w.begin() + static_cast<std::ptrdiff_t>(w.size() / 2), w.end());
      m[b] = w[w.size() / 2];
    }
    return m;
  };
  return {median(widths), median(feet)};
}

TEST(CsmPcf, BlurWidthInMetresHoldsAcrossCascades) {
  const Scene scene = wallScene();
  constexpr int kW = 320, kH = 240, kMap = 512;
  const RenderResult r = renderScene(scene, "csm", "pcf",
                                     {{"pcf.kernel", "box"}, {"pcf.radiusTexels", "4"}, {"csm.cascades", "4"},
                                      {"csm.blendBandM", "0"}},
                                     kW, kH, kMap);
  ASSERT_GE(r.frusta.views.size(), 3u);
  // Bins: the cascades' slices of camera depth (each view ends at its splitFarM).
  const std::vector<ShadowView>& v = r.frusta.views;
  ASSERT_EQ(v.size(), 4u);
  const std::vector<float> edges = {v[0].splitFarM, v[1].splitFarM, v[2].splitFarM, v[3].splitFarM};
  const EdgeAndFoot m = measureByDepth(r, scene, edges);
  const std::map<int, double>& w = m.bandM;
  ASSERT_TRUE(w.count(0) && w.count(2)) << "the edge must be seen in cascades 1 and 3";
  const double texel1 = v[1].extent.x / kMap, texel3 = v[3].extent.x / kMap;
  std::printf("csm pcf box r=4 (cascade 0 texel %.4f m): band %.3f m in cascade 1 (texel %.4f m), %.3f m in cascade 3 "
              "(texel %.4f m); foot detached %.3f m in cascade 1, %.3f m in cascade 3\n",
              v[0].extent.x / kMap, w.at(0), texel1, w.at(2), texel3, m.footM.at(0), m.footM.at(2));
  ASSERT_GT(texel3, 3.0 * texel1) << "the scene must give cascades of different texel sizes";
  // A radius fixed in texels would widen the band by texel3 / texel1; held in metres it stays
  // within a couple of (coarser) texels of cascade 1's width.
  EXPECT_LT(w.at(2), w.at(0) + 2.0 * texel3);
  EXPECT_LT(w.at(2) / w.at(0), 0.5 * texel3 / texel1);
  // The foot: at most two texels of the cascade (the bias's reach: one texel + up to one more
  // for the tap's distance, each t / cos 45° of depth here, minus what the blockers stand above).
  EXPECT_LE(m.footM.at(0), 2.0 * texel1);
  EXPECT_LE(m.footM.at(2), 2.0 * texel3);
}

}  // namespace
}  // namespace penumbra::test
