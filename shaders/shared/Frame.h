#pragma once
// Per-frame uniforms and per-object data, declared once for C++ and GLSL.
#include "shared/Cpp.h"
#include "shared/Enums.h"

PN_GPU_BEGIN

struct FrameUniforms {
  mat4 clipFromWorld;    // the camera's projection × view (Penumbra's own: reversed-Z)
  mat4 viewFromWorld;
  mat4 worldFromClip;    // inverse of clipFromWorld: unprojects the depth texture (PN_SURFACE_FROM_DEPTH)
  vec4 cameraPosition;   // xyz: world (m)
  vec4 lightDirection;   // xyz: unit, from the light toward the scene; w: PN_LIGHT_*
  vec4 lightPosition;    // xyz: spot or point position (m); w: unused
  vec4 lightRadiance;    // rgb: colour × intensity; w: light size (spot radius m | sun angular radius rad)
  vec4 ambient;          // rgb: ambient radiance
  ivec4 screen;          // x, y: size in pixels; z: frame index; w: unused
  vec4 sceneInfo;        // x: scene bounding radius (m); yzw: unused
  vec4 depthInfo;        // ndc.z = x · stored depth + y; z: the stored depth of background pixels; w: unused
  vec4 lightCone;        // x: cos(spot outer half angle), y: cos(inner half angle), z: range (m, 0 = none), w: unused
};

struct ObjectGpu {
  mat4 worldFromObject;
  mat4 normalFromObject;  // inverse transpose of the upper 3x3, in a mat4 for std140
  vec4 baseColor;         // rgb linear; a: alpha cutoff (0 = opaque)
  ivec4 material;         // x: texture layer or -1; y: alpha-mask flag; zw: unused
};

PN_GPU_END

#ifdef __cplusplus
static_assert(sizeof(penumbra::gpu::FrameUniforms) == 3 * 64 + 9 * 16, "std140 size of FrameUniforms");
static_assert(offsetof(penumbra::gpu::FrameUniforms, lightRadiance) == 192 + 48, "std140 offset");
static_assert(sizeof(penumbra::gpu::ObjectGpu) == 2 * 64 + 2 * 16, "std430 size of ObjectGpu");
#endif
