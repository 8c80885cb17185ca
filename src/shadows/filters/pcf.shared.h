#pragma once
// The pcf filter's uniform block and its kernel enum (also pcss's sampling pattern), declared
// once for C++ and GLSL.
#include "shared/Cpp.h"

// pcf.kernel / pcss.pattern
#define PN_KERNEL_BOX 0
#define PN_KERNEL_POISSON 1

PN_GPU_BEGIN

struct PcfUniforms {
  vec4 params;   // x: radius (texels), y: constant bias (linear depth), z: slope bias (texels), w: unused
  ivec4 config;  // x: PN_KERNEL_*, y: Poisson taps, zw: unused
};

PN_GPU_END

#ifdef __cplusplus
static_assert(sizeof(penumbra::gpu::PcfUniforms) == 32, "std140 size of PcfUniforms");
#endif
