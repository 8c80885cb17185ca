#pragma once
// Summed-area tables of depth moments (SatBuilder, passes/sat_scan.comp.glsl): O(1) box means.
// Precision strategy: every moment z^k (z = linear depth in [0, 1]) is stored as a fixed-point
// integer q_k ≈ z^k · 2^31 (q_1 = round(z · 2^31), q_{k+1} = round(q_k · q_1 / 2^31): within
// k · 2^-32 of z^k) and summed in 64-bit unsigned integers (native uint64_t where the driver
// has GL_ARB_gpu_shader_int64, else two 32-bit words with carry). Integer sums are exact and independent of the order of the parallel scan; a 2048² map
// sums to at most 2^22 · 2^31 = 2^53, which converts to double without rounding. Box sums are
// taken in double, so mean and variance carry no cancellation error beyond the 2^-32 rounding of
// each input value (k · 2^-32 for z^k).
// Layout: a storage buffer (binding PN_SSBO_SAT) of uvec4, one per texel and layer, row-major
// layers of size.x · size.y (satIndex); layer view·pairs + k holds moments 2k+1 and 2k+2 as
// (lo, hi, lo, hi) words of the inclusive prefix sum S(x, y) = sum over x' <= x, y' <= y.
// Readers include this file and get the buffer read-only; the builder defines PN_SAT_WRITER and
// declares it write-only itself.

#include "shared/Bindings.h"

#define PN_SAT_FRACTION_BITS 31
const double kSatFixedOne = 2147483648.0LF;  // 2^PN_SAT_FRACTION_BITS

#ifdef PN_NATIVE_INT64  // defined by a shader that enabled GL_ARB_gpu_shader_int64 at its top
uvec2 add64(uvec2 a, uvec2 b) { return unpackUint2x32(packUint2x32(a) + packUint2x32(b)); }
#else
uvec2 add64(uvec2 a, uvec2 b) {
  uint carry;
  uint lo = uaddCarry(a.x, b.x, carry);
  return uvec2(lo, a.y + b.y + carry);
}
#endif
uvec4 add64x2(uvec4 a, uvec4 b) { return uvec4(add64(a.xy, b.xy), add64(a.zw, b.zw)); }

double u64ToDouble(uvec2 v) { return double(v.y) * 4294967296.0LF + double(v.x); }

// Fixed-point depth: round(z · 2^31) for z in [0, 1] (float scaling by 2^31 is exact).
uint depthToFixed(float z) { return uint(round(clamp(z, 0.0, 1.0) * 2147483648.0)); }

// The product of two fixed-point values, rounded back to 31 fraction bits: (a·b + 2^30) >> 31.
uint fixedMul(uint a, uint b) {
  uint hi, lo, carry;
  umulExtended(a, b, hi, lo);
  lo = uaddCarry(lo, 1u << 30, carry);
  return ((hi + carry) << 1) | (lo >> 31);
}

int satIndex(ivec2 size, int layer, ivec2 texel) { return (layer * size.y + texel.y) * size.x + texel.x; }

#ifndef PN_SAT_WRITER
layout(std430, binding = PN_SSBO_SAT) readonly buffer SatTable { uvec4 b_sat[]; };

// The table at texel corner c (in texels, 0..size): the sum over texels x < c.x, y < c.y.
dvec2 satCorner(ivec2 size, ivec2 c, int layer) {
  if (c.x <= 0 || c.y <= 0) return dvec2(0.0LF);
  uvec4 v = b_sat[satIndex(size, layer, c - 1)];
  return dvec2(u64ToDouble(v.xy), u64ToDouble(v.zw));
}

// The table at a continuous corner position p (texels): bilinear in the corner grid, which is the
// exact integral of the piecewise-constant map over [0, p.x] x [0, p.y].
dvec2 satCornerBilinear(ivec2 size, vec2 p, int layer) {
  ivec2 i = clamp(ivec2(floor(p)), ivec2(0), size - 1);  // p.x = size: i = size-1, fx = 1
  double fx = double(p.x - float(i.x)), fy = double(p.y - float(i.y));
  dvec2 s00 = satCorner(size, i, layer), s10 = satCorner(size, i + ivec2(1, 0), layer);
  dvec2 s01 = satCorner(size, i + ivec2(0, 1), layer), s11 = satCorner(size, i + ivec2(1, 1), layer);
  return mix(mix(s00, s10, fx), mix(s01, s11, fx), fy);
}

