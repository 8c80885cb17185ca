#pragma once
// Soft-shadow geometry by similar triangles, for any shadow view (cascade): how large a region
// of the map can hold a receiver's blockers, and how wide its penumbra is, from the light's
// size and linear depths. Used by PCSS and by every technique that estimates a penumbra from an
// average blocker depth (VSSM, moment soft shadows).
//
// Light size as in Scene.h: spot = sphere radius R (m), sun = angular radius α (rad). Spot
// views are perspective: the light's centre is the view's origin, distances z are measured
// along its axis and a map uv spans extent·z metres at distance z. Sun views are orthographic:
// a map uv spans `extent` metres at every depth and the light is a cone of directions of half
// angle α. Depths in [0,1] are the maps' linear depths: z = near + depth·(far − near).
// Inputs: the receiver's world position, its view (cascade) and the light size; blocker depths
// are linear map depths. Outputs per map axis (xy): a view's extent may differ between x and y.
#include "common/shadow.glsl"

// Below this blocker fraction a search region holds no blocker worth a penumbra: fully lit
// (msm-soft, evsm-soft: the fraction their blocker estimate gives).
const float kMinBlockerFraction = 0.01;

// Distances are divided by at most this little (m): a point at the light's centre has no
// meaningful penumbra, and the guard keeps it finite.
const float kMinLightDistanceM = 1e-6;

// Distance (m) along the light's axis of linear depth `depth` in `view` (from the light's
// centre for a spot light, from an arbitrary origin behind the near plane for the sun).
float viewDistanceM(int view, float depth) {
  vec4 r = u_shadow.views[view].range;
  return r.x + depth * (r.y - r.x);
}

// The point of the receiver's ray toward the light's centre at distance zM along the axis.
vec3 pointOnLightRay(int view, vec3 wsReceiver, float zM) {
  float receiverM = lightDistance(view, wsReceiver);
  if (isPerspectiveView(view)) {
    vec3 light = u_frame.light.position.xyz;
    return light + (wsReceiver - light) * (zM / max(receiverM, kMinLightDistanceM));
  }
  return wsReceiver + toLight(wsReceiver) * (receiverM - zM);
}

// Radius (m) of the light's footprint in the plane at distance planeM along the axis, as seen
// from a receiver at receiverM: the cone from the receiver to the light cut by that plane.
//   spot: R · (z_r − z) / z_r      (similar triangles with apex at the receiver)
//   sun:  (z_r − z) · tan α        (the cone of the sun's directions, widening toward the light)
float lightFootprintRadiusM(int view, float receiverM, float planeM, float lightSize) {
  float gapM = max(receiverM - planeM, 0.0);
  return isPerspectiveView(view) ? lightSize * gapM / max(receiverM, kMinLightDistanceM) : gapM * tan(lightSize);
}

// The light's footprint (uv, per axis) in the plane at distance planeM along the axis, for a
// receiver at wsReceiver: every blocker at that distance or beyond that can occlude any part of
// the light lies within it (the footprint shrinks as the plane nears the receiver). The
// footprint is converted to uv at the point where the receiver's ray crosses that plane (exact
// for unwarped views; psm/tsm use the warp's local scale there).
vec2 lightFootprintRadiusUv(int view, vec3 wsReceiver, float planeM, float lightSize) {
  float receiverM = lightDistance(view, wsReceiver);
  float radiusM = lightFootprintRadiusM(view, receiverM, planeM, lightSize);
  return vec2(radiusM) / shadowMetresPerUv(view, pointOnLightRay(view, wsReceiver, planeM));
}

// Blocker search radius (uv, per axis) for a receiver at wsReceiver: the light's footprint on
// the view's near plane, the nearest place a blocker can be, so the region holds every texel
// that can occlude any part of the light. It widens with the light's size and with the
// receiver's distance from the near plane.
vec2 blockerSearchRadiusUv(int view, vec3 wsReceiver, float lightSize) {
  return lightFootprintRadiusUv(view, wsReceiver, u_shadow.views[view].range.x, lightSize);
}

