// evsm: exponential variance shadow maps (Lauritzen & McCool 2008). The map stores the moments of
// an exponential warp of linear light depth (exp_warp.shared.h): (p, p²) with p = exp(c+ (2z − 1)),
// and with 4 components also (n, n²) with n = −exp(−c− (2z − 1)); 32- or 16-bit floats, the
// exponents clamped so that neither overflows. They are prefiltered like vsm's (mip chain,
// trilinear taps over the pixel footprint widened to evsm.filterTexels), and V is Chebyshev's
// bound on each warp, the smaller of the two (common/exp_warp.glsl). The warp crushes occluders
// far in front of the receiver toward one value, so the variance two occluders at different
// depths create no longer lets light through: vsm's light bleeding falls by about e^(-2c·gap).
// What remains: bleeding where the receiver is within ~1/(2c) of the nearer occluder's depth, and
// vsm's edge shape (a fixed-width filter, not a penumbra).
#include "common/exp_warp.glsl"
#include "common/footprint.glsl"
#include "techniques/filters/evsm.shared.h"

layout(std140, binding = PN_UBO_FILTER) uniform EvsmBlock { EvsmUniforms u_evsm; };
layout(binding = PN_TEX_FILTER0) uniform sampler2DArray s_moments;

float shadowVisibility(SurfacePoint s) {
  int view = selectShadowView(s.ws);
  vec3 coord = shadowCoord(view, s.ws);
  if (!insideMap(coord)) return 1.0;
  vec4 moments = momentsOverFootprint(s_moments, view, s, coord.xy, u_evsm.params.z, u_evsm.mode.x, u_evsm.mode.y != 0);
  float v = evsmVisibility(moments, u_evsm.warp.xy, coord.z, texelDepthVariance(view, s.ws, u_evsm.params.x),
                           u_evsm.warp.z, u_evsm.warp.w > 2.5);
  return reduceLightBleeding(v, u_evsm.params.y);
}
