// second-depth: second-depth shadow maps (Wang & Molnar 1994). The map stores the midpoint
// between the first and the second surface seen from the light (depth peeling, see
// passes/depth_peel.frag.glsl and passes/second_depth_combine.comp.glsl), and the receiver is
// compared with it WITHOUT bias: a lit surface is always the first layer, half a layer's
// thickness in front of the stored value, so acne needs no tuning. Assumes watertight casters;
// texels with a single layer (open meshes) fall back to a one-texel slope offset. Artifacts:
// thin casters (little room between layers) and contact points still show acne; aliasing as hard.
#include "common/depth_compare.glsl"

layout(binding = PN_TEX_FILTER0) uniform sampler2DArray s_midpointMap;

float shadowVisibility(SurfacePoint s) {
  int view = selectShadowView(s.ws);
  vec3 coord = shadowCoord(view, s.ws);
  if (!insideMap(coord)) return 1.0;
  return compareDepth(coord.z, texelFetch(s_midpointMap, mapTexel(s_midpointMap, coord.xy, view), 0).r);
}
