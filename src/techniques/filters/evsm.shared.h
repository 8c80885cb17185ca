#pragma once
// The evsm filter's uniform block, declared once for C++ and GLSL.
#include "shared/Cpp.h"

PN_GPU_BEGIN

struct EvsmUniforms {
  vec4 warp;    // x: c+, y: c− (both within the storage's limit), z: the storage's relative variance floor
                // (exp_warp.shared.h), w: components (2 or 4)
  vec4 params;  // x: minimum variance (texels², common/shadow.glsl's texelDepthVariance, through the warp's
                // slope), y: light-bleeding reduction [0, 1), z: minimum filter width (texels), w: unused
  ivec4 mode;   // x: maximum anisotropic taps along the footprint's long axis; y: 1 = filter over the
                // pixel's footprint, 0 = a fixed filter of params.z texels; zw: unused
};

PN_GPU_END

#ifdef __cplusplus
static_assert(sizeof(penumbra::gpu::EvsmUniforms) == 48, "std140 size of EvsmUniforms");
#endif
