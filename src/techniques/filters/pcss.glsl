// pcss: percentage-closer soft shadows (Fernando 2005). (1) Blocker search: over the region of
// the map that the light subtends from the receiver (similar triangles onto the near plane),
// average the depths of the texels closer than the receiver. (2) Penumbra estimate:
// w = (d_receiver − d_blocker) · w_light / d_blocker (common/penumbra.glsl; the sun's version
// uses its angular radius). (3) PCF with a kernel of that width. Linear light depth, per view,
// so cascades with different extents and ranges work alike; the light size is the scene's.
// Artifacts: one average blocker depth per receiver, so overlapping blockers at different
// depths get one penumbra; noise from the rotated Poisson taps; cost grows with the taps only.
#include "common/depth_compare.glsl"
#include "common/penumbra.glsl"
#include "common/penumbra_debug.glsl"
#include "techniques/filters/pcss.shared.h"

layout(std140, binding = PN_UBO_FILTER) uniform PcssBlock { PcssUniforms u_pcss; };
layout(binding = PN_TEX_FILTER0) uniform sampler2DArray s_depthMap;       // raw depths: blocker search
layout(binding = PN_TEX_FILTER1) uniform PN_COMPARISON_MAP s_compareMap;  // the same map: filtering

// Tap i of `taps` in the chosen pattern, in the unit disk (Poisson: turned by patternRotation) or
// square (box).
vec2 patternTap(int i, int taps) {
  return PN_PCSS_PATTERN == PN_KERNEL_BOX ? boxTap(i, boxHalfSideForTaps(taps)) : kPoissonDisk[i];
}
mat2 patternRotation(mat2 rotation) { return PN_PCSS_PATTERN == PN_KERNEL_BOX ? mat2(1.0) : rotation; }
int patternTapCount(int taps) {
  return PN_PCSS_PATTERN == PN_KERNEL_BOX ? boxTapCount(boxHalfSideForTaps(taps)) : clamp(taps, 1, kPoissonDiskSize);
}

// Step (1): the mean linear depth of the texels in ±radiusUv that are closer to the light than
// the receiver (the same biased test as the filter, so the receiver never blocks itself).
// False when there is none: the receiver is fully lit.
bool averageBlockerDepth(ComparisonReceiver r, vec2 radiusUv, mat2 rotation, out float blockerDepth) {
  int taps = patternTapCount(PN_PCSS_BLOCKER_SAMPLES);
  TapKernel k = tapKernel(r, radiusUv, patternRotation(rotation), mapTexels(s_depthMap));
  float sum = 0.0;
  int blockers = 0;
  for (int i = 0; i < taps; ++i) {
    vec2 unit = patternTap(i, PN_PCSS_BLOCKER_SAMPLES);
    float stored = storedDepth(s_depthMap, k, tapTexel(k, unit));
    if (compareDepth(tapDepth(k, unit), stored) == 0.0) {
      sum += stored;
      ++blockers;
    }
  }
  blockerDepth = blockers > 0 ? sum / float(blockers) : r.depth;
  return blockers > 0;
}

float shadowVisibility(SurfacePoint s) {
  int view = selectShadowView(s.ws);
  vec3 coord = shadowCoord(view, s.ws);
  if (!insideViewMap(view, coord)) {
    recordNoBlocker(s);
    return 1.0;
  }
  float lightSize = u_frame.light.radiance.w;
  ComparisonReceiver r = comparisonReceiver(view, s, coord, u_pcss.params.x, u_pcss.params.y, u_pcss.bias.x);
  // No crease margin (common/depth_compare.glsl): the blocker search reaches many texels, where it
  // would hide real casters (room's table top above the wall it shadows), and the filter's kernel
  // is sized from blockers whose depths do not bound the nearest one (with it, night's spots lost
  // 0.2 % of their umbra). A kernel sized from a crease's own wall is narrow: the strip stays thin.
  r.creasePerTexel = 0.0;
  float texelUv = 1.0 / shadowMapSize();
  vec2 maxRadiusUv = vec2(u_pcss.params.w * texelUv);
  mat2 rotation = pixelRotation(s.pixel, samplingFrame());

  vec2 searchUv = blockerSearchRegionUv(view, s.ws, coord.xy, lightSize, vec2(0.0), maxRadiusUv);
  float blockerDepth;
  if (!averageBlockerDepth(r, searchUv, rotation, blockerDepth)) {
    recordNoBlocker(s);
    return 1.0;
  }
  recordPenumbra(s, view, blockerDepth, lightSize);

  vec2 radiusUv = clamp(0.5 * penumbraWidthUv(view, s.ws, blockerDepth, lightSize),
                        vec2(u_pcss.params.z * texelUv), maxRadiusUv);
  if (PN_PCSS_PATTERN == PN_KERNEL_BOX)
    return percentageCloserBox(s_compareMap, r, radiusUv, boxHalfSideForTaps(PN_PCSS_FILTER_SAMPLES));
  return percentageCloserPoisson(s_compareMap, r, radiusUv, PN_PCSS_FILTER_SAMPLES, rotation);
}
