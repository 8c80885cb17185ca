#pragma once
// The minimal lookup kernels' uniform block and kinds (micro/lookup.comp.glsl,
// report/VisibilityBaselines.cpp), declared once for C++ and GLSL.
#include "shared/Cpp.h"

// LOOKUP_KIND: which filter's lookup the kernel does.
#define PN_LOOKUP_COMPARE 0   // hard: one texel fetch and compare
#define PN_LOOKUP_BOX 1       // pcf: a LOOKUP_SIDE² box of fetch-and-compares (or hardware 2x2 compares)
#define PN_LOOKUP_MOMENTS2 2  // vsm: one trilinear tap of the (z, z²) chain + Chebyshev
#define PN_LOOKUP_MOMENTS4 3  // msm: one trilinear tap of the four-moment chain + Hamburger 4MSM
#define PN_LOOKUP_SAT 4       // vssm: one exact box mean of the (z, z²) summed-area table + Chebyshev

PN_GPU_BEGIN

struct LookupUniforms {
  // The one matrix: rows 0, 1, 3 are the view's clipFromWorld taken to map uv (uv = xy / w), row 2
  // is its depth plane (linear light depth, not divided by w).
  mat4 mapFromWorld;
  // x: depth bias (linear depth), y: box tap spacing (uv), z: mip level (moments) or box
  // half-size (texels, SAT), w: variance floor (linear depth², Chebyshev) or moment bias α (msm)
  vec4 params;
  ivec4 mapSize;  // xy: the map's (and the summed-area table's) texels per side; zw: unused
};

PN_GPU_END

#ifdef __cplusplus
static_assert(sizeof(penumbra::gpu::LookupUniforms) == 96, "std140 size of LookupUniforms");
#endif