// The box of half-size halfSize (texels) around centre, shrunk about its centre where it would
// cross the map's edge (at least half a texel each way). Clipped on one side only, a box is no
// longer centred on the receiver, and on a tilted receiver its mean depth then differs from the
// receiver's own: a false blocker along the map's edge.
void satCentredBox(ivec2 size, vec2 centre, vec2 halfSize, out vec2 lo, out vec2 hi) {
  vec2 h = max(min(halfSize, min(centre, vec2(size) - centre)), vec2(0.5));
  lo = centre - h;
  hi = centre + h;
}

// Mean of the two moments of pair layer `layer` of a size.x · size.y table over the box [lo, hi]
// (continuous texel coordinates, clipped to the map).
dvec2 satBoxMean(ivec2 size, vec2 lo, vec2 hi, int layer) {
  // Boxes narrower than a texel grow about their centre; the box is then clipped to the map
  // (the coordinates themselves are used as given: recentring would round them).
  vec2 grow = 0.5 * max(vec2(1.0) - (hi - lo), vec2(0.0));
  lo = clamp(lo - grow, vec2(0.0), vec2(size) - 0.5);
  hi = clamp(hi + grow, lo + 0.5, vec2(size));
  dvec2 sum = satCornerBilinear(size, hi, layer) - satCornerBilinear(size, vec2(lo.x, hi.y), layer) -
              satCornerBilinear(size, vec2(hi.x, lo.y), layer) + satCornerBilinear(size, lo, layer);
  double area = double(hi.x - lo.x) * double(hi.y - lo.y);
  return sum / (area * kSatFixedOne);
}

// The box with its edges moved to the nearest texel corners (at least one texel): 4 fetches
// instead of 16, for lookups that tolerate half a texel of error per edge (blocker searches).
dvec2 satBoxMeanSnapped(ivec2 size, vec2 lo, vec2 hi, int layer) {
  ivec2 l = clamp(ivec2(round(lo)), ivec2(0), size - 1);
  ivec2 h = clamp(ivec2(round(hi)), l + 1, size);
  dvec2 sum = satCorner(size, h, layer) - satCorner(size, ivec2(l.x, h.y), layer) -
              satCorner(size, ivec2(h.x, l.y), layer) + satCorner(size, l, layer);
  return sum / (double(h.x - l.x) * double(h.y - l.y) * kSatFixedOne);
}

// The mean of pair layer `layer` over the box of half-size radiusUv (map uv) around uv, kept
// centred (satCentredBox): the region read of the O(1) soft filters (vssm, msm-soft). `exact`: the
// box with its fractional edges (a filter); otherwise its edges snapped to texel corners (a
// blocker search, which needs only a rough blocker depth: a quarter of the fetches).
dvec2 satRegionMean(ivec2 size, vec2 uv, vec2 radiusUv, int layer, bool exact) {
  vec2 lo, hi;
  satCentredBox(size, uv * vec2(size), radiusUv * vec2(size), lo, hi);
  return exact ? satBoxMean(size, lo, hi, layer) : satBoxMeanSnapped(size, lo, hi, layer);
}

// Exact box sums over whole texels [lo, hi] (inclusive texel indices): the test's entry point.
dvec2 satTexelRectMean(ivec2 size, ivec2 lo, ivec2 hi, int layer) {
  dvec2 sum = satCorner(size, hi + 1, layer) - satCorner(size, ivec2(lo.x, hi.y + 1), layer) -
              satCorner(size, ivec2(hi.x + 1, lo.y), layer) + satCorner(size, lo, layer);
  double area = double(hi.x - lo.x + 1) * double(hi.y - lo.y + 1);
  return sum / (area * kSatFixedOne);
}
#endif  // PN_SAT_WRITER

// Mean and variance of depth from box means of (z, z^2). The subtraction is done in double, so a
// flat region gives 0 rather than float noise; the variance is never negative.
vec2 satMeanVariance(dvec2 m) { return vec2(float(m.x), float(max(m.y - m.x * m.x, 0.0LF))); }
