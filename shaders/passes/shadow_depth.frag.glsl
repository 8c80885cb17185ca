// Shadow pass for depth-only maps: writes linear light depth in [0,1] (docs/design.md convention),
// the same value for orthographic and perspective views. With PN_LINEAR_RASTER_DEPTH (orthographic
// views: linear depth is affine, geometry.vert.glsl makes it the clip z) the rasteriser's depth is
// that value and no fragment writes gl_FragDepth; with PN_OPAQUE_CASTERS there is no alpha test.
// Both keep the early depth test, unless PN_DITHER_TRANSLUCENT dithers translucent casters away
// (common/material.glsl: ditherTranslucent).
#include "common/frame.glsl"
#include "common/material.glsl"

layout(location = PN_LOC_VIEW) uniform int u_view;
in vec3 v_wsPosition;
in vec3 v_wsNormal;
in vec2 v_uv;

void main() {
#ifndef PN_OPAQUE_CASTERS
  alphaTest(v_uv);
#endif
  ditherTranslucent();
#ifndef PN_LINEAR_RASTER_DEPTH
  gl_FragDepth = clamp(dot(u_shadow.views[u_view].depthPlane, vec4(v_wsPosition, 1.0)), 0.0, 1.0);
#endif
}
