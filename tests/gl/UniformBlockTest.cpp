// The shared headers' C++ layout must match what the driver computes for std140.
#include "GlFixture.h"

#include "shader/ShaderLibrary.h"
#include "shared/Frame.h"
#include "shared/Shadow.h"

using namespace penumbra;

namespace {

GLint offsetOf(GLuint program, const char* name) {
  const GLuint index = glGetProgramResourceIndex(program, GL_UNIFORM, name);
  if (index == GL_INVALID_INDEX) {
    GLint count = 0;
    glGetProgramInterfaceiv(program, GL_UNIFORM, GL_ACTIVE_RESOURCES, &count);
    std::string names;
    for (GLint i = 0; i < count; ++i) {
      char buf[256];
      glGetProgramResourceName(program, GL_UNIFORM, static_cast<GLuint>(i), sizeof buf, nullptr, buf);
      names += std::string(" ") + buf;
    }
    ADD_FAILURE() << name << " is not an active uniform; active:" << names;
    return -1;
  }
  const GLenum prop = GL_OFFSET;
  GLint offset = -1;
  glGetProgramResourceiv(program, GL_UNIFORM, index, 1, &prop, 1, nullptr, &offset);
  return offset;
}

}  // namespace

TEST(UniformBlocks, DriverOffsetsMatchCpp) {
  test::glContext();
  ShaderLibrary lib;
  // A probe main that uses every member, so none is optimised away.
  const std::string main = R"(
#include "common/frame.glsl"
layout(local_size_x = 1) in;
layout(std430, binding = PN_SSBO_TEST) buffer Out { vec4 o[]; };
void main() {
  o[0] = u_frame.clipFromWorld[0] + u_frame.viewFromWorld[1] + u_frame.cameraPosition + u_frame.light.direction +
         u_frame.light.position + u_frame.light.radiance + u_frame.ambient + vec4(u_frame.screen) + u_frame.sceneInfo +
         u_frame.worldFromClip[3] + u_frame.depthInfo;
  o[1] = u_shadow.views[1].clipFromWorld[2] + u_shadow.views[1].depthPlane + u_shadow.views[1].range +
         u_shadow.views[1].extent + vec4(u_shadow.info);
})";
  const ExpandedSource src = expandIncludes({"probe.glsl"}, [&](std::string_view key) -> std::optional<std::string> {
    if (key == "probe.glsl") return main;
    return lib.source(key);
  });
  const std::string text = "#version 450 core\n" + src.text;
  const GLuint shader = glCreateShader(GL_COMPUTE_SHADER);
  const char* ptr = text.c_str();
  glShaderSource(shader, 1, &ptr, nullptr);
  glCompileShader(shader);
  GLint ok = 0;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  ASSERT_TRUE(ok);
  const GLuint program = glCreateProgram();
  glAttachShader(program, shader);
  glLinkProgram(program);
  glGetProgramiv(program, GL_LINK_STATUS, &ok);
  ASSERT_TRUE(ok);
  using gpu::FrameUniforms;
  using gpu::ShadowUniforms;
  using gpu::ShadowViewGpu;
  EXPECT_EQ(offsetOf(program, "u_frame.clipFromWorld"), GLint(offsetof(FrameUniforms, clipFromWorld)));
  EXPECT_EQ(offsetOf(program, "u_frame.cameraPosition"), GLint(offsetof(FrameUniforms, cameraPosition)));
  EXPECT_EQ(offsetOf(program, "u_frame.light.radiance"), GLint(offsetof(FrameUniforms, light) + offsetof(gpu::LightGpu, radiance)));
  EXPECT_EQ(offsetOf(program, "u_frame.screen"), GLint(offsetof(FrameUniforms, screen)));
  EXPECT_EQ(offsetOf(program, "u_frame.sceneInfo"), GLint(offsetof(FrameUniforms, sceneInfo)));
  EXPECT_EQ(offsetOf(program, "u_frame.worldFromClip"), GLint(offsetof(FrameUniforms, worldFromClip)));
  EXPECT_EQ(offsetOf(program, "u_frame.depthInfo"), GLint(offsetof(FrameUniforms, depthInfo)));
  const GLint view1 = GLint(sizeof(ShadowViewGpu));
  EXPECT_EQ(offsetOf(program, "u_shadow.views[1].depthPlane"), view1 + GLint(offsetof(ShadowViewGpu, depthPlane)));
  EXPECT_EQ(offsetOf(program, "u_shadow.views[1].extent"), view1 + GLint(offsetof(ShadowViewGpu, extent)));
  EXPECT_EQ(offsetOf(program, "u_shadow.info"), GLint(offsetof(ShadowUniforms, info)));
  glDeleteShader(shader);
  glDeleteProgram(program);
}
