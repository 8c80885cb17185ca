// Shadow pass for moment maps (vsm, vssm with source=mip, msm): writes the linear light depth z
// (docs/design.md convention, the same for orthographic and perspective views) to the depth buffer and
// its moments to colour target 0, ready to be filtered (mip chains) like any texture.
// Defines: PN_MOMENT_COUNT 2 → (z, z^2, 0, 0); 4 → (z, z^2, z^3, z^4).
//          PN_MOMENT_SLOPE_VARIANCE (2 moments): add the variance of the depth plane across this
//            texel, 1/4 (dz/dx^2 + dz/dy^2), to z^2 (Lauritzen's bias: a tilted receiver's own
//            moments no longer shadow it).
//          PN_MOMENTS_QUANTIZED (4 moments): store the optimised 16-bit basis (moments.glsl).
//          PN_OPAQUE_CASTERS: no alpha test (FrameContext's pass for opaque casters).
#include "common/frame.glsl"
#include "common/material.glsl"
#include "common/moments.glsl"

layout(location = PN_LOC_VIEW) uniform int u_view;
in vec3 v_wsPosition;
in vec3 v_wsNormal;
in vec2 v_uv;
layout(location = 0) out vec4 o_moments;

void main() {
  float z = clamp(dot(u_shadow.views[u_view].depthPlane, vec4(v_wsPosition, 1.0)), 0.0, 1.0);
  gl_FragDepth = z;
#if PN_MOMENT_COUNT == 2
  float z2 = z * z;
#ifdef PN_MOMENT_SLOPE_VARIANCE
  vec2 dz = vec2(dFdx(z), dFdy(z));  // before the alpha test's discard: derivatives need the quad
  z2 += 0.25 * dot(dz, dz);
#endif
#ifndef PN_OPAQUE_CASTERS
  alphaTest(v_uv);
#endif
  ditherTranslucent();
  o_moments = vec4(z, z2, 0.0, 0.0);
#elif PN_MOMENT_COUNT == 4
  vec4 b = depthMoments(z);
#ifndef PN_OPAQUE_CASTERS
  alphaTest(v_uv);
#endif
  ditherTranslucent();
#ifdef PN_MOMENTS_QUANTIZED
  b = quantizeMoments16(b);
#endif
  o_moments = b;
#else
#error PN_MOMENT_COUNT must be 2 or 4
#endif
}
