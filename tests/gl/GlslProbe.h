#pragma once
// GLSL unit tests: a test's own compute `main` (which #includes library files by key) compiled
// into a program, run, and its results read back from a storage buffer at PN_SSBO_TEST.
#include "gl/Objects.h"
#include "shader/ShaderLibrary.h"

#include <string>

namespace penumbra::test {

/// Compiles `main` as a compute program with `defines` before it. Throws penumbra::Error with
/// the driver log mapped to file:line when it does not compile or link.
gl::Program compileProbe(const std::string& label, const std::string& main, const ShaderDefines& defines = {});

}  // namespace penumbra::test
