// msm: moment shadow maps (Peters & Klein 2015). The map stores four moments (z, z^2, z^3, z^4)
// of linear light depth — as 32-bit floats, or as 16-bit UNORM in the paper's optimised basis —
// filtered like vsm's two (mip chain, trilinear taps over the pixel footprint widened to
// msm.filterTexels). Visibility is 1 − the Hamburger 4MSM bound: the smallest fraction of depth in
// front of the receiver that any distribution with these moments can have (common/moments.glsl).
// Four moments describe two overlapping occluders at different depths, so far less light bleeds
// than with vsm; what remains is the bound's slack, and the moment bias α lightens shadows a
// little. Costs: twice vsm's storage at 32 bits, and a 3x3 solve and a quadratic per lookup.
#include "common/footprint.glsl"
#include "common/moments.glsl"
#include "shadows/filters/msm.shared.h"

layout(std140, binding = PN_UBO_FILTER) uniform MsmBlock { MsmUniforms u_msm; };
layout(binding = PN_TEX_FILTER0) uniform sampler2DArray s_moments;

float shadowVisibility(SurfacePoint s) {
  int view = selectShadowView(s.ws);
  vec3 coord = shadowCoord(view, s.ws);
  if (!insideMap(coord)) return 1.0;
  vec4 b = momentsOverFootprint(s_moments, view, s, coord.xy, u_msm.params.z, u_msm.mode.x, PN_FOOTPRINT_PIXEL != 0);
  if (PN_MSM_QUANTIZED != 0) b = dequantizeMoments16(b);
  float alpha = floorMomentBias(texelDepthVariance(view, s.ws, u_msm.params.x), PN_MSM_QUANTIZED != 0);
  return 1.0 - hamburgerShadowIntensity(biasMoments(b, alpha), coord.z - u_msm.params.y);
}
