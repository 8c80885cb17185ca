// sdsm on the CPU: its logarithmic slices and side ladder, and its cascades against a stand-in for
// the GPU reduction (the same bounds taken on the CPU from surface samples): every sample inside
// its cascade, each cascade tight around its samples, whole-texel moves only when stabilised.
#include "ProjectionSamples.h"
#include "techniques/projections/CascadedProjection.h"
#include "techniques/projections/LightSpace.h"
#include "techniques/projections/SampleDistributionProjection.h"

#include "techniques/Registry.h"
#include <penumbra/SceneIO.h>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

using namespace penumbra;
using penumbra::test::visibleSurfaceSamples;

namespace {

constexpr float kAspect = 16.0f / 9.0f;
constexpr int kMapSize = 1024;

// PixelBounds from world points: what the GPU reduction computes from the covered pixels.
class PointBounds final : public PixelBounds {
public:
  PointBounds(std::vector<glm::vec3> points, const Camera& camera) : mPoints(std::move(points)), mCamera(camera) {}
  glm::vec2 depthRange() override { return cameraDepthRange(mPoints, mCamera); }
  std::vector<Aabb> sliceBounds(const glm::mat4& spaceFromWorld, std::span<const float> nearM, std::span<const float> farM) override {
    ++calls;
    std::vector<Aabb> out(nearM.size());
    for (const glm::vec3& p : mPoints) {
      const float d = glm::dot(p - mCamera.position, mCamera.forward());
      for (size_t i = 0; i < out.size(); ++i)
        if (d >= nearM[i] && d <= farM[i]) out[i].extend(glm::vec3(spaceFromWorld * glm::vec4(p, 1.0f)));
    }
    return out;
  }
  int calls = 0;

private:
  std::vector<glm::vec3> mPoints;
  Camera mCamera;
};

glm::vec2 ndc(const ShadowView& v, const glm::vec3& p) {
  const glm::vec4 c = v.clipFromWorld * glm::vec4(p, 1.0f);
  return glm::vec2(c) / c.w;
}

// The camera-depth interval view i must cover (its slice, with the blend band before its split).
std::pair<float, float> sliceOf(const LightFrusta& f, size_t i) {
  const float a = i == 0 ? 0.0f : f.views[i - 1].splitFarM - f.blendBandM;
  const float b = i + 1 == f.views.size() ? std::numeric_limits<float>::max() : f.views[i].splitFarM;
  return {a, b};
}

}  // namespace

TEST(Sdsm, SlicesAreLogarithmicWithABlendBandBeforeEachSplit) {
  const CascadeSlices s = logarithmicSlices(2.0f, 512.0f, 4, 1.0f);
  ASSERT_EQ(s.nearM.size(), 4u);
  EXPECT_FLOAT_EQ(s.nearM[0], 2.0f);
  EXPECT_FLOAT_EQ(s.farM[3], 512.0f);
  for (size_t i = 0; i < 4; ++i) EXPECT_NEAR(s.farM[i], 2.0f * std::pow(4.0f, static_cast<float>(i + 1)), 1e-3f * s.farM[i]);
  for (size_t i = 1; i < 4; ++i) EXPECT_FLOAT_EQ(s.nearM[i], s.farM[i - 1] - s.blendBandM);
  EXPECT_FLOAT_EQ(s.blendBandM, 1.0f);
  // At most half the shortest slice (2 → 8 m: 3 m).
  EXPECT_FLOAT_EQ(logarithmicSlices(2.0f, 512.0f, 4, 100.0f).blendBandM, 3.0f);
}

TEST(Sdsm, SidesTakeEighthOctaves) {
  for (float need : {0.37f, 1.0f, 5.5f, 123.4f}) {
    const float side = stableCascadeSide(need);
    EXPECT_GE(side, need);
    EXPECT_LT(side, need * std::exp2(0.125f) * 1.0001f);
    EXPECT_FLOAT_EQ(std::exp2(std::round(std::log2(side) * 8.0f) / 8.0f), side);
  }
  EXPECT_EQ(stableCascadeSide(5.5f), stableCascadeSide(5.51f));
}

