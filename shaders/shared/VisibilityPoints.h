#pragma once
// World points at which the visibility pass evaluates V instead of the G-buffer's pixels
// (Renderer::visibilityAt: the shimmer measure keeps the points of one frame fixed while the
// camera, and with it the shadow maps, moves). std430 storage, declared once for C++ and GLSL.
#include "shared/Cpp.h"

PN_GPU_BEGIN

struct VisibilityPointGpu {
  vec4 position;   // xyz: world (m); w: unused
  vec4 geoNormal;  // xyz: unit geometric normal; w: unused
  ivec4 pixel;     // xy: the pixel the point was seen at (filters' per-pixel noise); zw: unused
};

PN_GPU_END

// The storage block's header: x = point count, y = width of the dispatch grid (points per row).
#define PN_POINTS_GRID_WIDTH 256

#ifdef __cplusplus
static_assert(sizeof(penumbra::gpu::VisibilityPointGpu) == 48, "std430 size of VisibilityPointGpu");
#endif
