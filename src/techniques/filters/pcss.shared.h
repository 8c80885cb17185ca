#pragma once
// The pcss filter's uniform block, declared once for C++ and GLSL. Patterns are PN_KERNEL_*.
#include "techniques/filters/pcf.shared.h"

PN_GPU_BEGIN

// The blocker-search and filter taps and the pattern (PN_KERNEL_*) are compiled in as
// PN_PCSS_BLOCKER_SAMPLES, PN_PCSS_FILTER_SAMPLES and PN_PCSS_PATTERN.
struct PcssUniforms {
  vec4 params;   // x: constant bias (linear depth), y: slope bias (texels), z: min filter radius (texels), w: max radius (texels)
  vec4 bias;     // x: plane bias (texels), yzw: unused
};

PN_GPU_END

#ifdef __cplusplus
static_assert(sizeof(penumbra::gpu::PcssUniforms) == 32, "std140 size of PcssUniforms");
#endif
