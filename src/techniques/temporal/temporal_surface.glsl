// The frame's surfaces as the next frame's temporal pass reads them (temporal_accumulate.glsl):
// each pixel's world position (w = 1 where there is geometry), whatever the surface source (the
// engine's depth or a position texture), and its geometric normal.
#include "common/visibility.glsl"

layout(local_size_x = PN_SCREEN_GROUP, local_size_y = PN_SCREEN_GROUP) in;
layout(binding = PN_IMG_OUTPUT, rgba32f) uniform writeonly image2D i_surface;
layout(binding = PN_IMG_AUX0, rgba16f) uniform writeonly image2D i_normal;

void main() {
  ivec2 px = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(px, u_frame.screen.xy))) return;
  vec4 pos = surfacePosition(px);
  imageStore(i_surface, px, pos.w > 0.5 ? vec4(pos.xyz, 1.0) : vec4(0.0));
  imageStore(i_normal, px, pos.w > 0.5 ? vec4(normalize(surfaceGeoNormal(px, pos.xyz)), 0.0) : vec4(0.0));
}
