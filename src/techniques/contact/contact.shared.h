#pragma once
// The contact-shadow pass's uniform block, declared once for C++ and GLSL.
#include "shared/Cpp.h"

PN_GPU_BEGIN

// The step count (contact.steps) is compiled in as PN_CONTACT_STEPS.
struct ContactUniforms {
  vec4 march;  // x: march length (m), y: thickness (m), z: start offset along the normal (m),
               // w: depth tolerance (metres per metre of camera distance)
};

PN_GPU_END

#ifdef __cplusplus
static_assert(sizeof(penumbra::gpu::ContactUniforms) == 16, "std140 size of ContactUniforms");
#endif
