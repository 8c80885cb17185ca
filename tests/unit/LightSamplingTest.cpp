// The reference's light sampling (reference/LightSampling.h) in the form its per-pixel passes run:
// the branch-free square → disk map against its definition by cases in double precision with
// libm's sine and cosine, and the branch-free cone map against its branching definition bit for
// bit (docs/reference.md, "Estimator").
#include "reference/LightSampling.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

using namespace penumbra::reference;

namespace {

// The concentric map by its cases, in double precision with libm's sine and cosine: the disk
// point r·(cos θ, sin θ), θ from the wedge of the larger coordinate.
glm::dvec2 concentricByCases(float u, float v) {
  const double ox = 2.0 * u - 1.0, oy = 2.0 * v - 1.0;
  if (ox == 0.0 && oy == 0.0) return {0.0, 0.0};
  const double quarterPi = std::atan(1.0);
  const double r = std::abs(ox) > std::abs(oy) ? ox : oy;
  const double theta = std::abs(ox) > std::abs(oy) ? quarterPi * (oy / ox) : 2.0 * quarterPi - quarterPi * (ox / oy);
  return {r * std::cos(theta), r * std::sin(theta)};
}

// The cone map as first written, one branch per case: the definition the branch-free form matches.
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

TEST(LightSampling, BranchFreeMapsMatchTheirCases) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  // Random points, and the cases' borders: the centre, the axes, the diagonals, the corners.
  std::vector<std::pair<float, float>> points = {{0.5f, 0.5f}, {1.0f, 0.5f}, {0.0f, 0.5f}, {0.5f, 1.0f},
                                                 {0.5f, 0.0f}, {0.0f, 0.0f}, {1.0f, 1.0f}, {0.25f, 0.25f},
                                                 {0.75f, 0.25f}, {0.5f, 0.5f + 0x1p-24f}, {0.0f, 1.0f}};
  for (int i = 0; i < 100000; ++i) points.emplace_back(unit(rng), unit(rng));
  size_t differ = 0;
  double worst = 0.0;  // the disk point's error, in units of float's spacing at its radius
  for (const auto& [u, v] : points) {
    const glm::vec2 disk = concentricDisk(u, v);
    const glm::dvec2 exact = concentricByCases(u, v);
    const double r = glm::length(exact);
    if (r > 0.0) {
      worst = std::max(worst, glm::length(glm::dvec2(disk) - exact) / (r * 0x1p-24));
    } else {
      EXPECT_EQ(disk, glm::vec2(0.0f)) << "the centre";
    }
    EXPECT_LE(glm::length(glm::dvec2(disk)), 1.0 + 1e-6) << u << ", " << v << ": in the unit disk";
    for (float capHeight : {0.0f, 1e-5f, 0.02f, 1.0f}) {
      const glm::vec3 a = coneDirectionByCases(disk.x, disk.y, capHeight), b = coneDirection(disk.x, disk.y, capHeight);
      differ += !sameBits(a.x, b.x) || !sameBits(a.y, b.y) || !sameBits(a.z, b.z);
    }
  }
  // A few roundings: of o, of the ratio, of ψ, of the polynomials and of r times them (libm's
  // float sine and cosine of the wedge's float angle, as the map was first written, reach 5.4).
  EXPECT_LE(worst, 5.0);
  EXPECT_GT(worst, 0.0) << "float against double: some rounding shows";
  EXPECT_EQ(differ, 0u);
  // The axes and the diagonal land exactly where they belong.
  EXPECT_EQ(concentricDisk(1.0f, 0.5f), glm::vec2(1.0f, 0.0f));
  EXPECT_EQ(concentricDisk(0.5f, 0.0f), glm::vec2(0.0f, -1.0f));
  EXPECT_EQ(concentricDisk(0.0f, 0.5f), glm::vec2(-1.0f, 0.0f));
  // And the cone map is what it claims: the centre goes to +Z, a unit direction within the cap.
  EXPECT_EQ(coneDirection(0.0f, 0.0f, 0.5f), glm::vec3(0.0f, 0.0f, 1.0f));
  const glm::vec3 rim = coneDirection(1.0f, 0.0f, 0.02f);
  EXPECT_NEAR(glm::length(rim), 1.0f, 1e-6f);
  EXPECT_NEAR(rim.z, 1.0f - 0.02f, 1e-6f);
}

// sinCosQuarter over its whole domain, against libm in double precision: within a few float
// spacings of the true values.
TEST(LightSampling, QuarterTurnSineAndCosineAreWithinAFewUnitsInTheLastPlace) {
  constexpr float kQuarterPi = 0.78539816339744830962f;
  double worstSin = 0.0, worstCos = 0.0;
  constexpr int kSteps = 200000;
  for (int i = -kSteps; i <= kSteps; ++i) {
    const float psi = kQuarterPi * static_cast<float>(i) / static_cast<float>(kSteps);
    const SinCos sc = sinCosQuarter(psi);
    const double s = std::sin(static_cast<double>(psi)), c = std::cos(static_cast<double>(psi));
    if (s != 0.0) worstSin = std::max(worstSin, std::abs(sc.sin - s) / (std::abs(s) * 0x1p-24));
    worstCos = std::max(worstCos, std::abs(sc.cos - c) / (c * 0x1p-24));
  }
  EXPECT_EQ(sinCosQuarter(0.0f).sin, 0.0f);
  EXPECT_EQ(sinCosQuarter(0.0f).cos, 1.0f);
  EXPECT_LE(worstSin, 2.0);
  EXPECT_LE(worstCos, 2.0);
}
