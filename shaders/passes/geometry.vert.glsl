// Shared vertex stage of the shadow and G-buffer passes: object → world → the camera's clip
// space (u_view < 0) or shadow view u_view's clip space.
#include "common/frame.glsl"

layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in vec2 a_uv;

layout(location = PN_LOC_OBJECT) uniform int u_object;
layout(location = PN_LOC_VIEW) uniform int u_view;
#ifdef PN_PAGED_SHADOW_PASS
// A paged map's page (frame/VirtualPages.cpp): its part of the view's clip square blown up to
// the whole viewport (the page's tile of the pool).
layout(location = PN_LOC_PAGE) uniform vec4 u_page;
#endif

out vec3 v_wsPosition;
out vec3 v_wsNormal;
out vec2 v_uv;

void main() {
  ObjectGpu o = u_objects[u_object];
  vec4 ws = o.worldFromObject * vec4(a_position, 1.0);
  v_wsPosition = ws.xyz;
  v_wsNormal = mat3(o.normalFromObject) * a_normal;
  v_uv = a_uv;
  gl_Position = u_view < 0 ? u_frame.clipFromWorld * ws : u_shadow.views[u_view].clipFromWorld * ws;
#ifdef PN_LINEAR_RASTER_DEPTH
  // An orthographic shadow view (w = 1): clip z is the linear light depth itself, which the
  // rasteriser interpolates exactly (affine) and clamps to [0, 1] (depth clamping is on).
  gl_Position.z = dot(u_shadow.views[u_view].depthPlane, ws);
#endif
#ifdef PN_PAGED_SHADOW_PASS
  gl_Position.xy = gl_Position.xy * u_page.xy + u_page.zw * gl_Position.w;
#endif
}
