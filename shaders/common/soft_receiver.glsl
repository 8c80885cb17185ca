#pragma once
// The receiver of an O(1) soft filter that records its penumbra estimate (vssm, evsm-soft): its
// view, its map coordinate moved inside the map (common/depth_compare.glsl: coordInsideMap, for
// boxes around it), the light's size and the filter's radius bounds in uv. Outside the map there
// is nothing to search: the debug record says so (common/penumbra_debug.glsl) and it is lit.
#include "common/depth_compare.glsl"
#include "common/penumbra_debug.glsl"

struct SoftReceiver {
  int view;
  vec3 coord;        // map uv, linear depth t
  float lightSize;   // Scene.h's light size (spot: radius m; sun: angular radius rad)
  vec2 minRadiusUv;  // the search and filter radius bounds, per map axis
  vec2 maxRadiusUv;
};

// False where s lies outside its view's map (then V = 1).
bool softReceiver(SurfacePoint s, float minRadiusTexels, float maxRadiusTexels, out SoftReceiver r) {
  r.view = selectShadowView(s.ws);
  r.coord = shadowCoord(r.view, s.ws);
  if (!insideMap(r.coord)) {
    recordNoBlocker(s);
    return false;
  }
  r.coord = coordInsideMap(r.view, s, r.coord, ivec2(shadowMapSize()));
  r.lightSize = u_frame.light.radiance.w;
  float texelUv = 1.0 / shadowMapSize();
  r.minRadiusUv = vec2(minRadiusTexels * texelUv);
  r.maxRadiusUv = vec2(maxRadiusTexels * texelUv);
  return true;
}
