// Shadow pass for depth-only maps: writes linear light depth in [0,1] (docs/design.md convention),
// the same value for orthographic and perspective views.
#include "common/frame.glsl"
#include "common/material.glsl"

layout(location = PN_LOC_VIEW) uniform int u_view;
in vec3 v_wsPosition;
in vec3 v_wsNormal;
in vec2 v_uv;

void main() {
  alphaTest(v_uv);
  gl_FragDepth = clamp(dot(u_shadow.views[u_view].depthPlane, vec4(v_wsPosition, 1.0)), 0.0, 1.0);
}
