#pragma once
// Light sampling for the reference: deterministic per-pixel random numbers, a jittered grid of
// strata, and the area-preserving map from the unit square to a cone of directions (uniform in
// solid angle). Inline: these run once per shadow ray.
#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace penumbra::reference {

/// PCG32 (O'Neill 2014): small state, good statistics, one independent stream per pixel.
class Pcg32 {
public:
  Pcg32(uint64_t seed, uint64_t stream) : mInc((stream << 1u) | 1u) {
    next();
    mState += seed;
    next();
  }
  uint32_t next() {
    const uint64_t old = mState;
    mState = old * 6364136223846793005ull + mInc;
    const auto xorshifted = static_cast<uint32_t>(((old >> 18u) ^ old) >> 27u);
    const auto rot = static_cast<uint32_t>(old >> 59u);
    return (xorshifted >> rot) | (xorshifted << ((32u - rot) & 31u));
  }
  /// Uniform in [0, 1): 24 random bits, so 1.0f is never returned.
  float uniform() { return static_cast<float>(next() >> 8) * 0x1p-24f; }

private:
  uint64_t mState = 0;
  uint64_t mInc;
};

/// Columns of the jittered grid for n samples: the largest divisor of n that is ≤ √n, so the
/// grid has exactly n cells (16×16 for 256, 8×16 for 128; a prime n degrades to 1×n strips).
inline int strataColumns(int n) {
  int columns = static_cast<int>(std::sqrt(static_cast<double>(n)));
  while (columns > 1 && n % columns != 0) --columns;
  return columns < 1 ? 1 : columns;
}

/// sin ψ and cos ψ for |ψ| ≤ π/4, as their Taylor polynomials to degree 9 and 10 in float: the
/// terms left out are under 2·10⁻⁹, below float's spacing, so the error is the rounding's (a few
/// units in the last place). Plain arithmetic, so that a loop over many samples runs several to an
/// instruction, where a libm call would take them one at a time.
struct SinCos {
  float sin = 0.0f, cos = 1.0f;
};
inline SinCos sinCosQuarter(float psi) {
  const float p2 = psi * psi;
  const float s = psi + psi * p2 * (-1.0f / 6.0f + p2 * (1.0f / 120.0f + p2 * (-1.0f / 5040.0f + p2 * (1.0f / 362880.0f))));
  const float c = 1.0f + p2 * (-0.5f + p2 * (1.0f / 24.0f + p2 * (-1.0f / 720.0f + p2 * (1.0f / 40320.0f + p2 * (-1.0f / 3628800.0f)))));
  return {s, c};
}

/// Shirley & Chiu's concentric map, unit square → unit disk. Area-preserving and with low
/// distortion, so square strata stay compact cells on the disk (and on the light). Of the square's
/// point o = 2(u, v) − 1, the larger coordinate is the radius r (signed) and the ratio of the
/// other to it the angle from that axis, ψ = π/4 · ratio, |ψ| ≤ π/4: the disk point is
/// r·(cos ψ, sin ψ) about the x axis, r·(sin ψ, cos ψ) about the y axis, so the sine and cosine
/// are only ever taken within a quarter turn (sinCosQuarter). Without a branch (the wedge is a
/// select), so that a loop over many samples runs several to an instruction.
inline glm::vec2 concentricDisk(float u, float v) {
  const float ox = 2.0f * u - 1.0f, oy = 2.0f * v - 1.0f;
  constexpr float kQuarterPi = 0.78539816339744830962f;
  const bool aboutX = std::abs(ox) > std::abs(oy);
  const float r = aboutX ? ox : oy;
  // 0/0 at the centre only (about y, |ox| ≤ |oy| = 0), which is not kept.
  const SinCos sc = sinCosQuarter(kQuarterPi * ((aboutX ? oy : ox) / r));
  const float along = r * sc.cos, across = r * sc.sin;
  const bool centre = r == 0.0f;
  return {centre ? 0.0f : (aboutX ? along : across), centre ? 0.0f : (aboutX ? across : along)};
}

/// 1 − cos α for a cone of half angle α, without the cancellation of 1 − cos α for the sun's
/// tiny angles (0.0047 rad would keep ~2 significant digits in float).
inline float oneMinusCos(float angleRad) {
  const float s = std::sin(0.5f * angleRad);
  return 2.0f * s * s;
}

/// 1 − cos α of the cone subtended by a sphere of radius r at distance d > r: sin α = r/d.
inline float sphereOneMinusCos(float radiusM, float distanceM) {
  const float s2 = (radiusM / distanceM) * (radiusM / distanceM);
  return s2 / (1.0f + std::sqrt(1.0f - s2));
}

/// A disk point (x, y) → a direction in the cone about +Z with 1 − cos α = `capHeight`. The disk's
/// area maps linearly onto the cap's solid angle (r² ∝ 1 − cos θ), so uniform in → uniform out.
/// Without a branch, as concentricPolar.
inline glm::vec3 coneDirection(float x, float y, float capHeight) {
  const float r2 = x * x + y * y;
  const float h = r2 * capHeight;  // 1 − cos θ
  const float cosTheta = 1.0f - h;
  const float sinTheta = std::sqrt(std::max(0.0f, h * (2.0f - h)));
  const float scale = sinTheta / std::sqrt(r2);  // 0/0 at the centre, which is not kept
  const float dx = x * scale, dy = y * scale;
  const bool centre = r2 <= 0.0f;
  return {centre ? 0.0f : dx, centre ? 0.0f : dy, centre ? 1.0f : cosTheta};
}

/// An orthonormal frame with `n` as its third axis (Duff et al. 2017, branchless).
struct Frame {
  glm::vec3 t, b, n;
  glm::vec3 toWorld(const glm::vec3& v) const { return v.x * t + v.y * b + v.z * n; }
};
inline Frame frameAround(const glm::vec3& n) {
  const float sign = std::copysign(1.0f, n.z);
  const float a = -1.0f / (sign + n.z);
  const float b = n.x * n.y * a;
  return {{1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x}, {b, sign + n.y * n.y * a, -n.y}, n};
}

}  // namespace penumbra::reference
