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
#ifdef PN_DITHER_TRANSLUCENT
#include "common/sampling.glsl"
#endif

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

// Stochastic transparency in the shadow passes (each calls it after its alpha test, for opaque
// and masked casters alike; nothing without PN_DITHER_TRANSLUCENT, which FrameContext::
// shadowProgram sets for the translucent add-on's stochastic method): a translucent caster's
// fragment (CasterSet: material.z = 1, baseColor.rgb = its transmittance T) is kept with the
// probability of its opacity 1 − mean(T), by a per-texel noise that the frame's sampling index
// turns (common/sampling.glsl's pixelNoise), offset per object so that two panes over one texel
// are dithered apart. The map's filter taps and temporal accumulation average the kept texels.
void ditherTranslucent() {
#ifdef PN_DITHER_TRANSLUCENT
  ObjectGpu o = u_objects[u_object];
  float opacity = 1.0 - (o.baseColor.r + o.baseColor.g + o.baseColor.b) / 3.0;
  const ivec2 kObjectStep = ivec2(37, 71);  // texels between two objects' patterns
  if (o.material.z != 0 && pixelNoise(ivec2(gl_FragCoord.xy) + u_object * kObjectStep, samplingFrame()) >= opacity) discard;
#endif
}

// Linear base colour: the material's factor times its texture (if any).
vec3 materialBaseColor(vec2 uv) {
  vec3 factor = u_objects[u_object].baseColor.rgb;
  return materialHasTexture() ? factor * materialTexel(uv).rgb : factor;
}
