// The viewer's draw pass: the chosen channel(s) of the shown texture, mapped from the range
// (fixed, or measured by viewer_range.comp.glsl) to grey or Turbo. Non-finite values: magenta;
// the image's "no data" value (−1 = no blocker found): slate, apart from any measure.
#include "passes/viewer_display.glsl"
#include "shared/DebugColors.h"

layout(std430, binding = PN_VIEWER_SSBO_RANGE) readonly buffer RangeBlock { uint u_min; uint u_max; };
layout(location = 0) out vec4 o_color;

const vec3 kNonFiniteColor = vec3(1.0, 0.0, 1.0);
const vec3 kNoDataColor = vec3(PN_VIEWER_NO_DATA_RGB);
const float kMinRange = 1e-20;  // a constant image maps to 0 instead of dividing by zero

void main() {
  vec4 t = sourceAt(rectUv(gl_FragCoord.xy));
  vec2 range = u_display.mode.x != 0 ? vec2(floatFromOrdered(u_min), floatFromOrdered(u_max)) : u_display.range.xy;
  float scale = 1.0 / max(range.y - range.x, kMinRange);
  int c = u_display.source.z;
  vec3 color;
  if (c == PN_VIEWER_CHANNEL_RGB) {
    if (!finite(t.r) || !finite(t.g) || !finite(t.b)) color = kNonFiniteColor;
    else color = clamp((t.rgb - range.x) * scale, 0.0, 1.0);
  } else {
    float v = t[c];
    float x = clamp((v - range.x) * scale, 0.0, 1.0);
    if (!finite(v)) color = kNonFiniteColor;
    else if (noData(v)) color = kNoDataColor;
    else color = u_display.source.w == PN_VIEWER_MAP_TURBO ? turboColor(x).rgb : vec3(x);
  }
  o_color = vec4(color, 1.0);
}
