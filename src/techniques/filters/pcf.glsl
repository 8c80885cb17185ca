// pcf: percentage-closer filtering (Reeves, Salesin & Cook 1987). Around the receiver's texel,
// many depth comparisons are made and their 0/1 results averaged, giving a fractional V that
// anti-aliases the shadow's edge. The kernel is a box grid or a Poisson disk rotated per pixel,
// of a fixed radius in texels (of the finest cascade; held in metres across cascades): the edge is equally soft everywhere, so this is not a physical
// penumbra (pcss sizes the kernel from the light). Linear light depth, spot and sun alike.
// Artifacts: banding (box) or noise (Poisson) at large radii; a wide kernel on a tilted
// receiver needs a bias growing with tap distance, which detaches contact shadows a little.
#include "common/depth_compare.glsl"
#include "techniques/filters/pcf.shared.h"

layout(std140, binding = PN_UBO_FILTER) uniform PcfBlock { PcfUniforms u_pcf; };
layout(binding = PN_TEX_FILTER0) uniform PN_COMPARISON_MAP s_shadowMap;

float shadowVisibility(SurfacePoint s) {
  int view = selectShadowView(s.ws);
  vec3 coord = shadowCoord(view, s.ws);
  if (!insideViewMap(view, coord)) return 1.0;
  // The radius is in texels of view 0 (the finest cascade) and held in metres across the other
  // views, so the blur does not widen at every cascade split (one view: the ratio is 1). A point
  // light's cube faces are no cascades: each has the same texels at a given distance, and view 0
  // seen from another face's point can lie behind the light (a negative ratio).
  float radiusTexels = u_pcf.params.x;
  vec2 radiusUv = vec2(radiusTexels / shadowMapSize());
  if (view != 0 && !isPointLight()) {
    radiusUv *= shadowMetresPerUv(0, s.ws) / shadowMetresPerUv(view, s.ws);
    radiusTexels = max(radiusUv.x, radiusUv.y) * shadowMapSize();
  }
  ComparisonReceiver r = comparisonReceiver(view, s, coord, u_pcf.params.y, u_pcf.params.z, u_pcf.params.w);
#if PN_PCF_KERNEL == PN_KERNEL_BOX
#ifdef PN_PCF_BOX_HALF_SIDE
  return percentageCloserBox(s_shadowMap, r, radiusUv, PN_PCF_BOX_HALF_SIDE);
#else
  return percentageCloserBox(s_shadowMap, r, radiusUv, int(ceil(radiusTexels)));
#endif
#else
  return percentageCloserPoisson(s_shadowMap, r, radiusUv, PN_PCF_SAMPLES, pixelRotation(s.pixel, samplingFrame()));
#endif
}
