// The translucent add-on's tint (shadows/translucent/TranslucentShadows.h): for each pixel, the
// product of the translucent casters' transmittances in front of it, drawn over the filter's V
// with multiplicative blending (FrameContext::multiplyVisibility). Each texel of a box of
// (2·PN_TRANSLUCENT_RADIUS + 1)² around the receiver gives its product where the receiver lies
// behind the nearest translucent surface stored there (the receiver's plane at the texel's
// centre, moved back by the plane bias, farther than that depth), 1 where it does not; the box
// averages them, as pcf averages comparisons. What it cannot see: a receiver between two
// translucent layers counts both (the map keeps one depth per texel, the nearest).
#define PN_SHADOW_VALUE vec3
#include "common/depth_compare.glsl"
#include "techniques/translucent/translucent.shared.h"

layout(std140, binding = PN_UBO_FILTER) uniform TranslucentBlock { TranslucentUniforms u_translucent; };
layout(binding = PN_TEX_FILTER0) uniform sampler2DArray s_transmittance;  // rgb: product, a: nearest translucent depth

vec3 shadowVisibility(SurfacePoint s) {
  int view = selectShadowView(s.ws);
  vec3 coord = shadowCoord(view, s.ws);
  if (!insideMap(coord)) return vec3(1.0);
  ComparisonReceiver r = comparisonReceiver(view, s, coord, 0.0, 0.0, u_translucent.params.y);
  ivec3 centre = mapTexel(s_transmittance, coord.xy, view);
  ivec2 size = textureSize(s_transmittance, 0).xy;
  vec3 sum = vec3(0.0);
  for (int dy = -PN_TRANSLUCENT_RADIUS; dy <= PN_TRANSLUCENT_RADIUS; ++dy) {
    for (int dx = -PN_TRANSLUCENT_RADIUS; dx <= PN_TRANSLUCENT_RADIUS; ++dx) {
      ivec2 texel = clamp(centre.xy + ivec2(dx, dy), ivec2(0), size - 1);
      vec4 t = texelFetch(s_transmittance, ivec3(texel, view), 0);
      float depth = biasedDepthAt(r, (vec2(texel) + 0.5) / vec2(size));
      sum += compareDepth(depth, t.a) > 0.5 ? vec3(1.0) : t.rgb;
    }
  }
  const float kTaps = float((2 * PN_TRANSLUCENT_RADIUS + 1) * (2 * PN_TRANSLUCENT_RADIUS + 1));
  return sum / kTaps;
}
