#pragma once
// The minimal lookup kernels' uniform block and kinds (micro/lookup.glsl,
// bench/VisibilityBaselines.cpp), declared once for C++ and GLSL.
#include "shared/Cpp.h"

// LOOKUP_KIND: which filter's lookup the kernel does.
#define PN_LOOKUP_COMPARE 0   // hard: one texel fetch and compare
#define PN_LOOKUP_BOX 1       // pcf: a LOOKUP_SIDE² box of fetch-and-compares (or hardware 2x2 compares)
#define PN_LOOKUP_MOMENTS2 2  // vsm: one trilinear tap of the (z, z²) chain + Chebyshev
#define PN_LOOKUP_MOMENTS4 3  // msm: one trilinear tap of the four-moment chain + Hamburger 4MSM
#define PN_LOOKUP_SAT 4       // vssm: one exact box mean of the (z, z²) summed-area table + Chebyshev
#define PN_LOOKUP_POISSON 5   // pcf: LOOKUP_SIDE² fetch-and-compares on the Poisson disk, turned per pixel as pcf's
#define PN_LOOKUP_MARCH 6     // smrt: LOOKUP_RAYS rays toward the sun's disk, LOOKUP_STEPS fetch-and-compares each
// LOOKUP_FOOTPRINT (with MOMENTS2 or MOMENTS4): the tap is the pixel's footprint (ray differentials
// against the tangent plane, anisotropic trilinear taps: common/footprint.glsl) instead of one
// trilinear tap at the filter's width.

PN_GPU_BEGIN

struct LookupUniforms {
  // The one matrix: rows 0, 1, 3 are the view's clipFromWorld taken to map uv (uv = xy / w), row 2
  // is its depth plane (linear light depth, not divided by w).
  mat4 mapFromWorld;
  // x: depth bias (linear depth), y: box tap spacing or Poisson radius (uv), or the footprint's
  // minimum width (texels), z: mip level (moments) or box half-size (texels, SAT), w: variance
  // floor (linear depth², Chebyshev) or moment bias α (msm)
  vec4 params;
  ivec4 mapSize;  // xy: the map's (and the summed-area table's) texels per side; z: the footprint's
                  // most taps; w: unused
  // The camera, for the footprint: its position (xyz, m), its forward axis, and the change of a
  // camera ray's direction (at unit view depth, world space) from one pixel to the next in x and y.
  vec4 cameraPosition;
  vec4 cameraForward;
  vec4 rayStepX;
  vec4 rayStepY;
  vec4 light;  // the march: xyz, the unit vector toward the sun; w, the tangent of its angular radius
};

PN_GPU_END

#ifdef __cplusplus
static_assert(sizeof(penumbra::gpu::LookupUniforms) == 176, "std140 size of LookupUniforms");
#endif
