#pragma once
// The msm filter's uniform block, declared once for C++ and GLSL.
#include "shared/Cpp.h"

PN_GPU_BEGIN

// The storage (msm.storage: 1 = moments in the 16-bit basis) is compiled in as PN_MSM_QUANTIZED,
// the footprint switch as FootprintParams.h says.
struct MsmUniforms {
  vec4 params;  // x: moment bias (texels², see common/moments.glsl), y: depth bias (linear depth), z: minimum filter
                // width (texels), w: (light map size / translucent maps' size)², the moment bias's factor on the
                // translucent maps (msm.translucent)
  ivec4 mode;   // x: maximum anisotropic taps along the footprint's long axis; yzw: unused
};

PN_GPU_END

#ifdef __cplusplus
static_assert(sizeof(penumbra::gpu::MsmUniforms) == 32, "std140 size of MsmUniforms");
#endif
