// The visibility pass: one thread per pixel; V = shadowVisibility(...) of the active filter
// for pixels that face the light, 0 for pixels that face away (no direct light reaches them),
// 1 where there is no geometry.
#include "common/visibility.glsl"

layout(local_size_x = PN_SCREEN_GROUP, local_size_y = PN_SCREEN_GROUP) in;
layout(binding = PN_IMG_VISIBILITY, r32f) uniform writeonly image2D i_visibility;

void main() {
  ivec2 px = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(px, u_frame.screen.xy))) return;
  vec4 pos = texelFetch(s_gbufPosition, px, 0);
  float v = 1.0;
  if (pos.w > 0.5) {
    SurfacePoint s;
    s.ws = pos.xyz;
    s.geoNormal = normalize(texelFetch(s_gbufGeoNormal, px, 0).xyz);
    s.toLight = toLight(s.ws);
    s.NoL = dot(s.geoNormal, s.toLight);
    s.pixel = px;
    v = s.NoL > 0.0 ? clamp(shadowVisibility(s), 0.0, 1.0) : 0.0;
  }
  imageStore(i_visibility, px, vec4(v));
}