// The smallest linear depth in the box of half-size radiusUv around uv in `view` of a map of
// mapSize texels per side, from a min-depth pyramid (render/MinDepthPyramid.h: a texel of level
// k covers 2^(k+1) map texels per side): at the level whose texels are at least as wide as the
// box, the at most 2x2 texels over it. Their union holds the box, so the result is never above
// the box's own minimum. A paged map: its pool's pyramid, page by page (pagedMinDepthOverBox).
float minDepthOverBox(sampler2DArray pyramid, int view, vec2 uv, vec2 radiusUv, float mapSize) {
#ifdef PN_VIRTUAL_PAGES
  return pagedMinDepthOverBox(pyramid, view, uv, radiusUv);
#else
  vec2 lo = (uv - radiusUv) * mapSize, hi = (uv + radiusUv) * mapSize;
  float width = max(max(hi.x - lo.x, hi.y - lo.y), 1.0);
  int level = clamp(int(ceil(log2(width))) - 1, 0, textureQueryLevels(pyramid) - 1);
  // Level k's size from level 0's (GL's mip sizes): textureSize with a non-constant level on a
  // sampler passed as an argument read 1×1 on llvmpipe (Mesa 22.3).
  ivec2 size = max(textureSize(pyramid, 0).xy >> level, ivec2(1));
  float texelsPerCell = exp2(float(level + 1));
  ivec2 a = clamp(ivec2(floor(lo / texelsPerCell)), ivec2(0), size - 1);
  ivec2 b = clamp(ivec2(floor(hi / texelsPerCell)), a, min(a + 1, size - 1));
  float m = 1.0;
  for (int y = a.y; y <= b.y; ++y)
    for (int x = a.x; x <= b.x; ++x) m = min(m, texelFetch(pyramid, ivec3(x, y, view), level).r);
  return m;
#endif
}

// The blocker search region made tight: the near plane's footprint (blockerSearchRadiusUv,
// capped at maxRadiusUv) is searched for its nearest surface, and no blocker can be nearer than
// that, so the light's footprint at that surface's distance holds every blocker (a large sun
// region in a big scene shrinks to what the blockers around the receiver need).
vec2 nearestBlockerSearchRadiusUv(sampler2DArray pyramid, int view, vec3 wsReceiver, vec2 uv, float lightSize,
                                  vec2 maxRadiusUv) {
  vec2 nearPlane = min(blockerSearchRadiusUv(view, wsReceiver, lightSize), maxRadiusUv);
  float nearestM = max(viewDistanceM(view, minDepthOverBox(pyramid, view, uv, nearPlane, shadowMapSize())), u_shadow.views[view].range.x);
  return min(lightFootprintRadiusUv(view, wsReceiver, nearestM, lightSize), nearPlane);
}

#ifdef PN_TIGHT_SEARCH  // set by shadows/TightSearch.cpp with the pyramid bound
layout(binding = PN_TEX_MIN_DEPTH) uniform sampler2DArray s_minDepth;  // the map's min-depth pyramid
#endif

// A searching filter's blocker search region (uv half-size per axis) in [minRadiusUv,
// maxRadiusUv]: from the nearest surface when the tight search is on, else the near plane's.
vec2 blockerSearchRegionUv(int view, vec3 wsReceiver, vec2 uv, float lightSize, vec2 minRadiusUv, vec2 maxRadiusUv) {
#ifdef PN_TIGHT_SEARCH
  return max(nearestBlockerSearchRadiusUv(s_minDepth, view, wsReceiver, uv, lightSize, maxRadiusUv), minRadiusUv);
#else
  return clamp(blockerSearchRadiusUv(view, wsReceiver, lightSize), minRadiusUv, maxRadiusUv);
#endif
}

// Penumbra width (m) on the receiver for blockers at linear depth `blockerDepth`:
//   spot: w = (z_r − z_b) · w_light / z_b with w_light = 2R (the PCSS estimate),
//   sun:  w = (z_r − z_b) · 2 tan α (the same with the light at infinity).
float penumbraWidthM(int view, float receiverDepth, float blockerDepth, float lightSize) {
  float receiverM = viewDistanceM(view, receiverDepth);
  float blockerM = viewDistanceM(view, blockerDepth);
  float gapM = max(receiverM - blockerM, 0.0);
  return isPerspectiveView(view) ? gapM * 2.0 * lightSize / max(blockerM, kMinLightDistanceM) : gapM * 2.0 * tan(lightSize);
}

// The same penumbra as a width in map uv (per axis) at the receiver: the diameter of the
// light's footprint in the blockers' plane, i.e. the kernel that averages the right blockers.
// (A perspective map's uv spans z metres per unit at distance z, so w at the receiver over the
// receiver's span equals the footprint's diameter at the blockers over their span.)
vec2 penumbraWidthUv(int view, vec3 wsReceiver, float blockerDepth, float lightSize) {
  float widthM = penumbraWidthM(view, lightDepth(view, wsReceiver), blockerDepth, lightSize);
  return vec2(widthM) / shadowMetresPerUv(view, wsReceiver);
}
