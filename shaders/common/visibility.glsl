#pragma once
// Inputs of the visibility pass. A filter's GLSL file includes this and defines
//   float shadowVisibility(SurfacePoint s);   // 0 = shadowed … 1 = lit
// and passes/visibility.comp.glsl calls it for every pixel that faces the light.
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

// Tangent of the angle between the normal and the light, clamped: slope-scaled biases use it.
float slopeTangent(SurfacePoint s) {
  const float kMaxTangent = 10.0;  // ~84 degrees; beyond, the bias would push through casters
  float sinT = sqrt(max(1.0 - s.NoL * s.NoL, 0.0));
  return min(sinT / max(s.NoL, 1e-4), kMaxTangent);
}
