#pragma once
// A screen pixel's footprint in a shadow map, for prefiltered lookups (mip chains). The same
// filter code runs as a fragment shader over the screen and as a compute shader over a list of
// points (passes/visibility.glsl), where there are no neighbouring invocations to take derivatives
// from (and over the screen, a neighbour across a silhouette is another surface): instead the
// camera rays through the neighbouring pixels are intersected with the surface's tangent plane
// (ray differentials) and the offsets are projected into the map. Exact for planar receivers;
// assumes a symmetric perspective projection (Camera::clipFromView) or, with
// PN_CAMERA_ORTHOGRAPHIC, an orthographic one.
#include "common/visibility.glsl"

// A pixel's footprint is never allowed to exceed this many texels: at grazing angles the ray
// differential grows without bound and would average the whole map into one value.
const float kMaxFootprintTexels = 64.0;

// World-space direction of the camera ray through normalised device coordinates ndc.
vec3 cameraRayDirection(vec2 ndc) {
  mat4 m = u_frame.clipFromWorld;
  // clipFromWorld = P·V with P symmetric: its rows 0 and 1 are P00·(row 0 of V) and P11·(row 1 of
  // V), and V's rotation rows are unit vectors, so their xyz lengths are P00 and P11.
  float p00 = length(vec3(m[0][0], m[1][0], m[2][0]));
  float p11 = length(vec3(m[0][1], m[1][1], m[2][1]));
  return transpose(mat3(u_frame.viewFromWorld)) * vec3(ndc.x / p00, ndc.y / p11, -1.0);
}

// Where the ray through ndc meets the plane through ws with normal n (ws itself if it misses).
vec3 hitTangentPlane(vec2 ndc, vec3 ws, vec3 n) {
#ifdef PN_CAMERA_ORTHOGRAPHIC
  // Parallel rays along the view axis, each from its point on the clip space's z = 0 plane.
  vec4 o4 = u_frame.worldFromClip * vec4(ndc, 0.0, 1.0);
  vec3 o = o4.xyz / o4.w;
  vec3 d = cameraForward();
  float dn = dot(d, n);
  return abs(dn) > 1e-6 ? o + (dot(ws - o, n) / dn) * d : ws;
#else
  vec3 o = u_frame.cameraPosition.xyz;
  vec3 d = cameraRayDirection(ndc);
  float dn = dot(d, n);
  float t = abs(dn) > 1e-6 ? dot(ws - o, n) / dn : -1.0;
  return t > 0.0 ? o + t * d : ws;
#endif
}

// Shortens each axis of a footprint in a map of mapSize texels to kMaxFootprintTexels.
void limitFootprint(float mapSize, inout vec2 dUVdx, inout vec2 dUVdy) {
  float maxUV = kMaxFootprintTexels / mapSize;
  if (length(dUVdx) > maxUV) dUVdx *= maxUV / length(dUVdx);
  if (length(dUVdy) > maxUV) dUVdy *= maxUV / length(dUVdy);
}

// Map-uv offsets of one pixel step in screen x and y at s, in view `view`; `uv` is s's map uv.
// The steps start from s's own projection in the current camera, not from s.pixel: a point
// list (Renderer::visibilityAt) keeps the pixel a point was first seen at while the camera moves,
// and rays through that pixel miss the point, which turned the camera's move into a footprint.
void shadowFootprint(int view, SurfacePoint s, vec2 uv, out vec2 dUVdx, out vec2 dUVdy) {
  vec2 screen = vec2(u_frame.screen.xy);
  vec4 clip = u_frame.clipFromWorld * vec4(s.ws, 1.0);
  vec2 ndc = clip.xy / clip.w;
  vec2 stepNdc = 2.0 / screen;
  dUVdx = shadowCoord(view, hitTangentPlane(ndc + vec2(stepNdc.x, 0.0), s.ws, s.geoNormal)).xy - uv;
  dUVdy = shadowCoord(view, hitTangentPlane(ndc + vec2(0.0, stepNdc.y), s.ws, s.geoNormal)).xy - uv;
  limitFootprint(shadowMapSize(), dUVdx, dUVdy);
}

