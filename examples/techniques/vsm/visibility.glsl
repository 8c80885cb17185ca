// vsm as a technique folder: variance shadow maps (Donnelly & Lauritzen 2006). The map stores
// (z, z²) of linear light depth ("moments" in technique.json), filtered like a colour texture
// through its mip chain ("mips") over the pixel's footprint; Chebyshev's one-tailed bound on the
// mean and variance gives the lit fraction. The same code as Penumbra's built-in vsm, so the two
// give the same bits (tests/cli/TechniqueFolderCliTest.cpp).
#include "common/technique.glsl"
#include "common/chebyshev.glsl"
#include "common/footprint.glsl"

float shadowVisibility(SurfacePoint s) {
  int view = selectShadowView(s.ws);
  vec3 coord = shadowCoord(view, s.ws);
  if (!insideMap(coord)) return 1.0;
  vec2 moments = momentsOverFootprint(pn_moments, view, s, coord.xy, PARAM_filterTexels, PARAM_anisotropy,
                                      PARAM_footprint == PARAM_footprint_on).rg;
  vec2 mv = meanVariance(moments, texelDepthVariance(view, s.ws, PARAM_minVariance));
  return reduceLightBleeding(chebyshevUpperBound(mv.x, mv.y, coord.z), PARAM_bleedReduction);
}
