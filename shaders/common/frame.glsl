#pragma once
// The per-frame blocks every pass may read. Declared once; included by every pass.
#include "shared/Bindings.h"
#include "shared/Frame.h"
#include "shared/Shadow.h"

layout(std140, binding = PN_UBO_FRAME) uniform FrameBlock { FrameUniforms u_frame; };
layout(std140, binding = PN_UBO_SHADOW) uniform ShadowBlock { ShadowUniforms u_shadow; };
layout(std430, binding = PN_SSBO_OBJECTS) readonly buffer ObjectBlock { ObjectGpu u_objects[]; };

const float kPi = 3.14159265358979;

// The light's kind (PN_LIGHT_*): a compile-time constant in the visibility pass (PN_LIGHT_KIND,
// from FrameContext), read from the frame block elsewhere.
int lightKind() {
#ifdef PN_LIGHT_KIND
  return PN_LIGHT_KIND;
#else
  return int(u_frame.lightDirection.w);
#endif
}
bool isSpotLight() { return lightKind() == PN_LIGHT_SPOT; }
bool isPointLight() { return lightKind() == PN_LIGHT_POINT; }
// Spot and point lights: light from a sphere at u_frame.lightPosition.
bool isPositionalLight() { return lightKind() != PN_LIGHT_SUN; }

// Unit vector from a surface point toward the light's centre.
vec3 toLight(vec3 wsPosition) {
  return isPositionalLight() ? normalize(u_frame.lightPosition.xyz - wsPosition) : -u_frame.lightDirection.xyz;
}

// The light's unshadowed strength at wsPosition relative to its value without falloff: the
// spot's cone (smoothstep between the outer and inner cosines) times the range window
// (1 − (d/range)^4)^2; 1 for a sun. The same as lightFalloff() in C++ (src/scene/Scene.cpp).
float lightFalloff(vec3 wsPosition) {
  if (!isPositionalLight()) return 1.0;
  vec3 d = wsPosition - u_frame.lightPosition.xyz;
  float f = 1.0;
  if (u_frame.lightCone.z > 0.0) {
    float x = length(d) / u_frame.lightCone.z;
    float w = clamp(1.0 - x * x * x * x, 0.0, 1.0);
    f *= w * w;
  }
  if (isSpotLight()) {
    float cosAxis = dot(normalize(d), u_frame.lightDirection.xyz);
    float lo = u_frame.lightCone.x, hi = u_frame.lightCone.y;
    f *= hi > lo ? smoothstep(lo, hi, cosAxis) : step(lo, cosAxis);
  }
  return f;
}
