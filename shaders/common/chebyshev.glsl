#pragma once
// The Chebyshev–Cantelli one-tailed inequality, shared by every variance-based filter (vsm, vssm).
// For any distribution of depths z with mean mu and variance var, and a receiver at depth t > mu:
//   P(z >= t) <= p_max(t) = var / (var + (t - mu)^2).
// It assumes nothing about the distribution's shape; it is exact for a single planar occluder in
// front of a planar receiver, and too bright (light bleeding) when several occluders at different
// depths share a filter region.

// Upper bound on the fraction of depths at or beyond t ("lit fraction"); 1 where t <= mu.
float chebyshevUpperBound(float mu, float var, float t) {
  if (t <= mu) return 1.0;
  float d = t - mu;
  return var / (var + d * d);
}

// Mean and floored variance from the first two raw moments (E[z], E[z^2]). The floor hides both
// the float cancellation of E[z^2] - E[z]^2 and the zero variance of a region of one flat depth.
// The floor is kept above kMinVariance, so that t > mu always gives p_max < 1 (never 0 / 0).
const float kMinVariance = 1e-12;
float floorVariance(float variance, float minVariance) { return max(variance, max(minVariance, kMinVariance)); }
vec2 meanVariance(vec2 moments, float minVariance) {
  return vec2(moments.x, floorVariance(moments.y - moments.x * moments.x, minVariance));
}

// VSSM's blocker estimate: a region's mean depth is P·z_unocc + (1 − P)·z_occ with P = p_max and
// the unoccluded part taken at the receiver's depth (z_unocc = t), so z_occ = (mu − P·t) / (1 − P).
// Returns (z_occ clamped to [0, t], the blocker fraction 1 − P); (t, 0) where nothing is in front.
vec2 chebyshevBlockerDepth(float mu, float var, float t) {
  float unoccluded = chebyshevUpperBound(mu, var, t);
  if (unoccluded >= 1.0) return vec2(t, 0.0);
  return vec2(clamp((mu - unoccluded * t) / (1.0 - unoccluded), 0.0, t), 1.0 - unoccluded);
}

// Light-bleeding reduction: visibilities below `amount` become 0 and the rest is stretched back
// over [0, 1]. Bleeding regions are usually faint (p_max small), so cutting the low tail removes
// them at the price of darker, narrower penumbrae. amount = 0 is the identity.
float reduceLightBleeding(float pMax, float amount) {
  return clamp((pMax - amount) / (1.0 - amount), 0.0, 1.0);
}
