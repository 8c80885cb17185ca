// `penumbra tune --objective acne` without GL: the acne metric (over-darkening where the reference
// is fully lit), the objective that accepts at most 0.1 % of it and then prefers the least umbra
// leak, and the bias parameters it searches.
#include "tuner/TuneRunner.h"

#include <penumbra/Error.h>
#include <penumbra/Metrics.h>
#include "techniques/Registry.h"

#include <gtest/gtest.h>

#include <vector>

using namespace penumbra;
using namespace penumbra::report;

TEST(TuneAcne, AcneCountsOverDarkeningOnlyWhereTheReferenceIsFullyLit) {
  // 4 fully lit pixels (one darkened: acne), 2 in the penumbra (one darkened: not acne), 2 in the umbra.
  const std::vector<float> vRef = {1.0f, 1.0f, 1.0f, 0.99f, 0.5f, 0.5f, 0.0f, 0.0f};
  const std::vector<float> v = {1.0f, 0.0f, 0.95f, 0.99f, 0.5f, 0.2f, 0.0f, 0.0f};
  const VisibilityMetrics m = compareVisibility(v, vRef, {});
  EXPECT_EQ(m.fullyLitPixels, 4u);
  EXPECT_EQ(m.acnePixels, 1u);
  EXPECT_NEAR(m.acnePct, 25.0, 1e-9);
  EXPECT_EQ(m.overDarkPixels, 2u);  // over-darkening counts the penumbra's too
}

TEST(TuneAcne, ObjectiveRejectsAcneThenPrefersTheLeastUmbraLeak) {
  VisibilityMetrics clean, acne;
  clean.acnePct = kMaxAcnePct;  // at the bar: accepted
  clean.umbraLeakPct = 0.5;
  acne.acnePct = 2.0 * kMaxAcnePct;
  acne.umbraLeakPct = 0.0;
  EXPECT_EQ(objectiveValue(TuneObjective::Acne, clean), 0.5);
  EXPECT_GE(objectiveValue(TuneObjective::Acne, acne), kAcneRejectedError);
  EXPECT_EQ(parseObjective("acne"), TuneObjective::Acne);
  EXPECT_THROW(parseObjective("speed"), Error);
}

TEST(TuneAcne, BiasKeysAndBiasSize) {
  for (const char* key : {"hard.bias", "hard.constantBias", "hard.slopeBias", "hard.normalOffsetTexels", "pcf.constantBias"})
    EXPECT_TRUE(isBiasKey(key)) << key;
  for (const char* key : {"pcf.radiusTexels", "pcf.kernel", "csm.lambda", "uniform.marginTexels"})
    EXPECT_FALSE(isBiasKey(key)) << key;

  const Parameterized f(filterParams("hard"));
  std::vector<float> current;
  for (const ParamDesc& d : f.paramDescs()) current.push_back(f.param(d.key));
  const std::vector<TuneDim> space = tuneSpace(f.paramDescs(), current, TuneMapDefault{});
  TuneCandidate lo = defaultCandidate(space), hi = lo;
  for (size_t d = 0; d < space.size(); ++d) {
    lo[d] = space[d].lo;
    hi[d] = space[d].hi;
  }
  EXPECT_NEAR(tuneBiasSize(space, lo), 0.0, 1e-9);
  EXPECT_GT(tuneBiasSize(space, hi), tuneBiasSize(space, defaultCandidate(space)));
  // Far below one pixel's share of a 640x360 image: it only breaks ties.
  constexpr double kOnePixelPct = 100.0 / (640.0 * 360.0);
  EXPECT_LT(kBiasTieWeight * tuneBiasSize(space, hi), kOnePixelPct / 10.0);
}
