#pragma once
// Inputs of the visibility pass (and of passes that follow it over the same surfaces: contact
// shadows). A filter's GLSL file includes this and defines
//   float shadowVisibility(SurfacePoint s);   // 0 = shadowed … 1 = lit
// and passes/visibility.glsl calls it for every pixel that faces the light.
#include "common/shadow.glsl"

// The visibility array's texels: one channel (r32f), or with PN_VISIBILITY_RGB (a scene whose
// translucent casters tint V) RGB in an rgba32f layer, alpha unused. Passes that read and write
// it as an image (contact shadows, temporal accumulation) declare it with this format and hold
// its value as a VisibilityValue.
#ifdef PN_VISIBILITY_RGB
#define PN_VISIBILITY_FORMAT rgba32f
#define VisibilityValue vec3
VisibilityValue visibilityOfTexel(vec4 t) { return t.rgb; }
vec4 visibilityTexel(VisibilityValue v) { return vec4(v, 1.0); }
#else
#define PN_VISIBILITY_FORMAT r32f
#define VisibilityValue float
VisibilityValue visibilityOfTexel(vec4 t) { return t.r; }
vec4 visibilityTexel(VisibilityValue v) { return vec4(v); }
#endif

layout(binding = PN_TEX_GBUF_POSITION) uniform sampler2D s_gbufPosition;
layout(binding = PN_TEX_GBUF_GEONORMAL) uniform sampler2D s_gbufGeoNormal;

struct SurfacePoint {
  vec3 ws;         // world position (m)
  vec3 geoNormal;  // unit geometric normal, facing the camera
  vec3 toLight;    // unit, toward the light's centre
  float NoL;       // dot(geoNormal, toLight) > 0
  ivec2 pixel;
};

// The pixel's world position; w = 1 where there is geometry, 0 on background.
vec4 surfacePosition(ivec2 px) {
#ifdef PN_SURFACE_FROM_DEPTH
  // An engine's depth texture (bound where the position texture would be): unprojected through
  // the inverse of its own camera matrices, at the pixel's centre.
  float stored = texelFetch(s_gbufPosition, px, 0).r;
  if (stored == u_frame.depthInfo.z) return vec4(0.0);
  vec2 ndcXY = (vec2(px) + 0.5) / vec2(u_frame.screen.xy) * 2.0 - 1.0;
  vec4 ws = u_frame.worldFromClip * vec4(ndcXY, u_frame.depthInfo.x * stored + u_frame.depthInfo.y, 1.0);
  return vec4(ws.xyz / ws.w, 1.0);
#else
  return texelFetch(s_gbufPosition, px, 0);
#endif
}

// The camera's view direction (unit, world): where it looks.
vec3 cameraForward() { return -vec3(u_frame.viewFromWorld[0][2], u_frame.viewFromWorld[1][2], u_frame.viewFromWorld[2][2]); }

// The eye of the camera ray that sees ws: the camera's position, or for an orthographic camera
// (PN_CAMERA_ORTHOGRAPHIC: parallel rays) the point one metre before ws along its ray. A ray's
// origin, direction (normalize(ws - eye)) and distances along it mean the same either way.
vec3 cameraEyeFor(vec3 ws) {
#ifdef PN_CAMERA_ORTHOGRAPHIC
  return ws - cameraForward();
#else
  return u_frame.cameraPosition.xyz;
#endif
}

// What a pixel's width at ws scales with (m): its distance from the camera; 1 for an
// orthographic camera, whose pixels are as wide everywhere.
float pixelScaleAt(vec3 ws) {
#ifdef PN_CAMERA_ORTHOGRAPHIC
  return 1.0;
#else
  return distance(ws, u_frame.cameraPosition.xyz);
#endif
}

// A quantity that is affine over the screen across a plane: the inverse of the camera depth
// (the depth itself for an orthographic camera).
float screenAffineDepth(vec3 ws) {
#ifdef PN_CAMERA_ORTHOGRAPHIC
  return cameraViewDepth(ws);
#else
  return 1.0 / max(cameraViewDepth(ws), 1e-6);
#endif
}