// Every pixel in its cascade's map, and the cascade no larger than the ladder and the margins
// make it: the pixels span most of each axis (csm's cascade sides printed beside).
TEST(Sdsm, CascadesHoldTheirPixelsTightly) {
  for (const char* name : {"city", "boxes", "fence"}) {
    const Scene scene = makeBuiltinScene(name);
    PointBounds pixels(visibleSurfaceSamples(scene, kAspect, 4000, 3), scene.camera);
    auto p = makeProjection("sdsm");
    const LightFrusta f = p->computeFrustaFromPixels(scene.camera, kAspect, scene.light(), scene.extent(), kMapSize, pixels);
    ASSERT_EQ(f.views.size(), 4u) << name;
    EXPECT_EQ(pixels.calls, 1) << name;  // one reduction for every cascade's bounds
    const auto csm = makeProjection("csm")->computeFrusta(scene.camera, kAspect, scene.light(), scene.extent(), kMapSize);
    for (size_t i = 0; i < f.views.size(); ++i) {
      const auto [a, b] = sliceOf(f, i);
      glm::vec2 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
      int inSlice = 0, outside = 0;
      for (const glm::vec3& q : visibleSurfaceSamples(scene, kAspect, 4000, 3)) {
        const float d = glm::dot(q - scene.camera.position, scene.camera.forward());
        if (d < a || d > b) continue;
        ++inSlice;
        const glm::vec2 c = ndc(f.views[i], q);
        lo = glm::min(lo, c);
        hi = glm::max(hi, c);
        outside += std::abs(c.x) > 1.0f || std::abs(c.y) > 1.0f;
      }
      if (inSlice == 0) continue;
      EXPECT_EQ(outside, 0) << name << " cascade " << i;
      // 1/8 octave (×1.09) on each side, 3 texels each side of 1024: at least 1.8 of the 2 NDC units.
      const glm::vec2 span = hi - lo;
      std::printf("%-6s cascade %zu: %5d samples span %.3f x %.3f of 2 x 2; map %.1f x %.1f m (csm: %.1f m)\n", name, i,
                  inSlice, span.x, span.y, f.views[i].extent.x, f.views[i].extent.y, csm.views[i].extent.x);
      EXPECT_GT(span.x, 1.8f) << name << " cascade " << i;
      EXPECT_GT(span.y, 1.8f) << name << " cascade " << i;
    }
  }
}

// Stabilised: the same pixels moved with the camera by part of a texel along the light's x axis
// change the matrix at most once, by exactly one texel, and only in its translation.
TEST(Sdsm, StabilisedCascadesMoveByWholeTexels) {
  const Scene scene = makeBuiltinScene("city");
  const std::vector<glm::vec3> samples = visibleSurfaceSamples(scene, kAspect, 3000, 5);
  auto p = makeProjection("sdsm");
  PointBounds first(samples, scene.camera);
  const LightFrusta f0 = p->computeFrustaFromPixels(scene.camera, kAspect, scene.light(), scene.extent(), kMapSize, first);
  const glm::vec3 lightX = glm::vec3(glm::inverse(f0.views[0].viewFromWorld)[0]);
  for (size_t v = 0; v < f0.views.size(); ++v) {
    const float texelM = f0.views[v].extent.x / static_cast<float>(kMapSize);
    const float ndcPerTexel = 2.0f / static_cast<float>(kMapSize);
    int changes = 0;
    glm::mat4 previous = f0.views[v].clipFromWorld;
    for (int k = 1; k < 32; ++k) {
      const glm::vec3 move = lightX * (texelM * static_cast<float>(k) / 32.0f);
      Camera c = scene.camera;
      c.position += move;
      c.target += move;
      std::vector<glm::vec3> moved = samples;
      for (glm::vec3& q : moved) q += move;
      PointBounds pixels(moved, c);
      const glm::mat4 m = p->computeFrustaFromPixels(c, kAspect, scene.light(), scene.extent(), kMapSize, pixels).views[v].clipFromWorld;
      if (m == previous) continue;
      ++changes;
      for (int col = 0; col < 3; ++col) EXPECT_EQ(m[col], previous[col]) << "view " << v << ": rotation/scale changed";
      EXPECT_NEAR(std::abs(m[3].x - previous[3].x) / ndcPerTexel, 1.0f, 1e-2f) << "view " << v;
      previous = m;
    }
    EXPECT_LE(changes, 1) << "view " << v;
  }
}

// Without the pixels (map budgets, CPU tools) the same number of cascades, fitted to the geometry.
TEST(Sdsm, WithoutPixelsFitsTheGeometryWithTheSameViewCount) {
  const Scene scene = makeBuiltinScene("city");
  auto p = makeProjection("sdsm");
  p->setParam("sdsm.cascades", 3.0f);
  const LightFrusta f = p->computeFrusta(scene.camera, kAspect, scene.light(), scene.extent(), kMapSize);
  ASSERT_EQ(f.views.size(), 3u);
  for (size_t i = 1; i < f.views.size(); ++i) EXPECT_GT(f.views[i].splitFarM, f.views[i - 1].splitFarM);
}
