// The foundation's known answers: cast shadows where geometry says, acne without bias on a
// grazing plane and none with slope-scaled bias, and shadows still touching their casters.
#include "GlFixture.h"
#include "TestGeometry.h"

#include <random>

using namespace penumbra;
using namespace penumbra::test;

namespace {

constexpr int kSize = 256;
// Floor pixels robustly in or out of the hard shadow: count/2 of each kind.
FloorProbes hardProbes(const Scene& scene, const GBufferData& g, int count, float jitterM) {
  return floorProbes(scene, g, static_cast<size_t>(count) / 2, jitterM, 7, count * 40);
}

}  // namespace

TEST(HardShadow, BoxesProbePixels) {
  const Scene scene = makeBuiltinScene("boxes");
  const RenderResult r = renderScene(scene, "uniform", "hard", {{"light.size", "0"}, {"hard.bias", "slope"}}, kSize, kSize, 2048);
  const FloorProbes probes = hardProbes(scene, r.gbuffer, 400, 0.04f);
  ASSERT_GT(probes.shadowed.size(), 20u);
  ASSERT_GT(probes.lit.size(), 20u);
  for (size_t i : probes.shadowed) EXPECT_LT(r.visibility[i], 0.05f) << "pixel " << i << " should be shadowed";
  for (size_t i : probes.lit) EXPECT_GT(r.visibility[i], 0.95f) << "pixel " << i << " should be lit";
}

TEST(HardShadow, GrazingAcneWithoutBiasAndNoneWithSlopeBias) {
  const Scene scene = makeBuiltinScene("grazing");
  const RenderResult none = renderScene(scene, "uniform", "hard", {{"hard.bias", "none"}}, kSize, kSize, 2048);
  const RenderResult slope = renderScene(scene, "uniform", "hard", {{"hard.bias", "slope"}}, kSize, kSize, 2048);
  const double acneNone = acneFraction(scene, none), acneSlope = acneFraction(scene, slope);
  RecordProperty("acne_none_pct", std::to_string(100.0 * acneNone));
  RecordProperty("acne_slope_pct", std::to_string(100.0 * acneSlope));
  std::printf("grazing acne: bias=none %.2f%%, bias=slope %.3f%%\n", 100.0 * acneNone, 100.0 * acneSlope);
  EXPECT_GE(acneNone, 0.20);
  EXPECT_LE(acneSlope, 0.005);
}

// Peter-panning, as TestGeometry's contactGapTexels measures it, for the hard filter.
double contactGapTexels(const Scene& scene, const std::vector<std::pair<std::string, std::string>>& params) {
  return contactGapTexels(scene, renderScene(scene, "uniform", "hard", params, kSize, kSize, 2048), 2048);
}

TEST(HardShadow, SlopeBiasShadowStillTouchesTheBox) {
  Scene scene = makeBuiltinScene("grazing");
  // Look at the box's shadow, which the sun casts toward +x.
  scene.camera.position = {2.6f, 1.6f, 2.2f};
  scene.camera.target = {0.9f, 0.0f, 0.0f};
  const double slopeGap = contactGapTexels(scene, {{"hard.bias", "slope"}});
  // The same measure sees peter-panning when the bias exceeds the box (~1.1 m of depth).
  const double largeGap = contactGapTexels(scene, {{"hard.bias", "constant"}, {"hard.constantBias", "0.04"}});
  std::printf("contact gap: slope bias %.2f texels, large constant bias %.2f texels\n", slopeGap, largeGap);
  EXPECT_LE(slopeGap, 2.0);
  EXPECT_GT(largeGap, 4.0);
}

TEST(HardShadow, UnbiasedMapAgreesOnSpotLights) {
  // A spot-lit scene: probes on the floor under the pencil are in shadow, far ones lit.
  Scene scene = makeBuiltinScene("pen");
  const RenderResult r = renderScene(scene, "uniform", "hard", {{"light.size", "0"}}, kSize, kSize, 1024);
  const FloorProbes probes = hardProbes(scene, r.gbuffer, 200, 0.01f);
  ASSERT_GT(probes.shadowed.size(), 5u);
  ASSERT_GT(probes.lit.size(), 20u);
  size_t wrong = 0;
  for (size_t i : probes.shadowed) wrong += r.visibility[i] > 0.05f;
  for (size_t i : probes.lit) wrong += r.visibility[i] < 0.95f;
  EXPECT_EQ(wrong, 0u);
}

// Normal-offset bias (hard.bias=normal): the receiver moves along its normal before the lookup,
// so the grazing plane loses its acne like with slope bias and the box's shadow still touches it.
TEST(HardShadow, NormalOffsetBiasRemovesAcneAndKeepsContact) {
  const Scene scene = makeBuiltinScene("grazing");
  const RenderResult normal = renderScene(scene, "uniform", "hard", {{"hard.bias", "normal"}}, kSize, kSize, 2048);
  const double acneNormal = acneFraction(scene, normal);
  Scene contact = scene;
  contact.camera.position = {2.6f, 1.6f, 2.2f};
  contact.camera.target = {0.9f, 0.0f, 0.0f};
  const double gapNormal = contactGapTexels(contact, {{"hard.bias", "normal"}});
  RecordProperty("acne_normal_pct", std::to_string(100.0 * acneNormal));
  RecordProperty("contact_gap_normal_texels", std::to_string(gapNormal));
  std::printf("grazing, bias=normal: acne %.3f%%, contact gap %.2f texels\n", 100.0 * acneNormal, gapNormal);
  EXPECT_LE(acneNormal, 0.005);
  EXPECT_LE(gapNormal, 2.0);
}
