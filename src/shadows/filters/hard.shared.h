#pragma once
// The hard filter's uniform block, declared once for C++ and GLSL.
#include "shared/Cpp.h"
#include "shared/Enums.h"

PN_GPU_BEGIN

struct HardUniforms {
  vec4 bias;   // x: constant (linear depth units), y: slope scale (× texel size · tan θ), z: normal offset (texels), w: unused
  ivec4 mode;  // x: PN_BIAS_*; yzw: unused
};

PN_GPU_END

#ifdef __cplusplus
static_assert(sizeof(penumbra::gpu::HardUniforms) == 32, "std140 size of HardUniforms");
#endif
