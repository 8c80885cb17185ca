#pragma once
// The msm filter's uniform block, declared once for C++ and GLSL.
#include "shared/Cpp.h"

PN_GPU_BEGIN

struct MsmUniforms {
  vec4 params;  // x: moment bias (texels², see common/moments.glsl), y: depth bias (linear depth), z: minimum filter
                // width (texels), w: unused
  ivec4 mode;   // x: maximum anisotropic taps, y: 1 = moments stored in the 16-bit basis, z: 1 = filter
                // over the pixel's footprint, 0 = a fixed filter of params.z texels; w: unused
};

PN_GPU_END

#ifdef __cplusplus
static_assert(sizeof(penumbra::gpu::MsmUniforms) == 32, "std140 size of MsmUniforms");
#endif
