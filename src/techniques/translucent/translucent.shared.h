#pragma once
// The translucent add-on's uniform block, declared once for C++ and GLSL.
#include "shared/Cpp.h"

PN_GPU_BEGIN

// The box's half side (translucent.radiusTexels) is compiled in as PN_TRANSLUCENT_RADIUS.
struct TranslucentUniforms {
  vec4 params;  // x: unused, y: plane bias (texels of world size along the receiver's normal), zw: unused
};

PN_GPU_END

#ifdef __cplusplus
static_assert(sizeof(penumbra::gpu::TranslucentUniforms) == 16, "std140 size of TranslucentUniforms");
#endif
