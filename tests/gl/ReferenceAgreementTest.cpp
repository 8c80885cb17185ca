// The renderer and the Embree reference agree on the pixels they share: hard shadows on `boxes`
// with a point-size sun match the single-ray truth.
#include "GlFixture.h"

#include <penumbra/Metrics.h>
#include <penumbra/Reference.h>

using namespace penumbra;
using namespace penumbra::test;

TEST(ReferenceAgreement, HardSlopeOnBoxesWithinRmse005) {
  Scene scene = makeBuiltinScene("boxes");
  const RenderResult r = renderScene(scene, "uniform", "hard", {{"light.size", "0"}, {"hard.bias", "slope"}}, 256, 256, 2048);
  scene.lights.front().size = 0.0f;
  ReferenceOptions o;
  o.useCache = false;
  o.progress = false;
  const ReferenceResult ref = ReferenceTracer(scene).trace(r.gbuffer, scene.light(), o);
  const VisibilityMetrics m = compareVisibility(r.visibility, ref.visibility, ref.litMask);
  std::printf("boxes hard/slope vs reference: RMSE %.4f, leak %.3f%%, over-dark %.3f%% over %zu pixels\n", m.rmse,
              m.leakPct, m.overDarkPct, m.pixels);
  EXPECT_GT(m.pixels, 20000u);
  EXPECT_LE(m.rmse, 0.05);
}
