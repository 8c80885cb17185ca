// evsm-soft: exponential variance soft shadows. vssm's three O(1) steps on evsm's four warped
// moments (exp_warp.shared.h), read from their mip chain as boxes of sub-boxes
// (common/footprint.glsl: boxMeanFromMips): (1) blocker search over the PCSS search region
// (common/penumbra.glsl): Chebyshev on the negative warp gives the unoccluded fraction and, the
// unoccluded part taken at the receiver's depth, the blockers' warp and so their depth
// (common/exp_warp.glsl: evsmBlockerDepth); (2) penumbra width from it by similar triangles, as
// PCSS; (3) V = evsm's bound (the smaller of the two warps' Chebyshev bounds) over the
// penumbra-sized box. Why mips and not a summed-area table: a table sums values across the whole
// map, and at these exponents the warps of the far floor and of a receiver near the light differ
// by e^80, more than 64 bits hold (docs/evsm.md). Linear light depth per view. Artifacts: evsm's
// (bleeding within ~1/(2c+) of an occluder) and the mip boxes' blur (vssm.md, source=mip); the
// negative warp's mean leans toward the nearest blockers, so penumbrae of stacked blockers widen.
#include "common/depth_compare.glsl"
#include "common/exp_warp.glsl"
#include "common/footprint.glsl"
#include "common/penumbra.glsl"
#include "common/penumbra_debug.glsl"
#include "shadows/filters/evsm_soft.shared.h"

layout(std140, binding = PN_UBO_FILTER) uniform EvsmSoftBlock { EvsmSoftUniforms u_evsmSoft; };
layout(binding = PN_TEX_FILTER0) uniform sampler2DArray s_moments;

vec4 regionMoments(int view, vec2 uv, vec2 radiusUv) {
  return boxMeanFromMips(s_moments, view, uv, radiusUv, u_evsmSoft.mode.y, u_evsmSoft.mode.x);
}

float shadowVisibility(SurfacePoint s) {
  int view = selectShadowView(s.ws);
  vec3 coord = shadowCoord(view, s.ws);
  if (!insideMap(coord)) {
    recordNoBlocker(s);
    return 1.0;
  }
  coord = coordInsideMap(view, s, coord, ivec2(shadowMapSize()));
  float lightSize = u_frame.lightRadiance.w;
  float t = coord.z;
  float texelUv = 1.0 / shadowMapSize();
  vec2 minRadiusUv = vec2(u_evsmSoft.params.z * texelUv), maxRadiusUv = vec2(u_evsmSoft.params.w * texelUv);
  float depthVariance = texelDepthVariance(view, s.ws, u_evsmSoft.params.x);
  vec2 c = u_evsmSoft.warp.xy;
  float storageFloor = u_evsmSoft.warp.z;

  // (1) Blocker search.
  vec2 searchUv = blockerSearchRegionUv(view, s.ws, coord.xy, lightSize, minRadiusUv, maxRadiusUv);
  vec2 blocker = evsmBlockerDepth(regionMoments(view, coord.xy, searchUv).zw, t, WarpFloor(c.y, depthVariance, storageFloor));
  if (blocker.y < kMinBlockerFraction) {
    recordNoBlocker(s);
    return 1.0;
  }
  recordPenumbra(s, view, blocker.x, lightSize);

  // (2) Penumbra; (3) filtering over it.
  vec2 radiusUv = clamp(0.5 * penumbraWidthUv(view, s.ws, blocker.x, lightSize), minRadiusUv, maxRadiusUv);
  float v = evsmVisibility(regionMoments(view, coord.xy, radiusUv), c, t, depthVariance, storageFloor, true);
  return reduceLightBleeding(v, u_evsmSoft.params.y);
}
