#pragma once
// Summed-area tables of depth moments (SatBuilder, passes/sat_scan.comp.glsl): O(1) box means.
// Precision strategy: every moment z^k (z = linear depth in [0, 1]) is stored as a fixed-point
// integer q = round(z^k · 2^31) and summed in 64-bit unsigned integers (two 32-bit words with
// carry). Integer sums are exact and independent of the order of the parallel scan; a 2048² map
// sums to at most 2^22 · 2^31 = 2^53, which converts to double without rounding. Box sums are
// taken in double, so mean and variance carry no cancellation error beyond the 2^-32 rounding of
// each input value.
// Layout: an RGBA32UI 2D array; layer view·pairs + k holds moments 2k+1 and 2k+2 as
// (lo, hi, lo, hi) words of the inclusive prefix sum S(x, y) = sum over x' <= x, y' <= y.

#define PN_SAT_FRACTION_BITS 31
const double kSatFixedOne = 2147483648.0LF;  // 2^PN_SAT_FRACTION_BITS

uvec2 add64(uvec2 a, uvec2 b) {
  uint carry;
  uint lo = uaddCarry(a.x, b.x, carry);
  return uvec2(lo, a.y + b.y + carry);
}
uvec4 add64x2(uvec4 a, uvec4 b) { return uvec4(add64(a.xy, b.xy), add64(a.zw, b.zw)); }

double u64ToDouble(uvec2 v) { return double(v.y) * 4294967296.0LF + double(v.x); }

// Fixed-point value of a moment in [0, 1].
uvec2 toFixed64(double m) { return uvec2(uint(m * kSatFixedOne + 0.5LF), 0u); }

// The table at texel corner c (in texels, 0..size): the sum over texels x < c.x, y < c.y.
dvec2 satCorner(usampler2DArray sat, ivec2 c, int layer) {
  if (c.x <= 0 || c.y <= 0) return dvec2(0.0LF);
  uvec4 v = texelFetch(sat, ivec3(c - 1, layer), 0);
  return dvec2(u64ToDouble(v.xy), u64ToDouble(v.zw));
}

// The table at a continuous corner position p (texels): bilinear in the corner grid, which is the
// exact integral of the piecewise-constant map over [0, p.x] x [0, p.y].
dvec2 satCornerBilinear(usampler2DArray sat, vec2 p, int layer) {
  ivec2 i = clamp(ivec2(floor(p)), ivec2(0), textureSize(sat, 0).xy - 1);  // p.x = size: i = size-1, fx = 1
  double fx = double(p.x - float(i.x)), fy = double(p.y - float(i.y));
  dvec2 s00 = satCorner(sat, i, layer), s10 = satCorner(sat, i + ivec2(1, 0), layer);
  dvec2 s01 = satCorner(sat, i + ivec2(0, 1), layer), s11 = satCorner(sat, i + ivec2(1, 1), layer);
  return mix(mix(s00, s10, fx), mix(s01, s11, fx), fy);
}

// Mean of the two moments of pair layer `layer` over the box [lo, hi] (continuous texel
// coordinates, clamped to the map). The box is at least one texel wide on each side.
dvec2 satBoxMean(usampler2DArray sat, vec2 lo, vec2 hi, int layer) {
  vec2 size = vec2(textureSize(sat, 0).xy);
  vec2 c = clamp(0.5 * (lo + hi), vec2(0.5), size - 0.5);
  vec2 half_ = clamp(0.5 * (hi - lo), vec2(0.5), 0.5 * size);
  lo = max(c - half_, vec2(0.0));
  hi = min(c + half_, size);
  dvec2 sum = satCornerBilinear(sat, hi, layer) - satCornerBilinear(sat, vec2(lo.x, hi.y), layer) -
              satCornerBilinear(sat, vec2(hi.x, lo.y), layer) + satCornerBilinear(sat, lo, layer);
  double area = double(hi.x - lo.x) * double(hi.y - lo.y);
  return sum / (area * kSatFixedOne);
}

// Exact box sums over whole texels [lo, hi] (inclusive texel indices): the test's entry point.
dvec2 satTexelRectMean(usampler2DArray sat, ivec2 lo, ivec2 hi, int layer) {
  dvec2 sum = satCorner(sat, hi + 1, layer) - satCorner(sat, ivec2(lo.x, hi.y + 1), layer) -
              satCorner(sat, ivec2(hi.x + 1, lo.y), layer) + satCorner(sat, lo, layer);
  double area = double(hi.x - lo.x + 1) * double(hi.y - lo.y + 1);
  return sum / (area * kSatFixedOne);
}
