#pragma once
// A paged (virtual) projection's uniforms (frame/VirtualPages.h, common/shadow.glsl): how each
// pixel's level is chosen. The layout itself (page size, pages per side, the pool's tiles) is
// compiled into the passes that read it (PN_PAGE_SIZE, PN_PAGES_PER_SIDE, PN_POOL_TILES_PER_SIDE).
#include "shared/Cpp.h"

PN_GPU_BEGIN

struct PagesUniforms {
  // x: log2 of level 0's texel size (m); y: a pixel's width per metre of distance from the camera
  // (an orthographic camera: the pixel's width, m); z: level bias (levels, + = coarser);
  // w: margin (texels) marked around each pixel's texel
  vec4 lod;
  // x: grazing levels (at most this many levels finer where the camera grazes the surface more
  // than the light does); y: levels of each virtual map (the views; a point light's: a sixth of
  // them, face after face); z: the levels a pixel reads, the first this many of each map (a
  // perspective view's coarser ones only serve reads past the resident pages); w: unused
  vec4 shape;
};

PN_GPU_END

#ifdef __cplusplus
static_assert(sizeof(penumbra::gpu::PagesUniforms) == 32, "std140 size of PagesUniforms");
#endif
