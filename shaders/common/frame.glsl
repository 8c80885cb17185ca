#pragma once
// The per-frame blocks every pass may read. Declared once; included by every pass.
#include "shared/Bindings.h"
#include "shared/Frame.h"
#include "shared/Shadow.h"

layout(std140, binding = PN_UBO_FRAME) uniform FrameBlock { FrameUniforms u_frame; };
layout(std140, binding = PN_UBO_SHADOW) uniform ShadowBlock { ShadowUniforms u_shadow; };
layout(std430, binding = PN_SSBO_OBJECTS) readonly buffer ObjectBlock { ObjectGpu u_objects[]; };

const float kPi = 3.14159265358979;

// The frame index stochastic patterns turn by (common/sampling.glsl's pixelNoise): 0 unless the
// core accumulates V over frames (temporal.accumulate), so a single frame's pattern never moves.
int samplingFrame() { return u_frame.screen.w; }

// Any light's kind, direction toward it and falloff (the frame's light below, or one of the lit
// pass's list). With PN_ONLY_SUNS defined (the lit pass of a frame without spot or point lights)
// the positional code is compiled out: a software rasteriser runs both sides of a branch.
bool isPositional(LightGpu l) {
#ifdef PN_ONLY_SUNS
  return false;
#else
  return int(l.direction.w) != PN_LIGHT_SUN;
#endif
}
vec3 toLightOf(LightGpu l, vec3 wsPosition) {
  return isPositional(l) ? normalize(l.position.xyz - wsPosition) : -l.direction.xyz;
}
// The light's unshadowed strength at wsPosition relative to its value without falloff: the
// spot's cone (smoothstep between the outer and inner cosines) times the range window
// (1 − (d/range)^4)^2; 1 for a sun. The same as lightFalloff() in C++ (src/scene/Scene.cpp).
float lightFalloffOf(LightGpu l, vec3 wsPosition) {
  if (!isPositional(l)) return 1.0;
  vec3 d = wsPosition - l.position.xyz;
  float f = 1.0;
  if (l.cone.z > 0.0) {
    float x = length(d) / l.cone.z;
    float w = clamp(1.0 - x * x * x * x, 0.0, 1.0);
    f *= w * w;
  }
  if (int(l.direction.w) == PN_LIGHT_SPOT) {
    float cosAxis = dot(normalize(d), l.direction.xyz);
    f *= l.cone.y > l.cone.x ? smoothstep(l.cone.x, l.cone.y, cosAxis) : step(l.cone.x, cosAxis);
  }
  return f;
}

// The frame's light's kind (PN_LIGHT_*): a compile-time constant in the visibility pass
// (PN_LIGHT_KIND, from FrameContext), read from the frame block elsewhere.
int lightKind() {
#ifdef PN_LIGHT_KIND
  return PN_LIGHT_KIND;
#else
  return int(u_frame.light.direction.w);
#endif
}
bool isSpotLight() { return lightKind() == PN_LIGHT_SPOT; }
bool isPointLight() { return lightKind() == PN_LIGHT_POINT; }
// Spot and point lights: light from a sphere at u_frame.light.position.
bool isPositionalLight() { return lightKind() != PN_LIGHT_SUN; }

// Unit vector from a surface point toward the frame's light's centre.
vec3 toLight(vec3 wsPosition) {
  return isPositionalLight() ? normalize(u_frame.light.position.xyz - wsPosition) : -u_frame.light.direction.xyz;
}
