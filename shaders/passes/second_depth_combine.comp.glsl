// second-depth: the stored map = the midpoint between the first and the second surface seen
// from the light, per texel and view. A texel with one surface only (an open mesh such as a
// single-sided plane, or a closed one whose back lies beyond the far plane) has no midpoint: it
// stores the first depth plus kOpenMeshSlopeTexels texels of that surface's own slope, i.e.
// what a slope-scaled bias would do there, so open receivers do not self-shadow yet open
// casters still cast. A texel with no surface stays empty (1 = far).
#include "common/shadow.glsl"

layout(local_size_x = PN_SCREEN_GROUP, local_size_y = PN_SCREEN_GROUP) in;
layout(binding = PN_TEX_FILTER0) uniform sampler2DArray s_firstDepth;
layout(binding = PN_TEX_FILTER1) uniform sampler2DArray s_firstSlope;
layout(binding = PN_TEX_FILTER2) uniform sampler2DArray s_secondDepth;
layout(binding = PN_IMG_AUX0, r32f) uniform writeonly image2DArray i_midpoint;

const float kEmptyDepth = 1.0;  // the layers' clear value: nothing there
// The receiver's depth within a texel differs from the texel's sample by at most half the slope
// (fwidth spans a whole texel in x plus y), so one full slope leaves a margin of two.
const float kOpenMeshSlopeTexels = 1.0;

void main() {
  ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(texel, ivec2(shadowMapSize())))) return;
  for (int view = 0; view < shadowViewCount(); ++view) {
    ivec3 t = ivec3(texel, view);
    float first = texelFetch(s_firstDepth, t, 0).r;
    float second = texelFetch(s_secondDepth, t, 0).r;
    float stored = kEmptyDepth;
    if (first < kEmptyDepth) {
      stored = second < kEmptyDepth ? 0.5 * (first + second)
                                    : min(first + kOpenMeshSlopeTexels * texelFetch(s_firstSlope, t, 0).r, kEmptyDepth);
    }
    imageStore(i_midpoint, t, vec4(stored));
  }
}
