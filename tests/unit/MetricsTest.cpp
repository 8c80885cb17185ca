// Metrics on small synthetic images whose answers are worked out by hand.
#include <penumbra/Error.h>
#include <penumbra/Metrics.h>

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace penumbra {
namespace {

// Six pixels, every case once. Deltas V − V_ref: +0.3 leak, −0.4 over-dark, +0.05 and −0.08
// (below the threshold either way), 0, +0.5 (masked out).
const std::vector<float> kRef = {0.0f, 1.0f, 0.5f, 0.6f, 1.0f, 0.0f};
const std::vector<float> kV = {0.3f, 0.6f, 0.55f, 0.52f, 1.0f, 0.5f};
const std::vector<uint8_t> kMask = {1, 1, 1, 1, 1, 0};

TEST(Metrics, KnownAnswersIncludingLeakAndOverDarkSplit) {
  const VisibilityMetrics m = compareVisibility(kV, kRef, kMask);
  EXPECT_EQ(m.pixels, 5u);
  const double squares = 0.09 + 0.16 + 0.0025 + 0.0064 + 0.0;
  EXPECT_NEAR(m.rmse, std::sqrt(squares / 5.0), 1e-6);
  EXPECT_NEAR(m.mae, (0.3 + 0.4 + 0.05 + 0.08) / 5.0, 1e-6);
  EXPECT_NEAR(m.bias, (0.3 - 0.4 + 0.05 - 0.08) / 5.0, 1e-6);
  EXPECT_EQ(m.leakPixels, 1u);
  EXPECT_EQ(m.overDarkPixels, 1u);
  EXPECT_NEAR(m.leakPct, 20.0, 1e-9);
  EXPECT_NEAR(m.overDarkPct, 20.0, 1e-9);
  // The one leak is at V_ref = 0: inside the umbra.
  EXPECT_EQ(m.umbraLeakPixels, 1u);
  EXPECT_NEAR(m.umbraLeakPct, 20.0, 1e-9);
  // Penumbra: V_ref 0.5 and 0.6 only (0 and 1 are outside (0.02, 0.98)).
  EXPECT_EQ(m.penumbraPixels, 2u);
  EXPECT_NEAR(m.penumbraRmse, std::sqrt((0.0025 + 0.0064) / 2.0), 1e-6);
}

TEST(Metrics, EmptyMaskMeansEveryPixelAndAllZeroMaskMeansNone) {
  const VisibilityMetrics all = compareVisibility(kV, kRef, {});
  EXPECT_EQ(all.pixels, 6u);
  EXPECT_EQ(all.leakPixels, 2u);  // the +0.5 pixel now counts
  const VisibilityMetrics none = compareVisibility(kV, kRef, std::vector<uint8_t>(6, 0));
  EXPECT_EQ(none.pixels, 0u);
  EXPECT_EQ(none.rmse, 0.0);  // zeros, not NaN
  EXPECT_EQ(none.leakPct, 0.0);
}

TEST(Metrics, UmbraLeaksAreLeaksWhereTheReferenceIsAtMostPenumbraLow) {
  // Leaks (ΔV = +0.3) at V_ref 0, 0.02 (umbra, bound included), 0.03 and 0.5 (penumbra).
  const std::vector<float> ref = {0.0f, 0.02f, 0.03f, 0.5f};
  const std::vector<float> v = {0.3f, 0.32f, 0.33f, 0.8f};
  const VisibilityMetrics m = compareVisibility(v, ref, {});
  EXPECT_EQ(m.leakPixels, 4u);
  EXPECT_EQ(m.umbraLeakPixels, 2u);
  EXPECT_NEAR(m.umbraLeakPct, 50.0, 1e-9);
}

// A 6×4 image: a point light's hard edge between columns 2 and 3 (lit left, umbra right), one
// masked-out umbra pixel at (0, 0). A filter softens the edge: columns 2 and 3 get V 0.6 and 0.4.
// Those pixels straddle the edge (V_ref 1 or 0 at their centres only), so with the image's width
// they are neither fully lit nor umbra; acne at (0, 3) and a leak at (5, 3), away from the
// edge, still count, and so does the lit pixel beside the masked one.
TEST(Metrics, AcneAndUmbraAreJudgedAtThePixelsFootprint) {
  constexpr int kW = 6, kH = 4;
  std::vector<float> ref(kW * kH), v(kW * kH);
  std::vector<uint8_t> mask(kW * kH, 1);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const size_t i = static_cast<size_t>(y * kW + x);
      ref[i] = x < 3 ? 1.0f : 0.0f;
      v[i] = x == 2 ? 0.6f : x == 3 ? 0.4f : ref[i];
    }
  mask[0] = 0;
  ref[0] = 0.0f;
  v[1] = 0.5f;            // acne beside the masked pixel: its neighbour does not count
  v[3 * kW + 0] = 0.7f;   // acne two pixels from the edge
  v[3 * kW + 5] = 0.25f;  // a leak two pixels inside the umbra
  const VisibilityMetrics footprint = compareVisibility(v, ref, mask, kW);
  EXPECT_EQ(footprint.fullyLitPixels, 7u);  // columns 0 and 1 less the masked pixel
  EXPECT_EQ(footprint.acnePixels, 2u);
  EXPECT_EQ(footprint.umbraLeakPixels, 1u);  // columns 4 and 5: 8 umbra pixels, one leaks
  EXPECT_EQ(footprint.overDarkPixels, 6u);   // the edge's 4 lit pixels still over-dark, and 2 acne
  EXPECT_EQ(footprint.leakPixels, 5u);
  // As samples (no width) every pixel is its own footprint: the edge's pixels count as acne and leaks.
  const VisibilityMetrics samples = compareVisibility(v, ref, mask);
  EXPECT_EQ(samples.fullyLitPixels, 11u);
  EXPECT_EQ(samples.acnePixels, 6u);
  EXPECT_EQ(samples.umbraLeakPixels, 5u);
  EXPECT_THROW(compareVisibility(v, ref, mask, 5), Error);  // 24 pixels are not rows of 5
}

TEST(Metrics, PenumbraBoundsAreStrict) {
  const std::vector<float> ref = {0.02f, 0.98f, 0.03f};
  const std::vector<float> v = {0.52f, 0.48f, 0.33f};
  const VisibilityMetrics m = compareVisibility(v, ref, {});
  EXPECT_EQ(m.penumbraPixels, 1u);
  EXPECT_NEAR(m.penumbraRmse, 0.3, 1e-6);
  EXPECT_NEAR(m.rmse, std::sqrt((0.25 + 0.25 + 0.09) / 3.0), 1e-6);
}

TEST(Metrics, SizeMismatchThrows) {
  EXPECT_THROW(compareVisibility(kV, std::vector<float>(5), {}), Error);
  EXPECT_THROW(compareVisibility(kV, kRef, std::vector<uint8_t>(3, 1)), Error);
  EXPECT_THROW(errorHeatmap(kV, kRef, kMask, 4, 2), Error);
}

const uint8_t* pixelAt(const ColorImage& image, int x, int yTop) {
  return &image.rgba[4 * (static_cast<size_t>(yTop) * static_cast<size_t>(image.width) + static_cast<size_t>(x))];
}

TEST(Metrics, HeatmapTintsLeaksAndOverDarkeningOnGrey) {
  // 3×2, G-buffer order (row 0 = bottom). Bottom row: leak 0.5, over-dark 0.5, leak 0.1.
  // Top row: exact, over-dark 0.5 but masked out, exact.
  const std::vector<float> ref = {0.0f, 1.0f, 0.5f, 0.5f, 1.0f, 0.5f};
  const std::vector<float> v = {0.5f, 0.5f, 0.6f, 0.5f, 0.5f, 0.5f};
  const std::vector<uint8_t> mask = {1, 1, 1, 1, 0, 1};
  const ColorImage h = errorHeatmap(v, ref, mask, 3, 2);
  ASSERT_EQ(h.rgba.size(), 24u);
  // Bottom row lands in the image's last row. Full scale 0.5: fully tinted.
  EXPECT_EQ(pixelAt(h, 0, 1)[0], kLeakColor[0]);
  EXPECT_EQ(pixelAt(h, 0, 1)[2], kLeakColor[2]);
  EXPECT_EQ(pixelAt(h, 1, 1)[2], kOverDarkColor[2]);
  EXPECT_EQ(pixelAt(h, 1, 1)[0], kOverDarkColor[0]);
  // A small leak is a weaker tint: red above the grey, but less red than the full leak.
  const uint8_t* small = pixelAt(h, 2, 1);
  EXPECT_GT(small[0], small[1]);
  EXPECT_LT(small[0] - small[1], pixelAt(h, 0, 1)[0] - pixelAt(h, 0, 1)[1]);
  // No error, and masked-out error: pure grey (from V_ref: 0.5 → 40 + 0.6·127.5, 1 → 40 + 153).
  for (int x = 0; x < 3; ++x) {
    const uint8_t* p = pixelAt(h, x, 0);
    EXPECT_EQ(p[0], p[1]);
    EXPECT_EQ(p[1], p[2]);
    EXPECT_EQ(p[3], 255);
  }
  EXPECT_EQ(pixelAt(h, 1, 0)[0], 193);
  EXPECT_EQ(pixelAt(h, 0, 0)[0], 117);
}

TEST(Metrics, DilatedHeatmapSpreadsTheLargestErrorWithItsSign) {
  // 5×1: one leak of 0.4 at x = 1, an over-dark of 0.2 at x = 4, a masked-out error at x = 3.
  const std::vector<float> ref = {0.5f, 0.5f, 0.5f, 0.5f, 0.5f};
  const std::vector<float> v = {0.5f, 0.9f, 0.5f, 0.0f, 0.3f};
  const std::vector<uint8_t> mask = {1, 1, 1, 0, 1};
  const ColorImage plain = errorHeatmap(v, ref, mask, 5, 1);
  const ColorImage h = errorHeatmap(v, ref, mask, 5, 1, nullptr, HeatmapOptions{.fullScaleDeltaV = 0.5f, .dilatePx = 1});
  auto reddish = [](const uint8_t* p) { return p[0] > p[2]; };
  auto bluish = [](const uint8_t* p) { return p[2] > p[0]; };
  EXPECT_FALSE(reddish(pixelAt(plain, 0, 0))) << "without dilation only the leaking pixel is red";
  for (const int x : {0, 1, 2}) EXPECT_TRUE(reddish(pixelAt(h, x, 0))) << x << ": within 1 px of the leak";
  EXPECT_EQ(pixelAt(h, 0, 0)[0], pixelAt(h, 1, 0)[0]) << "the neighbour shows the leak's own strength";
  // x = 3 is masked out: it shows its neighbour's over-darkening, not its own larger error.
  EXPECT_TRUE(bluish(pixelAt(h, 3, 0)));
  EXPECT_EQ(pixelAt(h, 3, 0)[2], pixelAt(h, 4, 0)[2]);
  EXPECT_THROW(errorHeatmap(v, ref, mask, 5, 1, nullptr, HeatmapOptions{.fullScaleDeltaV = 0.5f, .dilatePx = -1}), Error);
}

TEST(Metrics, HeatmapUsesTheBaseImageForItsGrey) {
  const std::vector<float> same = {0.5f, 0.5f};
  ColorImage base{2, 1, {0, 0, 0, 255, 255, 255, 255, 255}};
  const ColorImage h = errorHeatmap(same, same, {}, 2, 1, &base);
  EXPECT_EQ(pixelAt(h, 0, 0)[0], 40);   // black → the grey floor
  EXPECT_EQ(pixelAt(h, 1, 0)[0], 193);  // white → floor + contrast
  ColorImage wrong{1, 1, {0, 0, 0, 255}};
  EXPECT_THROW(errorHeatmap(same, same, {}, 2, 1, &wrong), Error);
}

TEST(Metrics, VisibilityImageIsLinearGreyFlippedToTopDown) {
  const ColorImage image = visibilityImage(std::vector<float>{0.0f, 1.0f, 0.5f, 2.0f}, 2, 2);
  EXPECT_EQ(pixelAt(image, 0, 1)[0], 0);    // bottom-left in, bottom-left out (last row)
  EXPECT_EQ(pixelAt(image, 1, 1)[1], 255);
  EXPECT_EQ(pixelAt(image, 0, 0)[2], 128);  // 0.5 → 127.5 rounds up
  EXPECT_EQ(pixelAt(image, 1, 0)[0], 255);  // clamped
  EXPECT_EQ(pixelAt(image, 1, 0)[3], 255);
}

}  // namespace
}  // namespace penumbra

