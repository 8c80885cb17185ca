#pragma once
// The light's shadow views (one per cascade), declared once for C++ and GLSL.
#include "shared/Cpp.h"
#include "shared/Bindings.h"

PN_GPU_BEGIN

struct ShadowViewGpu {
  mat4 clipFromWorld;  // rasterisation and lookup: ndc.xy * 0.5 + 0.5 = map uv
  vec4 depthPlane;     // linear light depth in [0,1] = dot(depthPlane, vec4(ws, 1))
  vec4 range;          // x: near (m), y: far (m), z: 1 = perspective / 0 = orthographic, w: split far (view depth, m)
  vec4 extent;         // xy: ortho: map extent (m); perspective: extent at 1 m (2 tan(half fov)); z: blend band (m); w: 1 = warped (psm/tsm: texel size from clipFromWorld's derivatives)
};

struct ShadowUniforms {
  ShadowViewGpu views[PN_MAX_SHADOW_VIEWS];
  ivec4 info;  // x: view count, y: map size (texels), z: projection kind (PN_PROJ_*), w: debug flags
};

PN_GPU_END

#ifdef __cplusplus
static_assert(sizeof(penumbra::gpu::ShadowViewGpu) == 64 + 3 * 16, "std140 size of ShadowViewGpu");
static_assert(sizeof(penumbra::gpu::ShadowUniforms) == PN_MAX_SHADOW_VIEWS * 112 + 16, "std140 size of ShadowUniforms");
#endif
