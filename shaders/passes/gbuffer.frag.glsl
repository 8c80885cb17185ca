// G-buffer pass: world position, shading and geometric normals (both turned toward the camera,
// so open meshes shade from either side), base colour, and which triangle the pixel shows: the
// reference skips that triangle's own hits instead of lifting rays off it (docs/reference.md).
#include "common/frame.glsl"
#include "common/material.glsl"

in vec3 v_wsPosition;
in vec3 v_wsNormal;
in vec2 v_uv;

layout(location = 0) out vec4 o_position;
layout(location = 1) out vec4 o_normal;
layout(location = 2) out vec4 o_geoNormal;
layout(location = 3) out vec4 o_albedo;
// (object index + 1, triangle index in the object's mesh); 0 = none (cleared background).
// gl_PrimitiveID counts from 0 in each draw, and GpuScene draws one object's whole mesh per call.
layout(location = 4) out uvec2 o_triangle;

void main() {
  alphaTest(v_uv);
  vec3 toCamera = u_frame.cameraPosition.xyz - v_wsPosition;
  // The triangle's own plane, from screen-space derivatives of the interpolated position.
  vec3 g = normalize(cross(dFdx(v_wsPosition), dFdy(v_wsPosition)));
  if (dot(g, toCamera) < 0.0) g = -g;
  vec3 n = normalize(v_wsNormal);
  if (dot(n, g) < 0.0) n = -n;
  o_position = vec4(v_wsPosition, 1.0);
  o_normal = vec4(n, 0.0);
  o_geoNormal = vec4(g, 0.0);
  o_albedo = vec4(materialBaseColor(v_uv), 1.0);
  o_triangle = uvec2(uint(u_object) + 1u, uint(gl_PrimitiveID));
}
