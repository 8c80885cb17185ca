#pragma once
// The texel-density heatmap's colour ramp, written once and compiled as C++ (the heatmap image,
// comparison/TexelDensity.cpp) and as GLSL (the lit pass's PN_VIEW_TEXEL_DENSITY debug view).
// Input: log2 of the screen pixels covered by one shadow-map texel. 0 (one texel per pixel) is
// neutral grey; under-sampled (texels larger than pixels: blocky shadow edges) goes warm, to
// red at 2^PN_DENSITY_LOG2_HI pixels per texel; over-sampled (texels wasted) goes cool, to blue
// at 2^PN_DENSITY_LOG2_LO.
#include "shared/Cpp.h"

#define PN_DENSITY_LOG2_LO -4.0f
#define PN_DENSITY_LOG2_HI 6.0f

PN_GPU_BEGIN

// Display-referred RGB in [0,1] (written to the 8-bit image as is); alpha 1.
PN_SHARED_FN vec4 densityRampColor(float log2PixelsPerTexel) {
  const vec4 cool = vec4(0.15f, 0.35f, 0.95f, 1.0f);
  const vec4 neutral = vec4(0.85f, 0.85f, 0.82f, 1.0f);
  const vec4 warm = vec4(1.0f, 0.75f, 0.15f, 1.0f);
  const vec4 hot = vec4(0.85f, 0.1f, 0.08f, 1.0f);
  float x = log2PixelsPerTexel;
  if (x <= 0.0f) {
    float t = x / PN_DENSITY_LOG2_LO;
    t = t > 1.0f ? 1.0f : t;
    return neutral + (cool - neutral) * t;
  }
  float t = x / PN_DENSITY_LOG2_HI;
  t = t > 1.0f ? 1.0f : t;
  // Warm for the first half, red beyond: the eye reads "how bad" in two steps.
  return t < 0.5f ? neutral + (warm - neutral) * (2.0f * t) : warm + (hot - warm) * (2.0f * t - 1.0f);
}

PN_GPU_END
