// vssm: variance soft shadow maps (Yang et al. 2010). PCSS's three steps with no loop over texels:
// (1) blocker search: the mean μ and variance σ² of depth over the search region (common/
// penumbra.glsl) in O(1); Chebyshev gives the unoccluded fraction P ≈ P(z >= t), and the region's
// mean splits as μ = P·z_unocc + (1 − P)·z_occ with z_unocc assumed = t, the receiver's depth,
// so z_occ = (μ − P·t) / (1 − P); (2) penumbra width from z_occ by similar triangles, as PCSS;
// (3) visibility = Chebyshev over the penumbra-sized box. Moments come from a summed-area table
// of (z, z²) (source=sat: exact boxes) or from the mip chain of vsm (source=mip: trilinear boxes,
// approximate). Linear light depth per view. Artifacts: vsm's light bleeding; z_unocc = t makes
// blockers look farther than they are when the region mixes receiver and far geometry.
#include "common/chebyshev.glsl"
#include "common/footprint.glsl"
#include "common/sat.glsl"
#include "common/soft_receiver.glsl"
#include "techniques/filters/vssm.shared.h"

layout(std140, binding = PN_UBO_FILTER) uniform VssmBlock { VssmUniforms u_vssm; };
// Where region moments come from (PN_VSSM_SOURCE): the SAT (source=sat) is common/sat.glsl's
// storage buffer.
#if PN_VSSM_SOURCE != PN_VSSM_SOURCE_SAT
layout(binding = PN_TEX_FILTER0) uniform sampler2DArray s_moments;
#endif

// Above this unoccluded fraction the region has no blocker worth a penumbra: fully lit. It also
// keeps 1 − P away from 0 in the blocker-depth division.
const float kUnoccludedLit = 0.99;

// Mean and variance (floored at minVariance) of depth over the box of half-size radiusUv around
// uv in `view`.
// `exact`: a box with fractional edges (the filter); otherwise edges may snap to whole texels
// (the blocker search, which only needs a rough blocker depth: 4 texel fetches instead of 16).
vec2 regionMeanVariance(int view, vec2 uv, vec2 radiusUv, float minVariance, bool exact) {
#if PN_VSSM_SOURCE == PN_VSSM_SOURCE_SAT
  vec2 m = satMeanVariance(satRegionMean(ivec2(shadowMapSize()), uv, radiusUv, view, exact));
  return vec2(m.x, floorVariance(m.y, minVariance));
#else
  return meanVariance(boxMeanFromMips(s_moments, view, uv, radiusUv, u_vssm.mode.y, u_vssm.mode.x).rg, minVariance);
#endif
}

float shadowVisibility(SurfacePoint s) {
  SoftReceiver r;
  if (!softReceiver(s, u_vssm.params.z, u_vssm.params.w, r)) return 1.0;
  float t = r.coord.z;
  float minVariance = texelDepthVariance(r.view, s.ws, u_vssm.params.x);

  // (1) Blocker search.
  vec2 region = regionMeanVariance(r.view, r.coord.xy, softSearchRegionUv(s, r), minVariance, false);
  vec2 blocker = chebyshevBlockerDepth(region.x, region.y, t);
  if (1.0 - blocker.y > kUnoccludedLit) {
    recordNoBlocker(s);
    return 1.0;
  }
  float blockerDepth = blocker.x;
  recordPenumbra(s, r.view, blockerDepth, r.lightSize);

  // (2) Penumbra; (3) filtering over it.
  vec2 filtered = regionMeanVariance(r.view, r.coord.xy, softFilterRadiusUv(s, r, blockerDepth), minVariance, true);
  return reduceLightBleeding(chebyshevUpperBound(filtered.x, filtered.y, t), u_vssm.params.y);
}
