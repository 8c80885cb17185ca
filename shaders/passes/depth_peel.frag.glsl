// Depth-peeling shadow pass of second-depth shadow maps (Wang & Molnar 1994), both layers in
// linear light depth like passes/shadow_depth.frag.glsl.
//   PN_PEEL_LAYER 0: the nearest surface, plus its depth slope per texel (colour 0): how much
//                    the surface's depth changes across one texel, for texels with no second layer.
//   PN_PEEL_LAYER 1: the nearest surface strictly behind layer 0 (bound at PN_TEX_FILTER0).
#include "common/frame.glsl"
#include "common/material.glsl"

layout(location = PN_LOC_VIEW) uniform int u_view;
in vec3 v_wsPosition;
in vec3 v_wsNormal;
in vec2 v_uv;

#if PN_PEEL_LAYER == 0
layout(location = 0) out float o_depthSlope;
#else
layout(binding = PN_TEX_FILTER0) uniform sampler2DArray s_firstLayer;
// A fragment counts as "behind layer 0" only beyond this linear depth (~0.1 mm per 10 m of
// range). Layer 0's own fragment reproduces its depth bit for bit, so the margin only has to
// exceed float rounding near 1 (6e-8); it also merges coplanar faces (a box resting on a floor).
const float kPeelEpsilonDepth = 1e-5;
#endif

void main() {
  float depth = dot(u_shadow.views[u_view].depthPlane, vec4(v_wsPosition, 1.0));
#if PN_PEEL_LAYER == 0
  o_depthSlope = fwidth(depth);  // |∂d/∂x| + |∂d/∂y| per texel: the steepest change across one
#else
  float first = texelFetch(s_firstLayer, ivec3(ivec2(gl_FragCoord.xy), u_view), 0).r;
  if (depth <= first + kPeelEpsilonDepth) discard;
#endif
#ifndef PN_OPAQUE_CASTERS
  alphaTest(v_uv);
#endif
  ditherTranslucent();
  gl_FragDepth = clamp(depth, 0.0, 1.0);
}
