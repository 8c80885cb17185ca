#pragma once
// The evsm-soft filter's uniform block, declared once for C++ and GLSL.
#include "shared/Cpp.h"

PN_GPU_BEGIN

struct EvsmSoftUniforms {
  vec4 warp;    // x: c+, y: c− (both within the storage's limit), z: the storage's relative variance floor
                // (exp_warp.shared.h), w: components (always 4)
  vec4 params;  // x: minimum variance (texels², through each warp's slope), y: light-bleeding reduction [0, 1),
                // z: minimum filter radius (texels), w: maximum search/filter radius (texels)
  ivec4 mode;   // x: maximum anisotropic taps per sub-box, y: sub-boxes per axis (mip split), zw: unused
};

PN_GPU_END

#ifdef __cplusplus
static_assert(sizeof(penumbra::gpu::EvsmSoftUniforms) == 48, "std140 size of EvsmSoftUniforms");
#endif
