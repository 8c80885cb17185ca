// pcf as a technique folder: percentage-closer filtering (Reeves, Salesin & Cook 1987). Many
// depth comparisons around the receiver's texel are averaged, over a box grid or a Poisson disk
// turned per pixel, of a fixed radius in texels. The same code as Penumbra's built-in pcf, so the
// two give the same bits (tests/cli/TechniqueFolderCliTest.cpp).

// Each tap through the hardware's 2x2 comparison: common/depth_compare.glsl then takes the map
// as a sampler2DArrayShadow, which pn_depthCompareMap is.
#if PARAM_hardwareCompare == PARAM_hardwareCompare_on
#define PN_HARDWARE_COMPARE
#define SHADOW_MAP pn_depthCompareMap
#else
#define SHADOW_MAP pn_depthMap
#endif

#include "common/technique.glsl"
#include "common/depth_compare.glsl"

float shadowVisibility(SurfacePoint s) {
  int view = selectShadowView(s.ws);
  vec3 coord = shadowCoord(view, s.ws);
  if (!insideMap(coord)) return 1.0;
  // A turned kernel reaches √2 × its radius: it stays inside the map.
  float radiusTexels = min(PARAM_radiusTexels, 0.5 * (shadowMapSize() - 1.0) / sqrt(2.0));
  vec2 radiusUv = vec2(radiusTexels / shadowMapSize());
  // The radius is in texels of view 0 (the finest cascade), held in metres across the others; a
  // point light's cube faces are no cascades.
  if (view != 0 && !isPointLight()) {
    radiusUv *= shadowMetresPerUv(0, s.ws) / shadowMetresPerUv(view, s.ws);
    radiusTexels = max(radiusUv.x, radiusUv.y) * shadowMapSize();
  }
  ComparisonReceiver r = comparisonReceiver(view, s, coord, PARAM_constantBias, PARAM_slopeBias, PARAM_planeBiasTexels);
#if PARAM_kernel == PARAM_kernel_box
  return percentageCloserBox(SHADOW_MAP, r, radiusUv, int(ceil(radiusTexels)));
#else
  return percentageCloserPoisson(SHADOW_MAP, r, radiusUv, PARAM_samples, pixelRotation(s.pixel, samplingFrame()));
#endif
}
