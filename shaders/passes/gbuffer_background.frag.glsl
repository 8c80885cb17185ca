// G-buffer background: every attachment's value where no surface was drawn (all zero: position.w
// = 0 marks background for every reader). A full-screen triangle on the far plane, depth-tested
// EQUAL after the surfaces, writes only the uncovered pixels: cheaper than clearing every
// attachment over the whole screen and then overwriting most of it (docs/design.md).
#include "common/gbuffer_outputs.glsl"

void main() {
  o_position = vec4(0.0);
  o_normal = vec4(0.0);
  o_geoNormal = vec4(0.0);
  o_albedo = vec4(0.0);
#if PN_GBUFFER_TRIANGLES
  o_triangle = uvec2(0u);
#endif
}
