#pragma once
// Per-frame uniforms and per-object data, declared once for C++ and GLSL.
#include "shared/Cpp.h"
#include "shared/Enums.h"

PN_GPU_BEGIN

// One light as every pass sees it: the frame's shadowing light (FrameUniforms::light) and each
// light of the lit pass's list (PN_SSBO_LIGHTS).
struct LightGpu {
  vec4 direction;  // xyz: unit, from the light toward the scene; w: PN_LIGHT_*
  vec4 position;   // xyz: spot or point position (m); w: unused
  vec4 radiance;   // rgb: colour × intensity; w: light size (sphere radius m | sun angular radius rad)
  vec4 cone;       // x: cos(spot outer half angle), y: cos(inner half angle), z: range (m, 0 = none), w: unused
};

struct FrameUniforms {
  mat4 clipFromWorld;    // the camera's projection × view (Penumbra's own: reversed-Z)
  mat4 viewFromWorld;
  mat4 worldFromClip;    // inverse of clipFromWorld: unprojects the depth texture (PN_SURFACE_FROM_DEPTH)
  vec4 cameraPosition;   // xyz: world (m)
  LightGpu light;        // the light this pass shadows
  vec4 ambient;          // rgb: ambient radiance
  ivec4 screen;          // x, y: size in pixels; z: frame index; w: sampling frame (0 unless V accumulates over frames)
  vec4 sceneInfo;        // x: scene bounding radius (m); yzw: unused
  vec4 depthInfo;        // ndc.z = x · stored depth + y; z: the stored depth of background pixels; w: unused
};

struct ObjectGpu {
  mat4 worldFromObject;
  mat4 normalFromObject;  // inverse transpose of the upper 3x3, in a mat4 for std140
  vec4 baseColor;         // rgb linear; a: alpha cutoff (0 = opaque)
  ivec4 material;         // x: texture layer or -1; y: alpha-mask flag; z: 1 = translucent caster (CasterSet), baseColor.rgb then its transmittance; w: unused
};

PN_GPU_END

#ifdef __cplusplus
static_assert(sizeof(penumbra::gpu::FrameUniforms) == 3 * 64 + 9 * 16, "std140 size of FrameUniforms");
static_assert(sizeof(penumbra::gpu::LightGpu) == 4 * 16, "std140/std430 size of LightGpu");
static_assert(offsetof(penumbra::gpu::FrameUniforms, light) == 192 + 16, "std140 offset");
static_assert(sizeof(penumbra::gpu::ObjectGpu) == 2 * 64 + 2 * 16, "std430 size of ObjectGpu");
#endif
