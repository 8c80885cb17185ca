#pragma once
// Included by the shared headers only when compiled as C++: GLSL's type names as glm aliases,
// so one struct declaration serves both languages (std140: scalars in fours, vec4, mat4).
#ifdef __cplusplus
#include <glm/glm.hpp>
#include <cstddef>
#include <cstdint>
namespace penumbra::gpu {
using vec4 = glm::vec4;
using ivec4 = glm::ivec4;
using uvec4 = glm::uvec4;
using mat4 = glm::mat4;
}  // namespace penumbra::gpu
#define PN_GPU_BEGIN namespace penumbra::gpu {
#define PN_GPU_END }
#define PN_SHARED_FN inline  // a function written once for both languages (GLSL's subset of C++)
#else
#define PN_GPU_BEGIN
#define PN_GPU_END
#define PN_SHARED_FN
#endif
