// esm: exponential shadow maps (Annen et al. 2008). The map stores one warp of linear light
// depth, p = exp(c (2z − 1)) in 32-bit floats (exp_warp.shared.h), prefiltered like vsm's moments
// (mip chain, trilinear taps over the pixel footprint widened to esm.filterTexels). Since the
// test exp(2c (z − t)) factors into p(z) / p(t), filtering p filters the test itself, and
// V = min(E[p] / p(t), 1) (common/exp_warp.glsl). One channel, no variance, no bleeding between
// occluders; but an occluder just in front of the receiver (a contact) weighs nearly 1, so
// shadows fade where casters meet receivers, and the approximation needs c large, which the
// storage caps (c <= 86 in float32).
#include "common/exp_warp.glsl"
#include "common/footprint.glsl"
#include "techniques/filters/esm.shared.h"

layout(std140, binding = PN_UBO_FILTER) uniform EsmBlock { EsmUniforms u_esm; };
layout(binding = PN_TEX_FILTER0) uniform sampler2DArray s_warp;

float shadowVisibility(SurfacePoint s) {
  int view = selectShadowView(s.ws);
  vec3 coord = shadowCoord(view, s.ws);
  if (!insideMap(coord)) return 1.0;
  float warp = momentsOverFootprint(s_warp, view, s, coord.xy, u_esm.params.y, u_esm.mode.x, u_esm.mode.y != 0).r;
  return esmVisibility(warp, u_esm.params.x, coord.z);
}
