// The viewer's range pass: min and max of the shown channel(s) over the pixels that will be
// displayed (not every texel of a 4096² map), written with atomics for the draw pass to read
// on the GPU (no read-back in between).
#include "passes/viewer_display.glsl"

layout(local_size_x = PN_VIEWER_GROUP, local_size_y = PN_VIEWER_GROUP) in;
layout(std430, binding = PN_VIEWER_SSBO_RANGE) buffer RangeBlock { uint o_min; uint o_max; };

void main() {
  ivec2 id = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(id, u_display.rect.zw))) return;
  vec4 t = sourceAt((vec2(id) + 0.5) / vec2(u_display.rect.zw));
  int c = u_display.source.z;
  int first = c == PN_VIEWER_CHANNEL_RGB ? 0 : c;
  int last = c == PN_VIEWER_CHANNEL_RGB ? 2 : c;
  for (int i = first; i <= last; ++i) {
    if (!finite(t[i]) || noData(t[i])) continue;
    uint u = orderedFromFloat(t[i]);
    atomicMin(o_min, u);
    atomicMax(o_max, u);
  }
}
