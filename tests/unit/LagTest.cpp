// Lag and ghosting (comparison/Lag.h) on crafted frames: a still plane whose reference darkens
// pixel by pixel, seen by a technique that shows the reference of the frame before (it lags by
// construction) and by the reference itself.
#include "comparison/Lag.h"

#include <gtest/gtest.h>

#include <vector>

using namespace penumbra;

namespace {

constexpr int kSide = 4;

// A kSide² frame of one still object: pixel (x, y) sees the point at its own clip-space centre
// (clipFromWorld = identity), V_ref = vRef, V = v.
FlickerFrame plane(const std::vector<float>& vRef, const std::vector<float>& v) {
  FlickerFrame f;
  f.width = f.height = kSide;
  f.cameraPosition = glm::vec3(0.0f, 0.0f, -1.0f);
  f.pixelAngleRad = 1.0f;  // a generous footprint: every point is found where it was
  for (int y = 0; y < kSide; ++y)
    for (int x = 0; x < kSide; ++x) {
      f.position.emplace_back((x + 0.5f) / kSide * 2.0f - 1.0f, (y + 0.5f) / kSide * 2.0f - 1.0f, 0.5f);
      f.geoNormal.emplace_back(0.0f, 0.0f, -1.0f);
    }
  f.object.assign(kSide * kSide, 1);
  f.mask.assign(kSide * kSide, 1);
  f.vRef = vRef;
  f.v = v;
  f.worldFromObject = {glm::mat4(1.0f)};
  return f;
}

// The reference of frame k: pixels 0 .. 2k−1 (row by row) are in shadow, the rest lit.
std::vector<float> shadowUpTo(int k) {
  std::vector<float> v(kSide * kSide, 1.0f);
  for (int i = 0; i < 2 * k && i < kSide * kSide; ++i) v[static_cast<size_t>(i)] = 0.0f;
  return v;
}

}  // namespace

TEST(Lag, ALaggingTechniqueShowsLagAndTheReferenceNone) {
  constexpr int kFrames = 6;
  std::vector<FlickerFrame> truth, lagging;  // nearest last
  LagCounts truthLag, laggingLag;
  for (int k = 0; k < kFrames; ++k) {
    truth.push_back(plane(shadowUpTo(k), shadowUpTo(k)));
    lagging.push_back(plane(shadowUpTo(k), shadowUpTo(k > 0 ? k - 1 : 0)));
    std::vector<const FlickerFrame*> truthBefore, laggingBefore;
    for (int j = k - 1; j >= 0; --j) {
      truthBefore.push_back(&truth[static_cast<size_t>(j)]);
      laggingBefore.push_back(&lagging[static_cast<size_t>(j)]);
    }
    truthLag += countLag(truth.back(), truthBefore);
    laggingLag += countLag(lagging.back(), laggingBefore);
  }
  // Frames 1..5 darken two new pixels each; with 4 frames looked back a pixel stays "changing"
  // for 4 frames after it darkened.
  EXPECT_EQ(truthLag.pixels, laggingLag.pixels);
  EXPECT_EQ(truthLag.pixels, 2u * (1 + 2 + 3 + 4 + 4));
  EXPECT_EQ(truthLag.rmse(), 0.0);
  EXPECT_EQ(truthLag.ghostPct(), 0.0);
  // The lagging technique is one frame late on the two pixels that darkened last: V = 1 where
  // V_ref = 0, too bright by 1, on 2 of the changing pixels of each frame.
  EXPECT_EQ(laggingLag.tooBright, 2u * (kFrames - 1));
  EXPECT_EQ(laggingLag.tooDark, 0u);
  EXPECT_NEAR(laggingLag.rmse(), std::sqrt(10.0 / static_cast<double>(laggingLag.pixels)), 1e-12);
  EXPECT_NEAR(laggingLag.ghostPct(), 100.0 * 10.0 / static_cast<double>(laggingLag.pixels), 1e-12);
}

TEST(Lag, OnlyTheLastFramesCount) {
  // A change 5 frames back is outside LagOptions::frames = 4; with 5 it counts.
  const FlickerFrame old = plane(shadowUpTo(0), shadowUpTo(0));
  const FlickerFrame now = plane(shadowUpTo(1), shadowUpTo(1));
  const std::vector<const FlickerFrame*> before = {&now, &now, &now, &now, &old};  // nearest first
  EXPECT_EQ(countLag(now, before).pixels, 0u);
  EXPECT_EQ(countLag(now, before, {.frames = 5}).pixels, 2u);
}
