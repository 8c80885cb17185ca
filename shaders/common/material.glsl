#pragma once
// Materials in the raster passes: the base colour (factor × texture) and the alpha test.
// Every fragment shader that draws scene objects — each shadow pass (depth, moments, …) and the
// G-buffer pass — includes this file and calls alphaTest(v_uv) first, so that alpha-masked
// casters cut the same holes in every map, in the camera view, and in the Embree reference
// (reference/EmbreeScene.cpp alphaAt() reads the same texel: nearest, repeat, uv (0,0) = the
// image's first stored row). GpuScene binds the object's texture at PN_TEX_BASECOLOR per draw.
// Usage:  #include "common/material.glsl"   then   void main() { alphaTest(v_uv); ... }
// Declares u_object (the draw's index into u_objects, PN_LOC_OBJECT): do not declare it again.
#include "common/frame.glsl"

layout(location = PN_LOC_OBJECT) uniform int u_object;
layout(binding = PN_TEX_BASECOLOR) uniform sampler2D s_baseColor;

bool materialHasTexture() { return u_objects[u_object].material.x >= 0; }

// The texel under uv: nearest, repeat wrapping; the exact rule of the reference's alphaAt().
vec4 materialTexel(vec2 uv) {
  ivec2 size = textureSize(s_baseColor, 0);
  vec2 wrapped = uv - floor(uv);
  ivec2 texel = min(size - 1, ivec2(wrapped * vec2(size)));
  return texelFetch(s_baseColor, texel, 0);  // sRGB texture: rgb arrives linear
}

// Discards the fragment where an alpha-masked material's texture is transparent
// (alpha < cutoff, ObjectGpu.baseColor.a). Opaque materials never discard.
void alphaTest(vec2 uv) {
  ObjectGpu o = u_objects[u_object];
  if (o.material.y != 0 && o.material.x >= 0 && materialTexel(uv).a < o.baseColor.a) discard;
}

// Linear base colour: the material's factor times its texture (if any).
vec3 materialBaseColor(vec2 uv) {
  vec3 factor = u_objects[u_object].baseColor.rgb;
  return materialHasTexture() ? factor * materialTexel(uv).rgb : factor;
}
