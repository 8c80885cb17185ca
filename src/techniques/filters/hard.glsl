// hard: the two-pass shadow map test (Williams 1978). The receiver's linear light depth is
// compared with the nearest depth stored in the map: lit when not farther. The comparison of
// a surface with its own rasterised depth fails at random along the texel grid ("acne"),
// worst when the light grazes the surface; the bias modes trade it against "peter-panning"
// (shadows detached from their casters).
#include "common/depth_compare.glsl"
#include "techniques/filters/hard.shared.h"

layout(std140, binding = PN_UBO_FILTER) uniform HardBlock { HardUniforms u_hard; };
layout(binding = PN_TEX_FILTER0) uniform sampler2DArray s_shadowMap;

float shadowVisibility(SurfacePoint s) {
  int view = selectShadowView(s.ws);
  const int mode = PN_HARD_BIAS;
  if (mode == PN_BIAS_PLANE) {
    // The receiver's own plane at the centre of the texel it reads, where that texel's depth was
    // rasterised: a planar receiver meets its map exactly, whatever its slope and the texel's size.
    vec3 coord = shadowCoord(view, s.ws);
    if (!insideViewMap(view, coord)) return 1.0;
    ComparisonReceiver r = comparisonReceiver(view, s, coord, 0.0, 0.0, u_hard.bias.w);
    ivec3 texel = mapTexel(s_shadowMap, coord.xy, view);
    float depth = biasedDepthAt(r, (vec2(texel.xy) + 0.5) / shadowMapSize());
    return compareDepth(depth, fetchMapDepth(s_shadowMap, texel));
  }
  vec3 ws = s.ws;
  if (mode == PN_BIAS_NORMAL) ws += s.geoNormal * (u_hard.bias.z * shadowTexelWorldSize(view, s.ws));
  vec3 coord = shadowCoord(view, ws);
  if (!insideViewMap(view, coord)) return 1.0;
  float bias = 0.0;
  if (mode != PN_BIAS_NONE) bias = u_hard.bias.x;
  // Across one texel, a plane tilted by θ from the light changes depth by texel · tan θ.
  if (mode == PN_BIAS_SLOPE) bias += slopeDepthOffset(view, s.ws, slopeTangent(s), u_hard.bias.y);
  float stored = fetchMapDepth(s_shadowMap, mapTexel(s_shadowMap, coord.xy, view));
  return coord.z - bias <= stored ? 1.0 : 0.0;
}
