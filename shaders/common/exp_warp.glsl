#pragma once
// Visibility from exponentially warped depth maps (esm, evsm, evsm-soft); the warps themselves
// and their limits are in shadows/filters/exp_warp.shared.h.
//  esm  (Annen et al. 2008, "Exponential shadow maps"): V = E[p] / p(t) = E[exp(2c (z − t))],
//       clamped to 1. Depths behind the receiver count more than 1 and depths just in front
//       nearly 1 (light near contacts); it never reads darker than the true lit fraction of
//       the region, since each term is >= 1 where z >= t and >= 0 elsewhere.
//  evsm (Lauritzen & McCool 2008, "Layered variance shadow maps"): Chebyshev's one-tailed bound
//       (common/chebyshev.glsl) on the mean and variance of a warp; with both warps, the smaller
//       of the two bounds. Each is an upper bound on the lit fraction, as vsm's, but the warp
//       pushes occluders far in front of the receiver toward 0 (p) or far out (n), so a region
//       of two occluders no longer bleeds: vsm's light bleeding shrinks by e^(-2c·gap).
// The bound is scale-free, so each warp is measured in units of its region's mean: a warp's
// values span e^±86 in float32, where absolute floors and distances are subnormal near one end
// and overflow near the other. In those units the second moment E[w²] / E[w]² is at most
// 1 / (the weight of the region's largest warp)², a few million for a 2048² map, and only the
// receiver's distance from the mean can grow without bound, which is capped (a smaller distance
// only makes the bound larger: still a bound).
#include "common/chebyshev.glsl"
#include "techniques/filters/exp_warp.shared.h"

// A receiver this many means away from its region's mean is as good as infinitely far: the
// bound is below 1e-30 of the variance (squares stay far below float32's 3.4e38).
const float kMaxRelativeDistance = 1e15;

// esm: the filtered E[p] against the receiver at t.
float esmVisibility(float meanWarp, float c, float t) { return min(meanWarp / positiveWarp(t, c), 1.0); }

// The variance floor of a warp, relative to its region's mean²: a depth variance (stored-depth
// units, from common/shadow.glsl's texelDepthVariance) taken through the warp's slope at the
// mean, |dw/dz| = 2c·|w| (a depth spread σ around the region's depths spreads their warps by
// 2c·|w|·σ), and at least the storage's rounding (exp_warp.shared.h). (Taken at the receiver's
// warp instead, the floor does not shrink with the warp of occluders in front, and with c+ = 40
// it let light through the shadow of `pen`, whose pencil lies within 1/(2c) of the floor: umbra
// leak 0.61 % against vsm's 0.06 %.)
struct WarpFloor {
  float c;              // the warp's exponent
  float depthVariance;  // linear depth²
  float storage;        // relative to the mean²
};

// A warp region's moments (E[w], E[w²]) and the receiver's warp w_t in units of the mean (both
// warps keep one sign, so the ratios are positive): (the receiver's w_t / E[w], variance / E[w]²).
vec2 warpReceiverVariance(vec2 moments, float wt, WarpFloor f) {
  float receiver = min(wt / moments.x, kMaxRelativeDistance);
  float variance = moments.y / (moments.x * moments.x) - 1.0;
  return vec2(receiver, max(variance, max(4.0 * f.c * f.c * f.depthVariance, f.storage)));
}

// Chebyshev's bound on one warp, in units of the mean (the mean at 1). The positive warp's
// shadow side is a receiver beyond the mean (w_t / E[w] > 1); the negative warp's values are
// negative, so there a receiver beyond the mean has the smaller magnitude (w_t / E[w] < 1) and
// the bound is taken on the mirrored position.
float warpChebyshev(vec2 moments, float wt, WarpFloor f) {
  vec2 rv = warpReceiverVariance(moments, wt, f);
  return chebyshevUpperBound(1.0, rv.y, wt > 0.0 ? rv.x : 2.0 - rv.x);
}

// evsm: filtered moments (E p, E p², E n, E n²), exponents (c+, c−), receiver depth t, the depth
// variance floor and the storage's relative floor; `both`: 4 components (min of the two bounds),
// else the positive warp alone.
float evsmVisibility(vec4 moments, vec2 c, float t, float depthVariance, float storageFloor, bool both) {
  float v = warpChebyshev(moments.xy, positiveWarp(t, c.x), WarpFloor(c.x, depthVariance, storageFloor));
  if (both) v = min(v, warpChebyshev(moments.zw, negativeWarp(t, c.y), WarpFloor(c.y, depthVariance, storageFloor)));
  return v;
}

// vssm's blocker estimate (common/chebyshev.glsl: chebyshevBlockerDepth) on the negative warp
// (evsm-soft), mapped back to depth: (the blockers' depth in [0, t], their fraction). The
// region's mean magnitude is P·|n(t)| + (1 − P)·|n_occ|, the unoccluded part taken at the
// receiver; and |n_occ| / |n(t)| = exp(2c− (t − z_occ)). On this warp what lies behind the
// receiver weighs at most as much as the receiver's own depth would (|n| shrinks with depth);
// on the positive warp it weighs e^(2c+ Δz), and a search region on a tilted floor read as lit
// whatever it held. The warp weighs near blockers more (a mean of e^(−2c z) sits near the
// smallest z), so a region of several blocker depths reads nearer the light than its plain mean.
vec2 evsmBlockerDepth(vec2 negativeMoments, float t, WarpFloor f) {
  vec2 rv = warpReceiverVariance(negativeMoments, negativeWarp(t, f.c), f);
  float unoccluded = chebyshevUpperBound(1.0, rv.y, 2.0 - rv.x);
  if (unoccluded >= 1.0) return vec2(t, 0.0);
  // |n_occ| / |n(t)| in units of the mean: (1 − P·r) / ((1 − P)·r), r = |n(t)| / E|n| < 1 here.
  float ratio = (1.0 - unoccluded * rv.x) / ((1.0 - unoccluded) * rv.x);
  return vec2(clamp(t - log(max(ratio, 1.0)) / (2.0 * f.c), 0.0, t), 1.0 - unoccluded);
}
