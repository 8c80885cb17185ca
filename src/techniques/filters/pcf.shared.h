#pragma once
// The pcf filter's uniform block and its kernel enum (also pcss's sampling pattern), declared
// once for C++ and GLSL.
#include "shared/Cpp.h"

// pcf.kernel / pcss.pattern
#define PN_KERNEL_BOX 0
#define PN_KERNEL_POISSON 1

PN_GPU_BEGIN

// The kernel (pcf.kernel, PN_KERNEL_*) and the Poisson taps (pcf.samples) are compiled in as
// PN_PCF_KERNEL and PN_PCF_SAMPLES.
struct PcfUniforms {
  vec4 params;   // x: radius (texels), y: constant bias (linear depth), z: slope bias (texels), w: plane bias (texels)
};

PN_GPU_END

#ifdef __cplusplus
static_assert(sizeof(penumbra::gpu::PcfUniforms) == 16, "std140 size of PcfUniforms");
#endif
