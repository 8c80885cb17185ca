#pragma once
// GLSL unit tests: a test's own compute `main` (which #includes library files by key) compiled
// into a program, run, and its results read back from a storage buffer at PN_SSBO_TEST.
#include "gl/Objects.h"
#include "shader/ShaderLibrary.h"

#include <glm/glm.hpp>
#include <string>
#include <vector>

namespace penumbra::test {

/// Compiles `main` as a compute program with `defines` before it. Throws penumbra::Error with
/// the driver log mapped to file:line when it does not compile or link.
gl::Program compileProbe(const std::string& label, const std::string& main, const ShaderDefines& defines = {});

/// The declarations a case probe's `main` starts with: one invocation per case, its input
/// i_cases[gl_GlobalInvocationID.x] (PN_SSBO_AUX), its output o_results[...] (PN_SSBO_TEST).
inline constexpr const char* kProbeCaseHeader = R"(
#include "shared/Bindings.h"
layout(local_size_x = 1) in;
layout(std430, binding = PN_SSBO_AUX) readonly buffer In { vec4 i_cases[]; };
layout(std430, binding = PN_SSBO_TEST) writeonly buffer Out { vec4 o_results[]; };
)";

/// Compiles `main` (which starts with kProbeCaseHeader), runs it once per element of `inputs`
/// and returns one vec4 per case.
std::vector<glm::vec4> runProbeCases(const std::string& label, const std::string& main,
                                     const std::vector<glm::vec4>& inputs, const ShaderDefines& defines = {});

}  // namespace penumbra::test
