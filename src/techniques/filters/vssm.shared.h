#pragma once
// The vssm filter's uniform block, declared once for C++ and GLSL.
#include "shared/Cpp.h"

PN_GPU_BEGIN

// The source (vssm.source) is compiled in as PN_VSSM_SOURCE.
struct VssmUniforms {
  vec4 params;  // x: minimum variance (texels², common/shadow.glsl), y: light-bleeding reduction [0, 1),
                // z: minimum filter radius (texels), w: maximum search/filter radius (texels)
  ivec4 mode;   // x: maximum anisotropic taps (source=mip), y: sub-boxes per axis (source=mip); zw: unused
};

PN_GPU_END

// vssm.source
#define PN_VSSM_SOURCE_SAT 0
#define PN_VSSM_SOURCE_MIP 1

#ifdef __cplusplus
static_assert(sizeof(penumbra::gpu::VssmUniforms) == 32, "std140 size of VssmUniforms");
#endif
