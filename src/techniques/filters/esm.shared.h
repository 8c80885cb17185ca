#pragma once
// The esm filter's uniform block, declared once for C++ and GLSL.
#include "shared/Cpp.h"

PN_GPU_BEGIN

struct EsmUniforms {
  vec4 params;  // x: exponent c (exp_warp.shared.h's positive warp), y: minimum filter width (texels), zw: unused
  ivec4 mode;   // x: maximum anisotropic taps along the footprint's long axis; y: 1 = filter over the
                // pixel's footprint, 0 = a fixed filter of params.y texels; zw: unused
};

PN_GPU_END

#ifdef __cplusplus
static_assert(sizeof(penumbra::gpu::EsmUniforms) == 32, "std140 size of EsmUniforms");
#endif
