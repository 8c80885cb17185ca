#pragma once
// The vsm filter's uniform block, declared once for C++ and GLSL.
#include "shared/Cpp.h"

PN_GPU_BEGIN

// The footprint switch is compiled in (FootprintParams.h).
struct VsmUniforms {
  vec4 params;  // x: minimum variance (texels², common/shadow.glsl's texelDepthVariance), y: light-bleeding
                // reduction amount [0, 1), z: minimum filter width (texels), w: unused
  ivec4 mode;   // x: maximum anisotropic taps along the footprint's long axis; yzw: unused
};

PN_GPU_END

#ifdef __cplusplus
static_assert(sizeof(penumbra::gpu::VsmUniforms) == 32, "std140 size of VsmUniforms");
#endif
