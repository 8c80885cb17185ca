#pragma once
// Inputs of the visibility pass (and of passes that follow it over the same surfaces: contact
// shadows). A filter's GLSL file includes this and defines
//   float shadowVisibility(SurfacePoint s);   // 0 = shadowed … 1 = lit
// and passes/visibility.glsl calls it for every pixel that faces the light.
#include "common/shadow.glsl"

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
