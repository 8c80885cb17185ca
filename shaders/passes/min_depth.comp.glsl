// One level of a min-depth pyramid (MinDepthPyramid): each texel holds the smallest linear depth
// of the 2x2 texels under it in the level below (level 0: of the shadow map itself, channel r),
// so a texel of level k is the minimum over 2^(k+1) x 2^(k+1) map texels. Levels halve rounding
// down (GL's mip sizes), so the last row and column of a level also take the odd texel left over
// below them: every map texel is under the texel that floor(x / 2^(k+1)), clamped, names.
// With u_minFilter (MinDepthPyramid::build, where GL_ARB_texture_filter_minmax is there) s_source
// has a sampler whose bilinear filter returns the minimum of its 2x2 texels instead of their
// weighted mean: a texel with exactly 2x2 texels under it is one filtered read at their shared
// corner, the same value as four texel fetches and their minimum, at the cost of one read.
#include "shared/Bindings.h"

layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = PN_TEX_FILTER0) uniform sampler2DArray s_source;  // the map, or the pyramid
layout(binding = PN_IMG_AUX0, r32f) uniform writeonly image2DArray i_level;
layout(location = PN_LOC_LEVEL) uniform int u_sourceLevel;  // the level of s_source to read
layout(location = PN_LOC_SWITCH) uniform int u_minFilter;    // 1: s_source's filter takes the minimum

void main() {
  ivec3 p = ivec3(gl_GlobalInvocationID);
  if (any(greaterThanEqual(p.xy, imageSize(i_level).xy))) return;
  ivec2 last = textureSize(s_source, u_sourceLevel).xy - 1;
  ivec2 outLast = imageSize(i_level).xy - 1;
  ivec2 hi = min(mix(2 * p.xy + 1, last, equal(p.xy, outLast)), last);
  float m = 1.0;  // linear depths lie in [0, 1]
  if (u_minFilter != 0 && all(equal(hi, 2 * p.xy + 1))) {
    vec2 corner = vec2(2 * p.xy + 1) / vec2(last + 1);  // the four texels' shared corner, in uv
    m = textureLod(s_source, vec3(corner, float(p.z)), float(u_sourceLevel)).r;
  } else {  // the last row or column over an odd side: 2x3, 3x2 or 3x3 texels
    for (int y = 2 * p.y; y <= hi.y; ++y)
      for (int x = 2 * p.x; x <= hi.x; ++x) m = min(m, texelFetch(s_source, ivec3(x, y, p.z), u_sourceLevel).r);
  }
  imageStore(i_level, p, vec4(m));
}
