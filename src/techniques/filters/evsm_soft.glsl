// evsm-soft: exponential variance soft shadows. vssm's three O(1) steps on evsm's four warped
// moments (exp_warp.shared.h), read from their mip chain as boxes of sub-boxes
// (common/footprint.glsl: boxMeanFromMips): (1) blocker search over the PCSS search region
// (common/penumbra.glsl): Chebyshev on the negative warp gives the unoccluded fraction and, the
// unoccluded part taken at the receiver's depth, the blockers' warp and so their depth
// (common/exp_warp.glsl: evsmBlockerDepth); (2) penumbra width from it by similar triangles, as
// PCSS; (3) V = evsm's bound (the smaller of the two warps' Chebyshev bounds) over the
// penumbra-sized box. Why mips and not a summed-area table: a table sums values across the whole
// map with an absolute precision, and at these exponents the squared warps of the far floor and
// of a receiver near the light differ by up to e^80 (docs/evsm-soft.md). Linear light depth per
// view. Artifacts: evsm's
// (bleeding within ~1/(2c+) of an occluder) and the mip boxes' blur (vssm.md, source=mip); the
// negative warp's mean leans toward the nearest blockers, so penumbrae of stacked blockers widen.
#include "common/exp_warp.glsl"
#include "common/footprint.glsl"
#include "common/soft_receiver.glsl"
#include "techniques/filters/evsm_soft.shared.h"

layout(std140, binding = PN_UBO_FILTER) uniform EvsmSoftBlock { EvsmSoftUniforms u_evsmSoft; };
layout(binding = PN_TEX_FILTER0) uniform sampler2DArray s_moments;

vec4 regionMoments(int view, vec2 uv, vec2 radiusUv) {
  return boxMeanFromMips(s_moments, view, uv, radiusUv, u_evsmSoft.mode.y, u_evsmSoft.mode.x);
}

float shadowVisibility(SurfacePoint s) {
  SoftReceiver r;
  if (!softReceiver(s, u_evsmSoft.params.z, u_evsmSoft.params.w, r)) return 1.0;
  float t = r.coord.z;
  float depthVariance = texelDepthVariance(r.view, s.ws, u_evsmSoft.params.x);
  vec2 c = u_evsmSoft.warp.xy;
  float storageFloor = u_evsmSoft.warp.z;

  // (1) Blocker search.
  vec4 region = regionMoments(r.view, r.coord.xy, softSearchRegionUv(s, r));
  vec2 blocker = evsmBlockerDepth(region.zw, t, WarpFloor(c.y, depthVariance, storageFloor));
  if (blocker.y < kMinBlockerFraction) {
    recordNoBlocker(s);
    return 1.0;
  }
  recordPenumbra(s, r.view, blocker.x, r.lightSize);

  // (2) Penumbra; (3) filtering over it.
  float v = evsmVisibility(regionMoments(r.view, r.coord.xy, softFilterRadiusUv(s, r, blocker.x)), c, t, depthVariance,
                           storageFloor, true);
  return reduceLightBleeding(v, u_evsmSoft.params.y);
}
