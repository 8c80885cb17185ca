// Shadow pass for exponentially warped maps (esm, evsm, evsm-soft): writes the linear light depth
// z (docs/design.md convention) to the depth buffer and the warps' moments (shadows/filters/
// exp_warp.shared.h; exponents from u_warp) to colour target 0, ready to be filtered.
// Defines: PN_EXP_WARP_COMPONENTS 1 → (p, 0, 0, 0) (esm); 2 → (p, p², 0, 0); 4 → (p, p², n, n²).
//   With 2 and 4, each second moment also gets the warp's variance across the texel: vsm's slope
//   term ¼(∂z/∂x² + ∂z/∂y²) carried through the warp's slope dw/dz = 2c·w (a tilted receiver's own
//   moments must not shadow it), clamped to the largest value the storage holds.
#include "common/frame.glsl"
#include "common/material.glsl"
#include "techniques/filters/exp_warp.shared.h"

layout(std140, binding = PN_UBO_FILTER) uniform ExpWarpBlock { ExpWarpUniforms u_warp; };
layout(location = PN_LOC_VIEW) uniform int u_view;
in vec3 v_wsPosition;
in vec3 v_wsNormal;
in vec2 v_uv;
layout(location = 0) out vec4 o_moments;

void main() {
  float z = clamp(dot(u_shadow.views[u_view].depthPlane, vec4(v_wsPosition, 1.0)), 0.0, 1.0);
  vec2 dz = vec2(dFdx(z), dFdy(z));  // before the alpha test's discard: derivatives need the quad
#ifndef PN_OPAQUE_CASTERS
  alphaTest(v_uv);
#endif
  ditherTranslucent();
  gl_FragDepth = z;
  vec2 c = u_warp.warp.xy;
  vec4 m = expWarpMoments(z, c.x, c.y);
#if PN_EXP_WARP_COMPONENTS == 1
  o_moments = vec4(m.x, 0.0, 0.0, 0.0);
#elif PN_EXP_WARP_COMPONENTS == 2 || PN_EXP_WARP_COMPONENTS == 4
  float slopeVariance = 0.25 * dot(dz, dz);
  float largest = u_warp.warp.z;
  m.y = min(m.y * (1.0 + 4.0 * c.x * c.x * slopeVariance), largest);
  m.w = min(m.w * (1.0 + 4.0 * c.y * c.y * slopeVariance), largest);
  o_moments = PN_EXP_WARP_COMPONENTS == 2 ? vec4(m.xy, 0.0, 0.0) : m;
#else
#error PN_EXP_WARP_COMPONENTS must be 1, 2 or 4
#endif
}
