// Shared by the viewer's range and draw passes: reads the shown texture at a position in the
// display rectangle, and the order-preserving float ↔ uint encoding used for atomic min/max.
#pragma once
#include "shared/Viewer.h"

layout(std140, binding = PN_VIEWER_UBO_DISPLAY) uniform ViewerDisplayBlock { ViewerDisplayUniforms u_display; };

#if PN_VIEWER_SOURCE == PN_VIEWER_SOURCE_2D_ARRAY
layout(binding = PN_VIEWER_TEX_SOURCE) uniform sampler2DArray s_source;
vec4 sourceAt(vec2 uv) { return textureLod(s_source, vec3(uv, float(u_display.source.x)), float(u_display.source.y)); }
#elif PN_VIEWER_SOURCE == PN_VIEWER_SOURCE_3D
layout(binding = PN_VIEWER_TEX_SOURCE) uniform sampler3D s_source;
vec4 sourceAt(vec2 uv) {
  int slices = textureSize(s_source, u_display.source.y).z;
  float w = (float(u_display.source.x) + 0.5) / float(max(slices, 1));
  return textureLod(s_source, vec3(uv, w), float(u_display.source.y));
}
#else
layout(binding = PN_VIEWER_TEX_SOURCE) uniform sampler2D s_source;
vec4 sourceAt(vec2 uv) { return textureLod(s_source, uv, float(u_display.source.y)); }
#endif

// Texture coordinates of window pixel `px` (pixel centres) inside the display rectangle.
vec2 rectUv(vec2 px) { return (px - vec2(u_display.rect.xy)) / vec2(u_display.rect.zw); }

// IEEE floats ordered as unsigned integers: flip all bits of negatives, the sign bit of positives.
uint orderedFromFloat(float f) {
  uint u = floatBitsToUint(f);
  return (u & 0x80000000u) != 0u ? ~u : (u | 0x80000000u);
}
float floatFromOrdered(uint u) { return uintBitsToFloat((u & 0x80000000u) != 0u ? (u & 0x7FFFFFFFu) : ~u); }

bool finite(float v) { return !isnan(v) && !isinf(v); }

// The image's "nothing here" value (DebugImage::noData), when it has one.
bool noData(float v) { return u_display.mode.y != 0 && v == u_display.range.z; }
