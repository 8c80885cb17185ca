// The GL error policy (STYLE.md, Errors): a GL error raised by a call becomes penumbra::Error
// from throwIfGlError, naming where it happened — with the debug-message callback (Debug builds,
// and this fixture's context) carrying the driver's message, and without it (Release) through
// glGetError. Each error is reported once: the next check is clean.
#include "GlFixture.h"

#include "gl/Debug.h"

#include <penumbra/Error.h>

#include <epoxy/gl.h>

#include <string>

using namespace penumbra;
using namespace penumbra::test;

namespace {

constexpr GLenum kNotATextureTarget = 0x1234;  // no GL enum: GL_INVALID_ENUM
constexpr GLuint kNoSuchBuffer = 987654;       // never created: DSA calls raise GL_INVALID_OPERATION

// The message of the Error that throwIfGlError(where) throws, or "" if it does not throw.
std::string errorFrom(const char* where) {
  try {
    gl::throwIfGlError(where);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(GlError, DebugCallbackTurnsAnInvalidEnumIntoAnErrorOnce) {
  glContext();
  ASSERT_EQ(errorFrom("set-up"), "") << "a GL error was pending before the test";
  ASSERT_TRUE(glIsEnabled(GL_DEBUG_OUTPUT)) << "the GL test fixture asks for the debug callback";
  glBindTexture(kNotATextureTarget, 0);
  const std::string m = errorFrom("the invalid bind");
  std::printf("debug callback: %s\n", m.c_str());
  EXPECT_NE(m.find("OpenGL error in the invalid bind: "), std::string::npos) << m;
  // The driver's own words, not just a code: the callback's message is longer than "glGetError 0x0500".
  EXPECT_EQ(m.find("glGetError"), std::string::npos) << m;
  EXPECT_EQ(errorFrom("the next pass"), "") << "the same error was reported twice";
}

TEST(GlError, DsaCallOnAMissingObjectThrows) {
  glContext();
  ASSERT_EQ(errorFrom("set-up"), "");
  const float data = 1.0f;
  glNamedBufferSubData(kNoSuchBuffer, 0, sizeof(data), &data);
  const std::string m = errorFrom("the missing buffer");
  std::printf("DSA on a missing name: %s\n", m.c_str());
  EXPECT_NE(m.find("OpenGL error in the missing buffer: "), std::string::npos) << m;
  EXPECT_EQ(errorFrom("the next pass"), "");
}

// Release builds install no callback (ContextOptions::debug = kDebugBuild): glGetError still
// catches the error at the next check.
TEST(GlError, WithoutTheDebugCallbackGlGetErrorStillThrows) {
  glContext();
  ASSERT_EQ(errorFrom("set-up"), "");
  glDisable(GL_DEBUG_OUTPUT);
  glBindTexture(kNotATextureTarget, 0);
  const std::string m = errorFrom("the invalid bind");
  glEnable(GL_DEBUG_OUTPUT);
  std::printf("no callback: %s\n", m.c_str());
  // The code by name (release builds, where users meet it, have no callback).
  EXPECT_NE(m.find("OpenGL error in the invalid bind: GL_INVALID_ENUM"), std::string::npos) << m;
  EXPECT_EQ(errorFrom("the next pass"), "");
}