// Widens a footprint so that each axis spans at least minUV (a minimum filter width: the
// softness of a filtered hard shadow). A degenerate axis takes the map's own axis.
void widenFootprint(float minUV, inout vec2 dUVdx, inout vec2 dUVdy) {
  float lx = length(dUVdx), ly = length(dUVdy);
  dUVdx = lx > 1e-12 ? dUVdx * max(1.0, minUV / lx) : vec2(minUV, 0.0);
  dUVdy = ly > 1e-12 ? dUVdy * max(1.0, minUV / ly) : vec2(0.0, minUV);
}

// Filtered lookup over the footprint (dUVdx, dUVdy): anisotropic filtering done in the shader, as
// up to maxTaps trilinear taps spread along the footprint's long axis, each with the short axis's
// width. The same on every driver; with GL_TEXTURE_MAX_ANISOTROPY > 1, Mesa llvmpipe 22.3
// ignores textureGrad's explicit gradients (it filtered a step edge as if the footprint were one
// texel at any width), so hardware anisotropy cannot be used here (docs/vsm.md).
vec4 textureFootprint(sampler2DArray s, vec3 uvLayer, vec2 dUVdx, vec2 dUVdy, int maxTaps) {
  float lx = length(dUVdx), ly = length(dUVdy);
  vec2 major = lx >= ly ? dUVdx : dUVdy;
  vec2 minor = lx >= ly ? dUVdy : dUVdx;
  float ratio = max(lx, ly) / max(min(lx, ly), 1e-12);
  int taps = clamp(int(ceil(ratio - 1e-3)), 1, maxTaps);
  vec2 tapGrad = major / float(taps);
  vec4 sum = vec4(0.0);
  for (int i = 0; i < taps; ++i) {
    float offset = (float(i) + 0.5) / float(taps) - 0.5;
    sum += textureGrad(s, uvLayer + vec3(major * offset, 0.0), tapGrad, minor);
  }
  return sum / float(taps);
}

// The prefiltered moments under s's pixel footprint in `view` (s's map uv `uv`), the footprint
// widened to at least minTexels on each axis: what vsm and msm read from their mip chains.
// `usePixel` false: the pixel's footprint is ignored and the box is minTexels wide in map space,
// the same for every camera (as pcf's kernel).
vec4 momentsOverFootprint(sampler2DArray moments, int view, SurfacePoint s, vec2 uv, float minTexels, int maxTaps,
                          bool usePixel) {
  vec2 dx = vec2(0.0), dy = vec2(0.0);
  if (usePixel) shadowFootprint(view, s, uv, dx, dy);
  widenFootprint(minTexels / shadowMapSize(), dx, dy);
  return textureFootprint(moments, vec3(uv, float(view)), dx, dy, maxTaps);
}

// The mean of a mip chain over the box of half-size radiusUv around uv in `view`, read as
// split × split sub-boxes, each a footprint of trilinear taps (at most maxTaps along a non-square
// sub-box's long axis) at the level whose texels match its short side: what the O(1) soft filters
// read when their regions come from a mip chain (vssm with source=mip, evsm-soft). One trilinear
// read of the whole box weighs a tent twice the box's width (variance ×2 of the box's); 2 × 2
// sub-boxes one level finer ×1.25, 4 × 4 ×1.06.
vec4 boxMeanFromMips(sampler2DArray moments, int view, vec2 uv, vec2 radiusUv, int split, int maxTaps) {
  vec2 subUv = 2.0 * radiusUv / float(split);
  vec4 sum = vec4(0.0);
  for (int j = 0; j < split; ++j)
    for (int i = 0; i < split; ++i) {
      vec2 centre = uv - radiusUv + (vec2(i, j) + 0.5) * subUv;
      sum += textureFootprint(moments, vec3(centre, float(view)), vec2(subUv.x, 0.0), vec2(0.0, subUv.y), maxTaps);
    }
  return sum / float(split * split);
}
