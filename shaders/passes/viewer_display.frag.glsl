// The viewer's draw pass: the chosen channel(s) of the shown texture, mapped from the range
// (fixed, or measured by viewer_range.comp.glsl) to grey or Turbo. Non-finite values: magenta.
#include "passes/viewer_display.glsl"

layout(std430, binding = PN_VIEWER_SSBO_RANGE) readonly buffer RangeBlock { uint u_min; uint u_max; };
layout(location = 0) out vec4 o_color;

const vec3 kNonFiniteColor = vec3(1.0, 0.0, 1.0);
const float kMinRange = 1e-20;  // a constant image maps to 0 instead of dividing by zero

// Google's Turbo colour map, polynomial fit (Mikhailov 2019); display-referred RGB.
vec3 turbo(float x) {
  const vec4 kRed4 = vec4(0.13572138, 4.61539260, -42.66032258, 132.13108234);
  const vec4 kGreen4 = vec4(0.09140261, 2.19418839, 4.84296658, -14.18503333);
  const vec4 kBlue4 = vec4(0.10667330, 12.64194608, -60.58204836, 110.36276771);
  const vec2 kRed2 = vec2(-152.94239396, 59.28637943);
  const vec2 kGreen2 = vec2(4.27729857, 2.82956604);
  const vec2 kBlue2 = vec2(-89.90310912, 27.34824973);
  x = clamp(x, 0.0, 1.0);
  vec4 v4 = vec4(1.0, x, x * x, x * x * x);
  vec2 v2 = v4.zw * v4.z;
  return vec3(dot(v4, kRed4) + dot(v2, kRed2), dot(v4, kGreen4) + dot(v2, kGreen2), dot(v4, kBlue4) + dot(v2, kBlue2));
}

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
    else color = u_display.source.w == PN_VIEWER_MAP_TURBO ? turbo(x) : vec3(x);
  }
  o_color = vec4(color, 1.0);
}
