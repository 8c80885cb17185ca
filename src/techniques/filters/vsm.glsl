// vsm: variance shadow maps (Donnelly & Lauritzen 2006). The map stores (z, z^2) of linear light
// depth in 32-bit floats, so it can be filtered like a colour texture: a mip chain sampled
// trilinearly, with anisotropic taps, over the pixel's footprint (widened to vsm.filterTexels) gives
// the mean and variance of the depths under it, and Chebyshev's one-tailed bound gives the lit
// fraction. Exact for one planar occluder over a planar receiver; where occluders at different
// depths overlap in the footprint the bound is too bright ("light bleeding"), which the optional
// reduction trades against darker penumbrae.
#include "common/chebyshev.glsl"
#include "common/footprint.glsl"
#include "techniques/filters/vsm.shared.h"

layout(std140, binding = PN_UBO_FILTER) uniform VsmBlock { VsmUniforms u_vsm; };
layout(binding = PN_TEX_FILTER0) uniform sampler2DArray s_moments;

float shadowVisibility(SurfacePoint s) {
  int view = selectShadowView(s.ws);
  vec3 coord = shadowCoord(view, s.ws);
  if (!insideMap(coord)) return 1.0;
  vec2 moments = momentsOverFootprint(s_moments, view, s, coord.xy, u_vsm.params.z, u_vsm.mode.x, PN_FOOTPRINT_PIXEL != 0).rg;
  vec2 mv = meanVariance(moments, texelDepthVariance(view, s.ws, u_vsm.params.x));
  return reduceLightBleeding(chebyshevUpperBound(mv.x, mv.y, coord.z), u_vsm.params.y);
}
