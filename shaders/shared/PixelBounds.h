#pragma once
// The pixel-bounds reduction (passes/pixel_bounds.comp.glsl, frame/PixelBoundsReducer): the
// bounds, in a space the caller chooses, of the covered pixels that face the light, one box per
// slice of camera depth. Declared once for C++ and GLSL.
#include "shared/Cpp.h"

// Slices per dispatch: one per shadow view (cascade).
#define PN_PIXEL_BOUNDS_SLICES 8

PN_GPU_BEGIN

// Uniform block (binding PN_UBO_FILTER: the reduction runs before any filter's pass).
struct PixelBoundsUniforms {
  mat4 spaceFromWorld;  // where the bounds are taken (a light's view; the camera's for the depth range)
  vec4 sliceNear[2];    // slice i covers camera depths [sliceNear[i/4][i%4], sliceFar[i/4][i%4]] (m)
  vec4 sliceFar[2];
  ivec4 info;           // x: slice count
};

PN_GPU_END

// The storage block: per slice, 6 uints (min x, y, z then max x, y, z) holding floats in an order
// that unsigned comparison keeps (pixelBoundsKey), so atomicMin/atomicMax reduce floats.
#define PN_PIXEL_BOUNDS_WORDS 6

#ifdef __cplusplus
static_assert(sizeof(penumbra::gpu::PixelBoundsUniforms) == 64 + 64 + 16, "std140 size of PixelBoundsUniforms");
#endif
