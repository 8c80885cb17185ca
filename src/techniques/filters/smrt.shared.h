#pragma once
// The smrt filter's uniform block, declared once for C++ and GLSL.
#include "shared/Cpp.h"

PN_GPU_BEGIN

// The rays per pixel and the steps per ray are compiled in as PN_SMRT_RAYS and PN_SMRT_STEPS.
struct SmrtUniforms {
  vec4 params;   // x: constant bias (linear depth), y: slope bias (texels), z: thickness (m), w: unused
  vec4 spatial;  // x: the spatial filter's radius (pixels, 0 = off); yzw: unused
};

PN_GPU_END

#ifdef __cplusplus
static_assert(sizeof(penumbra::gpu::SmrtUniforms) == 32, "std140 size of SmrtUniforms");
#endif
