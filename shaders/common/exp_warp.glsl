#pragma once
// Visibility from exponentially warped depth maps (esm, evsm, evsm-soft); the warps themselves
// and their limits are in shadows/filters/exp_warp.shared.h. Everything is computed relative to
// the receiver's own warp w_t (moments divided by w_t and w_t²): a receiver near the light has
// w_t ~ e^-43, whose square is close to float32's smallest normal, and a floor or a distance in
// absolute units there would be subnormal or zero.
//  esm  (Annen et al. 2008, "Exponential shadow maps"): V = E[p] / p(t) = E[exp(2c+ (z − t))],
//       clamped to 1. Depths behind the receiver count more than 1 and depths just in front
//       nearly 1 (light near contacts); it never reads darker than the true lit fraction of
//       the region, since each term is >= 1 where z >= t and >= 0 elsewhere.
//  evsm (Lauritzen & McCool 2008, "Layered variance shadow maps"): Chebyshev's one-tailed bound
//       (common/chebyshev.glsl) on the mean and variance of a warp; with both warps, the smaller
//       of the two bounds. Each is an upper bound on the lit fraction, as vsm's, but the warp
//       pushes occluders far in front of the receiver toward 0 (p) or far out (n), so a region
//       of two occluders no longer bleeds: vsm's light bleeding shrinks by e^(-2c·gap).
#include "common/chebyshev.glsl"
#include "shadows/filters/exp_warp.shared.h"

// Relative moments are capped so that σ² + (t − μ)² stays finite in float32 (1e36 + 1e36):
// they reach e^172 where a region holds depths far behind a receiver near the light, and a
// bound that large is 1 (lit) or 0 anyway.
const float kMaxRelativeMean = 1e18;
const float kMaxRelativeSecondMoment = 1e36;

// esm: the filtered E[p] against the receiver at t.
float esmVisibility(float meanWarp, float c, float t) { return min(meanWarp / positiveWarp(t, c), 1.0); }

// A warp's mean and floored variance from its filtered moments (E[w], E[w²]), in units of the
// receiver's w_t (so w / w_t > 0 for both warps). The floor is a depth variance (stored-depth
// units, from common/shadow.glsl's texelDepthVariance) taken through the warp's slope at the
// region's mean, |dw/dz| = 2c·w: a depth spread σ around the region's depths spreads their warps
// by 2c·w·σ. (Taken at the receiver instead, as the warp's slope at t, the floor does not shrink
// with the warp for occluders in front, and with c+ = 40 it let light through the shadow of
// `pen`, whose pencil lies 1/(2c) in front of the floor: umbra leak 0.61 % against vsm's 0.06 %.)
// It is at least the storage's rounding (exp_warp.shared.h), in the same units.
struct WarpFloor {
  float c;              // the warp's exponent
  float depthVariance;  // linear depth²
  float storage;        // relative to the mean warp²
};

vec2 relativeWarpMeanVariance(vec2 moments, float wt, WarpFloor f) {
  float mean = min(moments.x / wt, kMaxRelativeMean);
  float second = min(moments.y / (wt * wt), kMaxRelativeSecondMoment);
  float minVariance = min(mean * mean * max(4.0 * f.c * f.c * f.depthVariance, f.storage), kMaxRelativeSecondMoment);
  return vec2(mean, max(second - mean * mean, minVariance));
}

// Chebyshev's bound on one warp, the receiver at relative warp 1. For the negative warp (w_t < 0)
// the relative value w / w_t decreases with depth, so its lit side is below 1 and the bound is
// taken on the mirrored mean.
float relativeWarpChebyshev(vec2 moments, float wt, WarpFloor f) {
  vec2 mv = relativeWarpMeanVariance(moments, wt, f);
  return chebyshevUpperBound(wt > 0.0 ? mv.x : 2.0 - mv.x, mv.y, 1.0);
}

// evsm: filtered moments (E p, E p², E n, E n²), exponents (c+, c−), receiver depth t, the depth
// variance floor and the storage's relative floor; `both`: 4 components (min of the two bounds),
// else the positive warp alone.
float evsmVisibility(vec4 moments, vec2 c, float t, float depthVariance, float storageFloor, bool both) {
  float v = relativeWarpChebyshev(moments.xy, positiveWarp(t, c.x), WarpFloor(c.x, depthVariance, storageFloor));
  if (both)
    v = min(v, relativeWarpChebyshev(moments.zw, negativeWarp(t, c.y), WarpFloor(c.y, depthVariance, storageFloor)));
  return v;
}

// vssm's blocker estimate (common/chebyshev.glsl: chebyshevBlockerDepth) on the positive warp,
// mapped back to depth: (the blockers' depth in [0, t], their fraction). The warp weighs far
// blockers more (a mean of e^(c z) sits near the largest z), so a region of several blocker
// depths reads nearer the receiver than its plain mean.
vec2 evsmBlockerDepth(vec2 moments, float t, WarpFloor f) {
  float c = f.c;
  vec2 mv = relativeWarpMeanVariance(moments, positiveWarp(t, c), f);
  vec2 b = chebyshevBlockerDepth(mv.x, mv.y, 1.0);
  // b.x = w_occ / w_t = exp(2c (z_occ − t)); 0 where the blockers lie beyond the warp's range.
  const float kSmallestRelativeWarp = 1e-37;  // a normal float: log stays finite
  return vec2(clamp(t + log(max(b.x, kSmallestRelativeWarp)) / (2.0 * c), 0.0, t), b.y);
}
