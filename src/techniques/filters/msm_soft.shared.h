#pragma once
// The msm-soft filter's uniform block, declared once for C++ and GLSL.
#include "shared/Cpp.h"

PN_GPU_BEGIN

struct MsmSoftUniforms {
  vec4 params;  // x: moment bias (texels²), y: depth bias (linear depth), z: minimum filter radius (texels),
                // w: maximum search/filter radius (texels)
};

PN_GPU_END

#ifdef __cplusplus
static_assert(sizeof(penumbra::gpu::MsmSoftUniforms) == 16, "std140 size of MsmSoftUniforms");
#endif
