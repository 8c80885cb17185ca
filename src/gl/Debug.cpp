#include "gl/Debug.h"

#include <penumbra/Error.h>

#include <fmt/format.h>

#include <cstdio>

namespace penumbra::gl {
namespace {

// The first GL error since the last check. The callback runs inside the driver, so it only
// records; throwIfGlError() throws from our own code (never unwind through the driver).
thread_local std::string tPendingError;

void GLAPIENTRY onDebugMessage(GLenum, GLenum type, GLuint, GLenum severity, GLsizei,
                               const GLchar* message, const void*) {
  if (type == GL_DEBUG_TYPE_ERROR) {
    if (tPendingError.empty()) tPendingError = message;
  } else if (severity == GL_DEBUG_SEVERITY_HIGH) {
    std::fprintf(stderr, "penumbra: GL: %s\n", message);
  }
}

// A glGetError code by name; out of memory says what usually causes it here.
std::string glErrorText(GLenum e) {
  switch (e) {
    case GL_INVALID_ENUM: return "GL_INVALID_ENUM";
    case GL_INVALID_VALUE: return "GL_INVALID_VALUE";
    case GL_INVALID_OPERATION: return "GL_INVALID_OPERATION";
    case GL_INVALID_FRAMEBUFFER_OPERATION: return "GL_INVALID_FRAMEBUFFER_OPERATION";
    case GL_OUT_OF_MEMORY:
      return "GL_OUT_OF_MEMORY (the shadow maps, the filter's tables or the image do not fit: try smaller maps (Technique::mapSize, "
             "or a light's shadow.mapSize in its scene file: LightShadowSettings::mapSize) or a smaller image)";
    case GL_STACK_OVERFLOW: return "GL_STACK_OVERFLOW";
    case GL_STACK_UNDERFLOW: return "GL_STACK_UNDERFLOW";
    case GL_CONTEXT_LOST: return "GL_CONTEXT_LOST";
    default: return fmt::format("glGetError 0x{:04x}", e);
  }
}

}  // namespace

std::string glString(GLenum name) {
  const auto* s = reinterpret_cast<const char*>(glGetString(name));
  return s ? s : "";
}


bool isSoftwareRenderer(std::string_view renderer) {
  return renderer.find("llvmpipe") != std::string_view::npos || renderer.find("softpipe") != std::string_view::npos;
}

void installDebugMessageCallback() {
  glEnable(GL_DEBUG_OUTPUT);
  glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
  glDebugMessageCallback(onDebugMessage, nullptr);
}

void throwIfGlError(const char* where) {
  std::string pending;
  pending.swap(tPendingError);
  // The callback does not clear GL's error flags: drain them all, or the next check would
  // report this error again. GL keeps at most one flag per error code (8 codes in 4.5); the
  // bound also stops a lost context that keeps answering GL_CONTEXT_LOST.
  constexpr int kMaxErrorFlags = 8;
  for (int i = 0; i < kMaxErrorFlags; ++i) {
    const GLenum e = glGetError();
    if (e == GL_NO_ERROR) break;
    if (pending.empty()) pending = glErrorText(e);
  }
  if (!pending.empty()) throw Error(fmt::format("OpenGL error in {}: {}", where, pending));
}

}  // namespace penumbra::gl
