// The reference's light sampling (reference/LightSampling.h) in the form its per-pixel passes run:
// the branch-free square → disk → cone maps give the bits of their branching definitions, so the
// references they make do not change (docs/reference.md, "Estimator").
#include "reference/LightSampling.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

using namespace penumbra::reference;

namespace {

// The maps as first written, one branch per case: the definitions the branch-free forms must match.
DiskPolar concentricPolarByCases(float u, float v) {
  const float ox = 2.0f * u - 1.0f, oy = 2.0f * v - 1.0f;
  if (ox == 0.0f && oy == 0.0f) return {};
  constexpr float kQuarterPi = 0.78539816339744830962f;
  if (std::abs(ox) > std::abs(oy)) return {ox, kQuarterPi * (oy / ox)};
  return {oy, 2.0f * kQuarterPi - kQuarterPi * (ox / oy)};
}

glm::vec3 coneDirectionByCases(float x, float y, float capHeight) {
  const float r2 = x * x + y * y;
  const float h = r2 * capHeight;
  const float cosTheta = 1.0f - h;
  if (r2 <= 0.0f) return {0.0f, 0.0f, 1.0f};
  const float sinTheta = std::sqrt(std::max(0.0f, h * (2.0f - h)));
  const float scale = sinTheta / std::sqrt(r2);
  return {x * scale, y * scale, cosTheta};
}

bool sameBits(float a, float b) { return std::bit_cast<uint32_t>(a) == std::bit_cast<uint32_t>(b); }

}  // namespace

TEST(LightSampling, BranchFreeMapsGiveTheBitsOfTheirCases) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  // Random points, and the cases' borders: the centre, the axes, the diagonals, the corners.
  std::vector<std::pair<float, float>> points = {{0.5f, 0.5f}, {1.0f, 0.5f}, {0.0f, 0.5f}, {0.5f, 1.0f},
                                                 {0.5f, 0.0f}, {0.0f, 0.0f}, {1.0f, 1.0f}, {0.25f, 0.25f},
                                                 {0.75f, 0.25f}, {0.5f, 0.5f + 0x1p-24f}};
  for (int i = 0; i < 100000; ++i) points.emplace_back(unit(rng), unit(rng));
  size_t differ = 0;
  for (const auto& [u, v] : points) {
    const DiskPolar cases = concentricPolarByCases(u, v), free = concentricPolar(u, v);
    differ += !sameBits(cases.r, free.r) || !sameBits(cases.theta, free.theta);
    const float x = free.r * std::cos(free.theta), y = free.r * std::sin(free.theta);
    for (float capHeight : {0.0f, 1e-5f, 0.02f, 1.0f}) {
      const glm::vec3 a = coneDirectionByCases(x, y, capHeight), b = coneDirection(x, y, capHeight);
      differ += !sameBits(a.x, b.x) || !sameBits(a.y, b.y) || !sameBits(a.z, b.z);
    }
  }
  EXPECT_EQ(differ, 0u);
  // And the maps are what they claim: the centre goes to +Z, a unit direction within the cap.
  EXPECT_EQ(coneDirection(0.0f, 0.0f, 0.5f), glm::vec3(0.0f, 0.0f, 1.0f));
  const glm::vec3 rim = coneDirection(1.0f, 0.0f, 0.02f);
  EXPECT_NEAR(glm::length(rim), 1.0f, 1e-6f);
  EXPECT_NEAR(rim.z, 1.0f - 0.02f, 1e-6f);
}
