// Contact shadows (docs/contact.md): what they restore where a shadow map's bias detaches a
// shadow from its caster, and what they darken that the reference keeps lit.
#include "GlFixture.h"
#include "TestGeometry.h"

#include <penumbra/Metrics.h>
#include <penumbra/Reference.h>

#include <cstdio>

using namespace penumbra;
using namespace penumbra::test;

namespace {

constexpr int kMapSize = 2048;
constexpr int kReferenceSamples = 64;

ReferenceResult trace(const Scene& scene, const GBufferData& g) {
  ReferenceOptions o;
  o.samples = kReferenceSamples;
  o.progress = false;
  return ReferenceTracer(scene).trace(g, scene.light(), o);
}

Params with(Params p, const Params& more) {
  p.insert(p.end(), more.begin(), more.end());
  return p;
}

const Params kContactOn = {{"contact.shadows", "on"}};

// Pixels the contact pass darkened (V lowered by more than kLeakThresholdV) where the reference
// is lit (V_ref > 1 − kLeakThresholdV): its own false shadows, in % of the lit pixels.
double falseShadowPct(const RenderResult& off, const RenderResult& on, const ReferenceResult& ref) {
  size_t lit = 0, wrong = 0;
  for (size_t i = 0; i < ref.litMask.size(); ++i) {
    if (!ref.litMask[i]) continue;
    ++lit;
    if (ref.visibility[i] > 1.0f - kLeakThresholdV && off.visibility[i] - on.visibility[i] > kLeakThresholdV) ++wrong;
  }
  return lit ? 100.0 * static_cast<double>(wrong) / static_cast<double>(lit) : 0.0;
}

}  // namespace

// grazing, looking at the box's shadow, with a constant bias large enough to detach it: pcf's
// shadow starts several texels behind the box; the march toward the sun finds the box in the
// depth buffer and brings the shadow back to its foot.
TEST(ContactShadows, RestoreTheContactThatABiasDetached) {
  Scene scene = makeBuiltinScene("grazing");
  scene.camera.position = {2.6f, 1.6f, 2.2f};
  scene.camera.target = {0.9f, 0.0f, 0.0f};
  const Params detached = {{"pcf.constantBias", "0.02"}};
  const RenderResult off = renderScene(scene, "uniform", "pcf", detached, 256, 256, kMapSize);
  // The bias lifts receivers ~0.3 m along the sun's low ray: the march must reach that far.
  const RenderResult on = renderScene(scene, "uniform", "pcf", with(detached, with(kContactOn, {{"contact.distanceM", "0.4"}})),
                                      256, 256, kMapSize);
  const double gapOff = contactGapTexels(scene, off, kMapSize), gapOn = contactGapTexels(scene, on, kMapSize);
  const ReferenceResult ref = trace(scene, off.gbuffer);
  const VisibilityMetrics mOff = compareVisibility(off.visibility, ref.visibility, ref.litMask);
  const VisibilityMetrics mOn = compareVisibility(on.visibility, ref.visibility, ref.litMask);
  std::printf("grazing pcf constantBias 0.02: gap %.2f -> %.2f texels, RMSE %.4f -> %.4f, false shadows %.3f %%\n", gapOff,
              gapOn, mOff.rmse, mOn.rmse, falseShadowPct(off, on, ref));
  EXPECT_GT(gapOff, 4.0) << "the bias must detach the shadow for the test to mean anything";
  EXPECT_LE(gapOn, 2.0);
  EXPECT_LT(mOn.rmse, mOff.rmse);
}

// pen: the pencil's tip touches the floor; around it the filter's bias and texels lose the
// contact. In a band of the floor within 5 cm of a caster the error drops.
TEST(ContactShadows, PenTipBandErrorDrops) {
  const Scene scene = makeBuiltinScene("pen");
  const RenderResult off = renderScene(scene, "uniform", "pcss", {}, 640, 360, 1024);
  const RenderResult on = renderScene(scene, "uniform", "pcss", kContactOn, 640, 360, 1024);
  const ReferenceResult ref = trace(scene, off.gbuffer);
  constexpr float kBandM = 0.05f;
  const std::vector<uint8_t> band = floorNearCasters(scene, off.gbuffer, ref.litMask, kBandM);
  const VisibilityMetrics bOff = compareVisibility(off.visibility, ref.visibility, band);
  const VisibilityMetrics bOn = compareVisibility(on.visibility, ref.visibility, band);
  const VisibilityMetrics all = compareVisibility(on.visibility, ref.visibility, ref.litMask);
  const VisibilityMetrics allOff = compareVisibility(off.visibility, ref.visibility, ref.litMask);
  std::printf("pen pcss, %zu band pixels within %.0f cm of a caster: RMSE %.4f -> %.4f; whole frame %.4f -> %.4f; "
              "false shadows %.3f %%\n", bOn.pixels, kBandM * 100.0f, bOff.rmse, bOn.rmse, allOff.rmse, all.rmse,
              falseShadowPct(off, on, ref));
  ASSERT_GT(bOn.pixels, 50u);
  EXPECT_LT(bOn.rmse, bOff.rmse);
}

// The pass's own errors: thin depth (everything seen is assumed contact.thicknessM thick) and
// casters the camera does not see. Measured on every built-in scene's own camera with pcf.
TEST(ContactShadows, FalseShadowsStayRare) {
  constexpr double kMaxFalsePct = 0.25;  // measured at most 0.055 % (boxes)
  for (const char* name : {"boxes", "pen", "fence", "grazing", "city"}) {
    const Scene scene = makeBuiltinScene(name);
    const std::string projection = std::string(name) == "city" ? "csm" : "uniform";
    const RenderResult off = renderScene(scene, projection, "pcf", {}, 256, 144, 1024);
    const RenderResult on = renderScene(scene, projection, "pcf", kContactOn, 256, 144, 1024);
    const ReferenceResult ref = trace(scene, off.gbuffer);
    const double pct = falseShadowPct(off, on, ref);
    const double rmseOff = compareVisibility(off.visibility, ref.visibility, ref.litMask).rmse;
    const double rmseOn = compareVisibility(on.visibility, ref.visibility, ref.litMask).rmse;
    std::printf("%-8s pcf + contact: false shadows %.3f %% of lit pixels, RMSE %.4f -> %.4f\n", name, pct, rmseOff, rmseOn);
    EXPECT_LE(pct, kMaxFalsePct) << name;
  }
}
