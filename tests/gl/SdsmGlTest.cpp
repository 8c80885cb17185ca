// sdsm through the core: the GPU reduction (passes/pixel_bounds.comp.glsl, frame/
// PixelBoundsReducer) places each cascade around the pixels it measured. Checked against the
// G-buffer read back: every covered pixel that faces the sun lies inside the cascade(s) of its
// depth, and those pixels span nearly the whole map both ways (the sides take eighth octaves and
// 3 texels of margin a side); projections that ask nothing run no reduction pass.
#include "GlFixture.h"

#include <cstdio>
#include <limits>

using namespace penumbra;
using namespace penumbra::test;

namespace {

constexpr int kWidth = 320, kHeight = 180, kMapSize = 1024;
constexpr float kMinSpanNdc = 1.75f;  // of 2: the ladder's ×1.09, margins and snapping
constexpr size_t kMinPixels = 200;    // a cascade with fewer is not checked for tightness

}  // namespace

TEST(SdsmGl, CascadesHoldTheirPixelsTightly) {
  for (const char* name : {"city", "boxes", "fence"}) {
    const Scene scene = makeBuiltinScene(name);
    const RenderResult r = renderScene(scene, "sdsm", "hard", {}, kWidth, kHeight, kMapSize);
    const LightFrusta& f = r.frusta;
    ASSERT_EQ(f.views.size(), 4u) << name;
    EXPECT_GT(r.timings.get("projection"), 0.0) << name << ": the reduction pass ran";
    const glm::mat4 view = scene.camera.viewFromWorld();
    const glm::vec3 toLight = -glm::normalize(scene.light().direction);
    for (size_t v = 0; v < f.views.size(); ++v) {
      const float a = v == 0 ? 0.0f : f.views[v - 1].splitFarM - f.blendBandM;
      const float b = v + 1 == f.views.size() ? std::numeric_limits<float>::max() : f.views[v].splitFarM;
      glm::vec2 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
      size_t pixels = 0, outside = 0;
      for (size_t i = 0; i < r.gbuffer.position.size(); ++i) {
        if (!r.gbuffer.covered(i) || glm::dot(glm::vec3(r.gbuffer.geoNormal[i]), toLight) <= 0.0f) continue;
        const glm::vec3 p(r.gbuffer.position[i]);
        const float depth = -(view * glm::vec4(p, 1.0f)).z;
        if (depth < a || depth > b) continue;
        ++pixels;
        const glm::vec4 c = f.views[v].clipFromWorld * glm::vec4(p, 1.0f);
        const glm::vec2 ndc = glm::vec2(c) / c.w;
        lo = glm::min(lo, ndc);
        hi = glm::max(hi, ndc);
        outside += glm::any(glm::greaterThan(glm::abs(ndc), glm::vec2(1.0f)));
      }
      std::printf("%-6s cascade %zu (to %.1f m): %6zu pixels span %.3f x %.3f of the map's 2 x 2\n", name, v, f.views[v].splitFarM,
                  pixels, hi.x - lo.x, hi.y - lo.y);
      EXPECT_EQ(outside, 0u) << name << " cascade " << v;
      if (pixels < kMinPixels) continue;
      EXPECT_GT(hi.x - lo.x, kMinSpanNdc) << name << " cascade " << v;
      EXPECT_GT(hi.y - lo.y, kMinSpanNdc) << name << " cascade " << v;
    }
  }
  const RenderResult csm = renderScene(makeBuiltinScene("boxes"), "csm", "hard", {}, kWidth, kHeight, kMapSize);
  EXPECT_EQ(csm.timings.get("projection"), 0.0) << "csm measures no pixels";
}
