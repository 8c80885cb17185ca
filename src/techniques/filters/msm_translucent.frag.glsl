// msm.translucent's shadow pass (shadows/filters/MsmFilter.h), drawn for the translucent casters
// alone and summed by additive blending (FrameContext::sumTranslucentViews), so the order they are
// drawn in does not matter. Each fragment's weight is its caster's absorbance: A = −ln(T) per
// channel (CasterSet puts the transmittance T in the object's baseColor.rgb), w = the mean of A
// over R, G, B. Two maps, one program each:
//   PN_MSM_ABSORBANCE 0: w·(z, z², z³, z⁴), the moments of the absorbance over linear light depth z;
//   PN_MSM_ABSORBANCE 1: (A_r, A_g, A_b, w), the totals (w's total is the moments' zeroth moment).
// A transmittance of 0 would be an infinite absorbance: T is floored at kMinTransmittance (a
// caster letting through less than that is opaque to within it).
#include "common/frame.glsl"
#include "common/material.glsl"
#include "common/moments.glsl"

const float kMinTransmittance = 1.0e-4;

layout(location = PN_LOC_VIEW) uniform int u_view;
in vec3 v_wsPosition;
in vec3 v_wsNormal;
in vec2 v_uv;
layout(location = 0) out vec4 o_sum;

void main() {
#ifndef PN_OPAQUE_CASTERS
  alphaTest(v_uv);
#endif
  float z = clamp(dot(u_shadow.views[u_view].depthPlane, vec4(v_wsPosition, 1.0)), 0.0, 1.0);
  vec3 absorbance = -log(max(u_objects[u_object].baseColor.rgb, vec3(kMinTransmittance)));
  float w = (absorbance.r + absorbance.g + absorbance.b) / 3.0;
#if PN_MSM_ABSORBANCE
  o_sum = vec4(absorbance, w);
#else
  o_sum = w * depthMoments(z);
#endif
}
