// The default bias model (docs/hard.md#the-default-bias-model): every comparison is made with the
// receiver's own plane at the centre of the texel it reads, moved back along the receiver's
// normal by a count of texels of world size (pcf and pcss: past their kernel's radius). With the
// defaults, on every built-in scene, every projection that takes its lights and each filter that
// compares depths, acne (the reference's fully lit pixels that V darkens by more than 0.1,
// acne_pct) stays within 0.1 %, and on the scenes made to show detached shadows (boxes, pen,
// grazing) so do umbra leaks (umbra_leak_pct) — measured as compare measures them
// (report::compareFrame: every light, at the pixel's footprint). city under one map, where the
// map's texel decides, is left to the docs (texelDecides). Without the margin the same measure
// sees the acne, and a shadow pushed off its caster leaks.
#include "GlFixture.h"

#include "comparison/FrameComparison.h"

#include <penumbra/Error.h>
#include <penumbra/Metrics.h>
#include <penumbra/Reference.h>
#include <penumbra/Technique.h>

#include <algorithm>
#include <cstdio>
#include <string>
#include <string_view>

using namespace penumbra;
using namespace penumbra::test;

namespace {

constexpr int kWidth = 256, kHeight = 144;  // small: one reference per scene
constexpr int kReferenceSamples = 32;
constexpr double kMaxAcnePct = 0.1;   // the bound `tune --objective acne` holds
constexpr double kMaxUmbraLeakPct = 0.1;
constexpr double kMaxNightPcfAcnePct = 0.025;  // the crease: 0.047 % without pcf's crease margin

RenderOptions smallFrame() {
  RenderOptions o;
  o.width = kWidth;
  o.height = kHeight;
  return o;
}

// One scene's references (every light), traced once on the G-buffer every technique shares.
struct SceneTruth {
  Scene scene;
  GBufferData gbuffer;
  std::vector<ReferenceResult> refs;
};

SceneTruth trace(const std::string& name) {
  SceneTruth t{makeBuiltinScene(name), {}, {}};
  const auto renderer = makeTestRenderer(t.scene, "uniform", "hard", {}, t.scene.shadow.mapSize);
  renderer->render(smallFrame());
  t.gbuffer = renderer->readGBuffer();
  ReferenceOptions o;
  o.samples = kReferenceSamples;
  o.progress = false;
  o.useCache = false;
  t.refs = report::traceLights(ReferenceTracer(renderer->scene()), t.gbuffer, renderer->scene().lights, o);
  return t;
}

VisibilityMetrics measure(const SceneTruth& t, const std::string& projection, const std::string& filter, const Params& params,
                          int mapSize) {
  const auto renderer = makeTestRenderer(t.scene, projection, filter, params, mapSize);
  renderer->render(smallFrame());
  return report::compareFrame(*renderer, t.gbuffer, t.refs, false).metrics;
}

bool refusesALight(const Scene& scene, const std::string& projection) {
  return std::any_of(scene.lights.begin(), scene.lights.end(),
                     [&](const Light& l) { return !projectionIncompatibility(projection, l).empty(); });
}

// city's one map spans the whole 640 m city (most pixels see a texel several pixels wide) and a
// warped map's far texels are metres wide: there pcf's and pcss's kernels, counted in texels,
// blur the sun's edge over several pixels whatever the bias. Those rows are measured at 640x360
// on 1x and 4x maps in docs/hard.md#the-default-bias-model (a 4x city map takes ~20 s a render
// here, beyond this suite's budget); the cascades (csm, sdsm) and the pages (virtual) hold the
// bound at the scene's size.
bool texelDecides(const std::string& scene, const std::string& projection) {
  return scene == "city" && projection != "csm" && projection != "sdsm" && projection != "virtual";
}

}  // namespace

TEST(BiasModel, DefaultsLeaveNoAcneAndNoDetachedShadow) {
  for (const std::string& name : builtinSceneNames()) {
    const SceneTruth truth = trace(name);
    const bool leakBound = name == "boxes" || name == "pen" || name == "grazing";
    for (const std::string& projection : projectionIds()) {
      if (refusesALight(truth.scene, projection)) {
        // A point light's six faces are uniform's and virtual's alone: the other projections
        // refuse the scene.
        EXPECT_THROW(measure(truth, projection, "hard", {}, truth.scene.shadow.mapSize), Error) << name << " " << projection;
        continue;
      }
      if (texelDecides(name, projection)) continue;
      for (const char* filter : {"hard", "pcf", "pcss"}) {
        const VisibilityMetrics m = measure(truth, projection, filter, {}, truth.scene.shadow.mapSize);
        std::printf("%-8s %-7s %-5s: acne %.3f %%  umbra leak %.3f %%\n", name.c_str(), projection.c_str(), filter, m.acnePct,
                    m.umbraLeakPct);
        EXPECT_LE(m.acnePct, kMaxAcnePct) << name << " " << projection << " " << filter;
        // pcf's crease margin (common/depth_compare.glsl): the foot of night's kerbs under its
        // lamps, lit walls on a lit street, read 0.047 % without it and 0.018 % with it.
        if (name == "night" && std::string_view(filter) == "pcf") {
          EXPECT_LE(m.acnePct, kMaxNightPcfAcnePct);
        }
        if (leakBound) {
          EXPECT_LE(m.umbraLeakPct, kMaxUmbraLeakPct) << name << " " << projection << " " << filter;
        }
      }
    }
  }
}

// Without a bias the receiver's plane meets its own map at float precision: the same measure then
// reads acne on most lit pixels, so the bounds above do measure the bias.
TEST(BiasModel, WithoutABiasTheMeasureSeesAcne) {
  const SceneTruth truth = trace("boxes");
  for (const char* projection : {"uniform", "lispsm", "sdsm"}) {
    const VisibilityMetrics none = measure(truth, projection, "hard", {{"hard.bias", "none"}}, truth.scene.shadow.mapSize);
    std::printf("boxes, %s, hard.bias=none: acne %.2f %%\n", projection, none.acnePct);
    EXPECT_GT(none.acnePct, 10.0 * kMaxAcnePct) << projection;
  }
}

// A shadow pushed away from its caster is seen too: grazing's box with a constant bias large
// enough for its 10-degree sun everywhere (docs/hard.md's peter-panning picture) leaks light into
// the reference's umbra at the box's foot, well beyond the bound above.
TEST(BiasModel, ADetachedShadowIsSeen) {
  const SceneTruth truth = trace("grazing");
  const VisibilityMetrics detached =
      measure(truth, "uniform", "hard", {{"hard.bias", "constant"}, {"hard.constantBias", "0.05"}}, truth.scene.shadow.mapSize);
  std::printf("grazing, hard.bias=constant 0.05: umbra leak %.3f %%\n", detached.umbraLeakPct);
  EXPECT_GT(detached.umbraLeakPct, kMaxUmbraLeakPct);
}
