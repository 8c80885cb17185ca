// Texel-density pass (comparison/TexelDensity.h): per pixel, the screen pixels covered by one
// shadow-map texel (common/texel_density.glsl). -1 where there is no geometry or the surface
// faces away from the light (no shadow-map lookup happens there).
#include "common/texel_density.glsl"
#include "common/visibility.glsl"

layout(local_size_x = PN_SCREEN_GROUP, local_size_y = PN_SCREEN_GROUP) in;
layout(binding = PN_IMG_OUTPUT, r32f) uniform writeonly image2D i_density;

void main() {
  ivec2 px = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(px, u_frame.screen.xy))) return;
  float density = screenPixelsPerTexel(s_gbufPosition, px);
  if (density > 0.0) {
    vec3 ws = texelFetch(s_gbufPosition, px, 0).xyz;
    if (dot(texelFetch(s_gbufGeoNormal, px, 0).xyz, toLight(ws)) <= 0.0) density = -1.0;
  }
  imageStore(i_density, px, vec4(density));
}
