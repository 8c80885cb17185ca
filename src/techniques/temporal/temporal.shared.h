#pragma once
// The temporal accumulation pass's uniform block, declared once for C++ and GLSL.
#include "shared/Cpp.h"

PN_GPU_BEGIN

struct TemporalUniforms {
  mat4 previousClipFromWorld;  // the camera of the frame the history was accumulated in
  vec4 blend;   // x: weight of this frame's V (temporal.alpha), y: surface tolerance (pixel footprints),
                // z: a pixel's footprint per metre of camera distance (orthographic: in metres),
                // w: 1 where the history is valid
  vec4 clip;    // x: PN_TEMPORAL_CLAMP_* (temporal.clamp), y: variance clip width (σ),
                // z: difference from the history beyond which this frame's V is taken (temporal.snapV), w: unused
  ivec4 layer;  // x: the light's layer of the visibility array; yzw: unused
};

PN_GPU_END

// temporal.clamp: how the history is held to this frame's 3×3 neighbourhood of V.
#define PN_TEMPORAL_CLAMP_OFF 0
#define PN_TEMPORAL_CLAMP_MINMAX 1
#define PN_TEMPORAL_CLAMP_VARIANCE 2

#ifdef __cplusplus
static_assert(sizeof(penumbra::gpu::TemporalUniforms) == 64 + 3 * 16, "std140 size of TemporalUniforms");
#endif
