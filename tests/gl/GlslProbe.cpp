#include "GlslProbe.h"

#include "GlFixture.h"
#include "shared/Bindings.h"

#include <penumbra/Error.h>

#include <fmt/format.h>

#include <optional>

namespace penumbra::test {

gl::Program compileProbe(const std::string& label, const std::string& main, const ShaderDefines& defines) {
  const std::string key = label + ".probe.glsl";
  ShaderLibrary lib;
  const ExpandedSource src = expandIncludes({key}, [&](std::string_view k) -> std::optional<std::string> {
    if (k == key) return main;
    return lib.source(k);
  });
  const std::string text = "#version 450 core\n" + defines.prelude() + src.text;
  const GLuint shader = glCreateShader(GL_COMPUTE_SHADER);
  const char* ptr = text.c_str();
  glShaderSource(shader, 1, &ptr, nullptr);
  glCompileShader(shader);
  GLint ok = 0, length = 0;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
    std::string log(static_cast<size_t>(std::max(length, 1)), '\0');
    glGetShaderInfoLog(shader, length, nullptr, log.data());
    glDeleteShader(shader);
    throw Error(fmt::format("probe '{}' failed to compile:\n{}", label, remapShaderLog(log.c_str(), src.files)));
  }
  const GLuint program = glCreateProgram();
  glAttachShader(program, shader);
  glLinkProgram(program);
  glDeleteShader(shader);
  glGetProgramiv(program, GL_LINK_STATUS, &ok);
  if (!ok) {
    glGetProgramiv(program, GL_INFO_LOG_LENGTH, &length);
    std::string log(static_cast<size_t>(std::max(length, 1)), '\0');
    glGetProgramInfoLog(program, length, nullptr, log.data());
    glDeleteProgram(program);
    throw Error(fmt::format("probe '{}' failed to link:\n{}", label, log.c_str()));
  }
  return gl::Program(label, program);
}

std::vector<glm::vec4> runProbeCases(const std::string& label, const std::string& main,
                                     const std::vector<glm::vec4>& inputs, const ShaderDefines& defines) {
  glContext();
  const gl::Program program = compileProbe(label, main, defines);
  gl::Buffer in(label + " in", inputs.size() * sizeof(glm::vec4), inputs.data());
  std::vector<glm::vec4> out(inputs.size(), glm::vec4(-1.0f));
  gl::Buffer outBuffer(label + " out", out.size() * sizeof(glm::vec4), out.data());
  in.bindBase(GL_SHADER_STORAGE_BUFFER, PN_SSBO_AUX);
  outBuffer.bindBase(GL_SHADER_STORAGE_BUFFER, PN_SSBO_TEST);
  program.use();
  glDispatchCompute(static_cast<GLuint>(inputs.size()), 1, 1);
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  outBuffer.download(out.data(), out.size() * sizeof(glm::vec4));
  return out;
}

}  // namespace penumbra::test
