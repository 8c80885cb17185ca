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
    vec3 light = u_frame.lightPosition.xyz;
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

// Blocker search radius (uv, per axis) for a receiver at wsReceiver: the light's footprint on
// the view's near plane, the nearest place a blocker can be, so the region holds every texel
// that can occlude any part of the light. It widens with the light's size and with the
// receiver's distance from the near plane. The footprint is converted to uv at the point where
// the receiver's ray crosses the near plane (exact for unwarped views; psm/tsm use the warp's
// local scale there).
vec2 blockerSearchRadiusUv(int view, vec3 wsReceiver, float lightSize) {
  float nearM = u_shadow.views[view].range.x;
  float receiverM = lightDistance(view, wsReceiver);
  float radiusM = lightFootprintRadiusM(view, receiverM, nearM, lightSize);
  return vec2(radiusM) / shadowMetresPerUv(view, pointOnLightRay(view, wsReceiver, nearM));
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
