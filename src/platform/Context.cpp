#include "platform/Context.h"

#include "gl/Debug.h"

#include <penumbra/Error.h>

#include <epoxy/egl.h>
#include <epoxy/gl.h>
#include <GLFW/glfw3.h>
#include <fmt/format.h>

#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

namespace penumbra::gl {
namespace {

constexpr const char* kHowToGetLlvmpipe =
    "install Mesa's software renderer (Debian: apt-get install libegl-mesa0 libgl1-mesa-dri, "
    "or run scripts/install-deps) or a GPU driver with EGL; EGL_PLATFORM=surfaceless and "
    "LIBGL_ALWAYS_SOFTWARE=1 force llvmpipe";

}  // namespace

void Context::initialiseCurrent(const ContextOptions& options, std::string platform) {
  PN_CHECK(epoxy_gl_version() >= 45,
           fmt::format("the OpenGL context from {} is version {}.{}, Penumbra needs 4.5 core; {}", platform,
                       epoxy_gl_version() / 10, epoxy_gl_version() % 10, kHowToGetLlvmpipe));
  mInfo.renderer = glString(GL_RENDERER);
  mInfo.version = glString(GL_VERSION);
  mInfo.vendor = glString(GL_VENDOR);
  mInfo.platform = std::move(platform);
  mInfo.softwareRenderer = isSoftwareRenderer(mInfo.renderer);
  if (options.verbose)
    std::fprintf(stderr, "penumbra: GL_RENDERER %s | GL_VERSION %s | %s\n", mInfo.renderer.c_str(),
                 mInfo.version.c_str(), mInfo.platform.c_str());
  if (options.debug) {
    installDebugMessageCallback();
  }
  // Reversed-Z camera depth (docs/design.md conventions).
  glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
}

// ---- EGL --------------------------------------------------------------------------------
struct HeadlessContext::Impl {
  EGLDisplay display = EGL_NO_DISPLAY;
  EGLContext context = EGL_NO_CONTEXT;
  std::string platform;
};

namespace {

bool hasExtension(const char* list, const char* name) {
  if (!list) return false;
  const size_t n = std::strlen(name);
  for (const char* p = list; (p = std::strstr(p, name)); p += n)
    if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0')) return true;
  return false;
}

// Tries to make a 4.5 core context current on `display`; returns it, or EGL_NO_CONTEXT with
// the reason recorded in `attempts` under `name`.
EGLContext tryCreate(EGLDisplay display, const std::string& name, std::vector<PlatformAttempt>& attempts) {
  EGLint major = 0, minor = 0;
  if (!eglInitialize(display, &major, &minor)) {
    attempts.push_back({name, fmt::format("eglInitialize failed (0x{:x})", eglGetError())});
    return EGL_NO_CONTEXT;
  }
  if (!eglBindAPI(EGL_OPENGL_API)) {
    attempts.push_back({name, "no desktop OpenGL API"});
    eglTerminate(display);
    return EGL_NO_CONTEXT;
  }
  const char* exts = eglQueryString(display, EGL_EXTENSIONS);
  EGLConfig config = EGL_NO_CONFIG_KHR;
  if (!hasExtension(exts, "EGL_KHR_no_config_context")) {
    const EGLint attribs[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_NONE};
    EGLint count = 0;
    if (!eglChooseConfig(display, attribs, &config, 1, &count) || count == 0) {
      attempts.push_back({name, "no OpenGL-renderable config"});
      eglTerminate(display);
      return EGL_NO_CONTEXT;
    }
  }
  const EGLint contextAttribs[] = {EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 5,
                                   EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                   EGL_NONE};
  EGLContext context = eglCreateContext(display, config, EGL_NO_CONTEXT, contextAttribs);
  if (context == EGL_NO_CONTEXT) {
    attempts.push_back({name, fmt::format("no OpenGL 4.5 core context (0x{:x})", eglGetError())});
    eglTerminate(display);
    return EGL_NO_CONTEXT;
  }
  if (!eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context)) {
    attempts.push_back({name, fmt::format("eglMakeCurrent without a surface failed (0x{:x})", eglGetError())});
    eglDestroyContext(display, context);
    eglTerminate(display);
    return EGL_NO_CONTEXT;
  }
  return context;
}

}  // namespace

