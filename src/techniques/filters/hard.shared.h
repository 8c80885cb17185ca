#pragma once
// The hard filter's uniform block, declared once for C++ and GLSL.
#include "shared/Cpp.h"
#include "shared/Enums.h"

PN_GPU_BEGIN

// The bias mode (hard.bias, PN_BIAS_*) is compiled in as PN_HARD_BIAS.
struct HardUniforms {
  vec4 bias;   // x: constant (linear depth units), y: slope scale (× texel size · tan θ), z: normal offset (texels), w: plane bias (texels of world size along the receiver's normal)
};

PN_GPU_END

#ifdef __cplusplus
static_assert(sizeof(penumbra::gpu::HardUniforms) == 16, "std140 size of HardUniforms");
#endif