// How far (relative to the pixel's own screenAffineDepth) a neighbour's extrapolation may land
// for the neighbour to count as on the pixel's surface: a plane lands on it but for rounding; a
// curved surface a little off; another surface, across a silhouette or a crease, far off.
const float kSameSurfaceMiss = 0.02;

// The geometric normal of the surface at px (at world position ws), facing the camera: the
// engine's normal texture, or without one (PN_NORMALS_FROM_POSITIONS) rebuilt from the
// neighbours' positions. On each axis the neighbour whose side continues the pixel's surface:
// screenAffineDepth extrapolated from the next two pixels on that side lands on the pixel's own.
// With such a neighbour on both axes, the plane through the three; on one axis only (a surface
// one pixel wide: a pole, a wire, a wall seen edge-on), the normal across that tangent that
// faces the camera most; on neither, the direction to the camera. Not normalised when read from
// the texture.
vec3 surfaceGeoNormal(ivec2 px, vec3 ws) {
#ifdef PN_NORMALS_FROM_POSITIONS
  float q = screenAffineDepth(ws);
  ivec2 size = u_frame.screen.xy;
  vec3 toEye = normalize(cameraEyeFor(ws) - ws);
  vec3 axes[2];
  bool found[2];
  for (int a = 0; a < 2; ++a) {
    ivec2 step = a == 0 ? ivec2(1, 0) : ivec2(0, 1);
    vec3 edge[2];
    float miss[2];
    for (int side = 0; side < 2; ++side) {
      ivec2 s = side == 0 ? step : -step;
      ivec2 p1 = px + s, p2 = px + 2 * s;
      vec4 n1 = all(greaterThanEqual(p1, ivec2(0))) && all(lessThan(p1, size)) ? surfacePosition(p1) : vec4(0.0);
      vec4 n2 = all(greaterThanEqual(p2, ivec2(0))) && all(lessThan(p2, size)) ? surfacePosition(p2) : vec4(0.0);
      edge[side] = side == 0 ? n1.xyz - ws : ws - n1.xyz;
      // No second neighbour (the screen's edge, background): the first one's own gap, counted
      // four times over so that a side with two neighbours wins a tie.
      float q1 = n1.w > 0.5 ? screenAffineDepth(n1.xyz) : 0.0;
      miss[side] = n1.w <= 0.5 ? 1e30 : n2.w > 0.5 ? abs(2.0 * q1 - screenAffineDepth(n2.xyz) - q) : 4.0 * abs(q1 - q);
    }
    axes[a] = miss[0] <= miss[1] ? edge[0] : edge[1];
    found[a] = min(miss[0], miss[1]) <= kSameSurfaceMiss * abs(q) && dot(axes[a], axes[a]) > 0.0;
  }
  vec3 n = toEye;
  if (found[0] && found[1]) {
    vec3 c = cross(axes[0], axes[1]);
    if (dot(c, c) > 0.0) n = normalize(c);
  } else if (found[0] || found[1]) {
    vec3 t = normalize(found[0] ? axes[0] : axes[1]);
    vec3 across = toEye - dot(toEye, t) * t;
    if (dot(across, across) > 1e-12) n = normalize(across);
  }
  return dot(n, toEye) < 0.0 ? -n : n;
#else
  return texelFetch(s_gbufGeoNormal, px, 0).xyz;
#endif
}

// Camera distance along the view axis (m) of the surface at px; far beyond anything on background.
float surfaceViewDepth(ivec2 px) {
  vec4 pos = surfacePosition(px);
  const float kBackgroundM = 1e30;  // farther than any surface
  return pos.w > 0.5 ? cameraViewDepth(pos.xyz) : kBackgroundM;
}

// Tangent of the angle between the normal and the light, clamped: slope-scaled biases use it.
float slopeTangent(SurfacePoint s) {
  const float kMaxTangent = 10.0;  // ~84 degrees; beyond, the bias would push through casters
  float sinT = sqrt(max(1.0 - s.NoL * s.NoL, 0.0));
  return min(sinT / max(s.NoL, 1e-4), kMaxTangent);
}
