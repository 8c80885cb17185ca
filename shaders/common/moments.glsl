#pragma once
// Four-moment depth distributions (Peters & Klein 2015, "Moment Shadow Mapping"). A filtered
// texel holds b = E[(z, z^2, z^3, z^4)] over its footprint. Among all depth distributions with
// these moments, the "Hamburger 4MSM" bound is the smallest possible fraction of depth in front of
// the receiver depth t: it is computed from the three-point distribution with these moments that
// has one point at t (the canonical representation through t), and it is sharp. The fraction is
// therefore never overestimated as shadow; it can be underestimated (leak) by at most the weight
// of that point at t. Requires the moments of depths in [0, 1] (linear light depth).
#include "common/MomentQuantization.h"
#include "common/chebyshev.glsl"

vec4 depthMoments(float z) {
  float z2 = z * z;
  return vec4(z, z2, z2 * z, z2 * z2);
}

// The optimised 16-bit storage basis (MomentQuantization.h). The result lies in [0, 1]^4 for z in
// [0, 1], so UNORM16 targets hold it; decode after filtering, never before.
vec4 quantizeMoments16(vec4 b) {
  vec4 q = mat4(PN_MSM16_ENCODE_MATRIX) * b;
  q.x += PN_MSM16_ENCODE_OFFSET_X;
  return q;
}
vec4 dequantizeMoments16(vec4 q) {
  q.x -= PN_MSM16_ENCODE_OFFSET_X;
  return mat4(PN_MSM16_DECODE_MATRIX) * q;
}

// The moment bias α: b' = (1 - α) b + α b*, with b* = 0.5 in every coordinate, the moments of
// half the mass at depth 0 and half at depth 1. Rounding can push a filtered vector out of the
// set of valid moment vectors (the Hankel matrix loses positive definiteness, e.g. a flat
// region, whose true vector lies on the boundary); mixing in a strictly spread distribution pulls
// it back inside. Larger α = more robust, but lighter shadows (the mixture's own mass at 0 leaks).
vec4 biasMoments(vec4 b, float alpha) { return mix(b, vec4(0.5), alpha); }

// The smallest α the solve stays stable with: the moments' own rounding must stay inside the
// mixture's spread. 32-bit floats (and the SAT's exact sums, solved in float): 1e-6, below which
// the solve breaks up (measured on city, where a cascade's texel is 4e-5 of its depth range:
// RMSE 0.042 at 1e-6, 0.22 at 1e-8); the 16-bit basis: 3e-5, Peters & Klein's value for its
// 2^-16 rounding. The filters state α in texels² of depth (common/shadow.glsl's
// texelDepthVariance) and keep it above these.
const float kMinMomentBiasFloat32 = 1e-6;
const float kMinMomentBiasQuantized16 = 3e-5;
float floorMomentBias(float alpha, bool quantized16) {
  return max(alpha, quantized16 ? kMinMomentBiasQuantized16 : kMinMomentBiasFloat32);
}

// A three-point distribution matching (1, b1, b2, b3, b4) with z[0] = t. z[1] <= z[2]; w sums to 1.
// `valid` false: rounding left the Hankel matrix singular or indefinite (below).
struct MomentSupport {
  vec3 z;
  vec3 w;
  bool valid;
};

// The support through t. The other two points are the roots of c0 + c1 z + c2 z^2 where
// c = B^-1 (1, t, t^2) and B is the 3x3 Hankel matrix of (1, b1..b4), solved by an LDL^T
// factorisation (no square roots); the weights follow from Lagrange interpolation on the three
// points. w[0] = 1 / ((1, t, t^2) · c) is the largest mass any matching distribution can put at t.
MomentSupport momentSupport(vec4 b, float t) {
  // B = L D L^T with L = [1 0 0; b1 1 0; b2 l32 1], D = diag(1, d22, d33).
  float d22 = b.y - b.x * b.x;
  float l32d22 = b.z - b.x * b.y;
  float l32 = l32d22 / d22;
  float d33 = (b.w - b.y * b.y) - l32 * l32d22;
  // Forward substitution L y = (1, t, t^2), scaling by D^-1, back substitution L^T c = y.
  vec3 c = vec3(1.0, t, t * t);
  c.y -= b.x;
  c.z -= b.y + l32 * c.y;
  c.y /= d22;
  c.z /= d33;
  c.y -= l32 * c.z;
  c.x -= dot(c.yz, b.xy);
  // Roots of the quadratic; a negative discriminant only arises from rounding.
  float p = c.y / c.z;
  float q = c.x / c.z;
  float r = sqrt(max(0.25 * p * p - q, 0.0));
  MomentSupport s;
  // The bias keeps d22 and d33 positive in exact arithmetic, but where a region holds (nearly)
  // one depth, d33 is a difference of moments that agree to their last bits and float32 storage
  // can leave it zero or negative (or NaN). The quadratic's roots are then meaningless, and they
  // showed as fully lit pixels scattered through an umbra (fence's floor behind its wall with a
  // 2048² map: msm RMSE 0.060 against 0.015 at 1024²).
  s.valid = d22 > 0.0 && d33 > 0.0;
  s.z = vec3(t, -0.5 * p - r, -0.5 * p + r);
  // w_i = E[(Z - z_j)(Z - z_k)] / ((z_i - z_j)(z_i - z_k)) over the two other points j, k.
  s.w.y = (b.y - b.x * (s.z.x + s.z.z) + s.z.x * s.z.z) / ((s.z.y - s.z.x) * (s.z.y - s.z.z));
  s.w.z = (b.y - b.x * (s.z.x + s.z.y) + s.z.x * s.z.y) / ((s.z.z - s.z.x) * (s.z.z - s.z.y));
  s.w.x = 1.0 - s.w.y - s.w.z;
  return s;
}

// Hamburger 4MSM: the sharp lower bound on the fraction of depth strictly in front of t (the
// shadow intensity, 0 = lit). b must already be biased (biasMoments).
float hamburgerShadowIntensity(vec4 b, float t) {
  MomentSupport s = momentSupport(b, t);
  // A degenerate solve: the higher moments carry nothing beyond the first two, and for the one-
  // or two-depth regions that produce it Chebyshev's bound is exact.
  if (!s.valid) {
    vec2 mv = meanVariance(b.xy, 0.0);
    return 1.0 - chebyshevUpperBound(mv.x, mv.y, t);
  }
  float intensity = 0.0;
  if (s.z.z < t) intensity = 1.0 - s.w.x;  // both other points in front: everything but the mass at t
  else if (s.z.y < t) intensity = s.w.y;
  return clamp(intensity, 0.0, 1.0);
}

// The mean depth of the part of the canonical representation in front of t (moment-based blocker
// search). x: mean blocker depth, y: blocker fraction (0 = no blocker; x is then t).
vec2 momentBlockerDepth(vec4 b, float t) {
  MomentSupport s = momentSupport(b, t);
  if (!s.valid) {  // as hamburgerShadowIntensity: vssm's estimate from the first two moments
    vec2 mv = meanVariance(b.xy, 0.0);
    return chebyshevBlockerDepth(mv.x, mv.y, t);
  }
  float w = 0.0, wz = 0.0;
  if (s.z.y < t) { w += s.w.y; wz += s.w.y * s.z.y; }
  if (s.z.z < t) { w += s.w.z; wz += s.w.z * s.z.z; }
  return w > 0.0 ? vec2(wz / w, w) : vec2(t, 0.0);
}
