// G-buffer pass: world position, shading and geometric normals (both turned toward the camera,
// so open meshes shade from either side; a mesh without normals shades with the geometric one), base colour, and, when the frame records them, which
// triangle the pixel shows: the reference skips that triangle's own hits instead of lifting rays
// off it (docs/reference.md). Background pixels are written after, by gbuffer_background.frag.glsl.
#include "common/frame.glsl"
#include "common/gbuffer_outputs.glsl"
#include "common/material.glsl"

in vec3 v_wsPosition;
in vec3 v_wsNormal;
in vec2 v_uv;
#if PN_GBUFFER_TRIANGLES
// gl_PrimitiveID counts from 0 in each draw; GpuScene draws an object's mesh in one draw, or in
// pieces on a software rasteriser (gl/Draw.h), and gives each piece's first triangle here.
layout(location = PN_LOC_FIRST_TRIANGLE) uniform uint u_firstTriangle;
#endif

void main() {
  alphaTest(v_uv);
  vec3 toCamera = u_frame.cameraPosition.xyz - v_wsPosition;
  // The triangle's own plane, from screen-space derivatives of the interpolated position.
  vec3 g = normalize(cross(dFdx(v_wsPosition), dFdy(v_wsPosition)));
  if (dot(g, toCamera) < 0.0) g = -g;
  // A mesh without normals (GpuScene: the attribute reads 0) is shaded flat, by that plane.
  vec3 n = dot(v_wsNormal, v_wsNormal) > 0.0 ? normalize(v_wsNormal) : g;
  if (dot(n, g) < 0.0) n = -n;
  o_position = vec4(v_wsPosition, 1.0);
  o_normal = vec4(n, 0.0);
  o_geoNormal = vec4(g, 0.0);
  o_albedo = vec4(materialBaseColor(v_uv), 1.0);
#if PN_GBUFFER_TRIANGLES
  o_triangle = uvec2(uint(u_object) + 1u, u_firstTriangle + uint(gl_PrimitiveID));
#endif
}
