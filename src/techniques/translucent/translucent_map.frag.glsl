// The translucent add-on's map pass (shadows/translucent/TranslucentShadows.h), drawn for the
// translucent casters over the opaque casters' depth: each fragment outputs its caster's
// transmittance (rgb, multiplied into the map by the blend) and its linear light depth (alpha,
// kept by its minimum). Writes gl_FragDepth, the same linear depth the opaque depth holds, so the
// depth test drops translucent surfaces behind the nearest opaque one.
#include "common/material.glsl"

layout(location = PN_LOC_VIEW) uniform int u_view;
in vec3 v_wsPosition;
in vec3 v_wsNormal;
in vec2 v_uv;
layout(location = 0) out vec4 o_transmittance;

void main() {
#ifndef PN_OPAQUE_CASTERS
  alphaTest(v_uv);
#endif
  float depth = clamp(dot(u_shadow.views[u_view].depthPlane, vec4(v_wsPosition, 1.0)), 0.0, 1.0);
  gl_FragDepth = depth;
  o_transmittance = vec4(u_objects[u_object].baseColor.rgb, depth);  // CasterSet: rgb = the transmittance
}