std::string headlessContextError(const std::vector<PlatformAttempt>& attempts) {
  std::string tried;
  for (const char* platform : kHeadlessPlatforms) {
    // Attempts under this platform's name, or a numbered one of it ("EGL device 0").
    std::string reasons;
    for (const PlatformAttempt& a : attempts) {
      if (a.platform.rfind(platform, 0) != 0) continue;
      if (!reasons.empty()) reasons += "; ";
      reasons += a.platform == platform ? a.why : fmt::format("#{}: {}", a.platform.substr(std::strlen(platform) + 1), a.why);
    }
    if (!tried.empty()) tried += ", ";
    tried += fmt::format("{} ({})", platform, reasons.empty() ? "not tried" : reasons);
  }
  return fmt::format("could not create a headless OpenGL 4.5 core context; tried {}; {}", tried, kHowToGetLlvmpipe);
}

HeadlessContext::HeadlessContext(const ContextOptions& options) : mImpl(std::make_unique<Impl>()) {
  std::vector<PlatformAttempt> attempts;
  const char* clientExts = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  if (!clientExts) {
    throw Error(fmt::format("no EGL library could be loaded; {}", kHowToGetLlvmpipe));
  }
  // 1. Mesa's surfaceless platform (llvmpipe, or Mesa GPU drivers).
  const std::string surfaceless = kHeadlessPlatforms[0];
  if (hasExtension(clientExts, "EGL_MESA_platform_surfaceless")) {
    EGLDisplay d = eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    if (d != EGL_NO_DISPLAY) {
      EGLContext c = tryCreate(d, surfaceless, attempts);
      if (c != EGL_NO_CONTEXT) { mImpl->display = d; mImpl->context = c; mImpl->platform = surfaceless; }
    } else {
      attempts.push_back({surfaceless, "no display"});
    }
  } else {
    attempts.push_back({surfaceless, "extension EGL_MESA_platform_surfaceless missing"});
  }
  // 2. The EGL device platform (NVIDIA's driver exposes its GPUs this way).
  const std::string device = kHeadlessPlatforms[1];
  if (mImpl->context == EGL_NO_CONTEXT) {
    if (!hasExtension(clientExts, "EGL_EXT_platform_device")) {
      attempts.push_back({device, "extension EGL_EXT_platform_device missing"});
    } else {
      EGLDeviceEXT devices[16];
      EGLint count = 0;
      if (!eglQueryDevicesEXT(16, devices, &count)) {
        attempts.push_back({device, fmt::format("eglQueryDevicesEXT failed (0x{:x})", eglGetError())});
      } else if (count == 0) {
        attempts.push_back({device, "no devices"});
      }
      for (EGLint i = 0; i < count && mImpl->context == EGL_NO_CONTEXT; ++i) {
        const std::string name = fmt::format("{} {}", device, i);
        EGLDisplay d = eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr);
        if (d == EGL_NO_DISPLAY) {
          attempts.push_back({name, "no display"});
          continue;
        }
        EGLContext c = tryCreate(d, name, attempts);
        if (c != EGL_NO_CONTEXT) { mImpl->display = d; mImpl->context = c; mImpl->platform = name; }
      }
    }
  }
  if (mImpl->context == EGL_NO_CONTEXT) throw Error(headlessContextError(attempts));
  initialiseCurrent(options, mImpl->platform);
}

HeadlessContext::~HeadlessContext() {
  if (mImpl && mImpl->display != EGL_NO_DISPLAY) {
    eglMakeCurrent(mImpl->display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(mImpl->display, mImpl->context);
    eglTerminate(mImpl->display);
  }
}

// ---- GLFW -------------------------------------------------------------------------------
WindowContext::WindowContext(int width, int height, const std::string& title, const ContextOptions& options) {
  PN_CHECK(glfwInit(), "could not initialise GLFW (is a display available? under no display, run with xvfb-run)");
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  glfwWindowHint(GLFW_OPENGL_DEBUG_CONTEXT, options.debug ? GLFW_TRUE : GLFW_FALSE);
  mWindow = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
  if (!mWindow) {
    glfwTerminate();
    throw Error(fmt::format("could not open a {}x{} window with an OpenGL 4.5 core context; {}", width,
                            height, kHowToGetLlvmpipe));
  }
  glfwMakeContextCurrent(mWindow);
  initialiseCurrent(options, "GLFW");
}

WindowContext::~WindowContext() {
  if (mWindow) glfwDestroyWindow(mWindow);
  glfwTerminate();
}

}  // namespace penumbra::gl
