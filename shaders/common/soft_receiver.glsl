#pragma once
// The receiver of an O(1) soft filter (vssm, evsm-soft, msm-soft): its view, its map coordinate
// moved inside the map (common/depth_compare.glsl: coordInsideMap, for boxes around it), the
// light's size and the filter's radius bounds in uv; and the regions of the three steps they
// share: (1) the blocker search's, (2)-(3) the penumbra-sized filter's. Outside the map there is
// nothing to search: it is lit, and the filters that record their penumbra estimate (vssm,
// evsm-soft) say so in the debug record (common/penumbra_debug.glsl).
#include "common/depth_compare.glsl"
#include "common/penumbra_debug.glsl"

struct SoftReceiver {
  int view;
  vec3 coord;        // map uv, linear depth t
  float lightSize;   // Scene.h's light size (spot: radius m; sun: angular radius rad)
  vec2 minRadiusUv;  // the search and filter radius bounds, per map axis
  vec2 maxRadiusUv;
};

// False where s lies outside its view's map (then V = 1). Records nothing: for a filter that keeps
// no penumbra record (msm-soft).
bool softReceiverNoRecord(SurfacePoint s, float minRadiusTexels, float maxRadiusTexels, out SoftReceiver r) {
  r.view = selectShadowView(s.ws);
  r.coord = shadowCoord(r.view, s.ws);
  if (!insideMap(r.coord)) return false;
  r.coord = coordInsideMap(r.view, s, r.coord, ivec2(shadowMapSize()));
  r.lightSize = u_frame.light.radiance.w;
  float texelUv = 1.0 / shadowMapSize();
  r.minRadiusUv = vec2(minRadiusTexels * texelUv);
  r.maxRadiusUv = vec2(maxRadiusTexels * texelUv);
  return true;
}

// False where s lies outside its view's map (then V = 1), which the debug record says.
bool softReceiver(SurfacePoint s, float minRadiusTexels, float maxRadiusTexels, out SoftReceiver r) {
  if (softReceiverNoRecord(s, minRadiusTexels, maxRadiusTexels, r)) return true;
  recordNoBlocker(s);
  return false;
}

// Step (1)'s region: the PCSS blocker search's half-size around r (common/penumbra.glsl), within
// the radius bounds.
vec2 softSearchRegionUv(SurfacePoint s, SoftReceiver r) {
  return blockerSearchRegionUv(r.view, s.ws, r.coord.xy, r.lightSize, r.minRadiusUv, r.maxRadiusUv);
}

// Steps (2) and (3): the filter's half-size for blockers at linear depth blockerDepth, half the
// penumbra's width by similar triangles, within the radius bounds.
vec2 softFilterRadiusUv(SurfacePoint s, SoftReceiver r, float blockerDepth) {
  return clamp(0.5 * penumbraWidthUv(r.view, s.ws, blockerDepth, r.lightSize), r.minRadiusUv, r.maxRadiusUv);
}
