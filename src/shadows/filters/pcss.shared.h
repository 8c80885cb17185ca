#pragma once
// The pcss filter's uniform block, declared once for C++ and GLSL. Patterns are PN_KERNEL_*.
#include "shadows/filters/pcf.shared.h"

PN_GPU_BEGIN

struct PcssUniforms {
  vec4 params;   // x: constant bias (linear depth), y: slope bias (texels), z: min filter radius (texels), w: max radius (texels)
  ivec4 config;  // x: blocker-search taps, y: filter taps, z: pattern PN_KERNEL_*, w: unused
};

PN_GPU_END

#ifdef __cplusplus
static_assert(sizeof(penumbra::gpu::PcssUniforms) == 32, "std140 size of PcssUniforms");
#endif