// Colour V_ref (translucent casters): a black shadow under a tinted glass misses each channel of
// the glass's light, and the image shows the missing light per channel around mid grey.
namespace penumbra {

TEST(Metrics, ColourErrorPerChannelAndAsAnImage) {
  const std::vector<glm::vec3> v = {glm::vec3(0.0f), glm::vec3(1.0f), glm::vec3(0.0f)};
  const std::vector<glm::vec3> ref = {{0.85f, 0.45f, 0.3f}, glm::vec3(1.0f), glm::vec3(1.0f)};
  const std::vector<uint8_t> mask = {1, 1, 0};  // the third pixel's error is not measured
  const ColourMetrics m = compareColourVisibility(v, ref, mask);
  EXPECT_EQ(m.pixels, 2u);
  EXPECT_NEAR(m.channelRmse[0], 0.85 / std::sqrt(2.0), 1e-6);
  EXPECT_NEAR(m.channelRmse[1], 0.45 / std::sqrt(2.0), 1e-6);
  EXPECT_NEAR(m.channelRmse[2], 0.3 / std::sqrt(2.0), 1e-6);
  EXPECT_NEAR(m.rmse, std::sqrt((0.85 * 0.85 + 0.45 * 0.45 + 0.3 * 0.3) / 6.0), 1e-6);
  EXPECT_THROW(compareColourVisibility(v, std::vector<glm::vec3>(2), mask), Error);

  const std::vector<glm::vec3> halfRed = {{0.5f, 0.25f, 0.0f}, glm::vec3(1.0f), glm::vec3(1.0f)};
  const ColorImage image = colourErrorImage(v, halfRed, mask, 3, 1, 0.5f);
  EXPECT_EQ(std::vector<uint8_t>(image.rgba.begin(), image.rgba.begin() + 4), (std::vector<uint8_t>{1, 65, 128, 255}));
  EXPECT_EQ(std::vector<uint8_t>(image.rgba.begin() + 4, image.rgba.begin() + 8), (std::vector<uint8_t>{128, 128, 128, 255}));
  EXPECT_EQ(std::vector<uint8_t>(image.rgba.begin() + 8, image.rgba.begin() + 12), (std::vector<uint8_t>{40, 40, 40, 255}));
}

}  // namespace penumbra
