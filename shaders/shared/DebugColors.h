#pragma once
// Colours of the debug views, written once and compiled as C++ (the viewer's legends) and as
// GLSL (the lit pass's PN_VIEW_CASCADES tint, the viewer's display pass): a legend shows exactly
// the colours the picture uses.
#include "shared/Cpp.h"

PN_GPU_BEGIN

// The PN_VIEW_CASCADES tint of cascade `index`, cycled beyond four cascades; alpha 1.
PN_SHARED_FN vec4 cascadeColor(int index) {
  int k = index % 4;
  if (k == 0) return vec4(1.0f, 0.35f, 0.3f, 1.0f);
  if (k == 1) return vec4(0.35f, 0.9f, 0.35f, 1.0f);
  if (k == 2) return vec4(0.35f, 0.55f, 1.0f, 1.0f);
  return vec4(1.0f, 0.85f, 0.3f, 1.0f);
}

// Google's Turbo colour map, polynomial fit (Mikhailov 2019), of x in [0, 1] (clamped):
// display-referred RGB, alpha 1.
PN_SHARED_FN vec4 turboColor(float x) {
  const vec4 kRed4 = vec4(0.13572138f, 4.61539260f, -42.66032258f, 132.13108234f);
  const vec4 kGreen4 = vec4(0.09140261f, 2.19418839f, 4.84296658f, -14.18503333f);
  const vec4 kBlue4 = vec4(0.10667330f, 12.64194608f, -60.58204836f, 110.36276771f);
  const vec4 kRed2 = vec4(-152.94239396f, 59.28637943f, 0.0f, 0.0f);
  const vec4 kGreen2 = vec4(4.27729857f, 2.82956604f, 0.0f, 0.0f);
  const vec4 kBlue2 = vec4(-89.90310912f, 27.34824973f, 0.0f, 0.0f);
  float t = x < 0.0f ? 0.0f : (x > 1.0f ? 1.0f : x);
  vec4 v4 = vec4(1.0f, t, t * t, t * t * t);
  vec4 v2 = vec4(v4.z * v4.z, v4.w * v4.z, 0.0f, 0.0f);
  return vec4(dot(v4, kRed4) + dot(v2, kRed2), dot(v4, kGreen4) + dot(v2, kGreen2), dot(v4, kBlue4) + dot(v2, kBlue2), 1.0f);
}

PN_GPU_END
