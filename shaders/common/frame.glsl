#pragma once
// The per-frame blocks every pass may read. Declared once; included by every pass.
#include "shared/Bindings.h"
#include "shared/Frame.h"
#include "shared/Shadow.h"

layout(std140, binding = PN_UBO_FRAME) uniform FrameBlock { FrameUniforms u_frame; };
layout(std140, binding = PN_UBO_SHADOW) uniform ShadowBlock { ShadowUniforms u_shadow; };
layout(std430, binding = PN_SSBO_OBJECTS) readonly buffer ObjectBlock { ObjectGpu u_objects[]; };

const float kPi = 3.14159265358979;

// The light's kind: a compile-time constant in the visibility pass (PN_LIGHT_KIND, from
// FrameContext), read from the frame block elsewhere.
bool isSpotLight() {
#ifdef PN_LIGHT_KIND
  return PN_LIGHT_KIND == PN_LIGHT_SPOT;
#else
  return u_frame.lightDirection.w == float(PN_LIGHT_SPOT);
#endif
}

// Unit vector from a surface point toward the light's centre.
vec3 toLight(vec3 wsPosition) {
  return isSpotLight() ? normalize(u_frame.lightPosition.xyz - wsPosition) : -u_frame.lightDirection.xyz;
}
