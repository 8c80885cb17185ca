#pragma once
// OpenGL 4.5 core contexts: headless through EGL (Mesa llvmpipe's surfaceless platform, then the
// EGL device platform for NVIDIA GPUs) and windowed through GLFW (the viewer).
#include <memory>
#include <string>

struct GLFWwindow;

namespace penumbra::gl {

struct GlInfo {
  std::string renderer, version, vendor;
  std::string platform;  ///< "EGL surfaceless", "EGL device 0", "GLFW"
  /// True on software rasterisers (llvmpipe/softpipe), whose timer queries read 0: time passes
  /// with glFinish + a steady clock there instead.
  bool softwareRenderer = false;
};

#ifdef NDEBUG
inline constexpr bool kDebugBuild = false;
#else
inline constexpr bool kDebugBuild = true;
#endif

struct ContextOptions {
  /// Install the debug-message callback (GL errors then throw at the end of the pass);
  /// on by default in Debug builds.
  bool debug = kDebugBuild;
  bool verbose = false;  ///< print GL_RENDERER / GL_VERSION once on stderr
};

/// Throws penumbra::Error if the debug callback recorded a GL error (or glGetError reports one)
/// since the last call. The renderer calls it after every pass.
void throwIfGlError(const char* where);

/// Base of both kinds: reads GlInfo, sets Penumbra's global GL state (reversed-Z clip control).
class Context {
public:
  virtual ~Context() = default;
  const GlInfo& info() const { return mInfo; }

protected:
  void initialiseCurrent(const ContextOptions& options, std::string platform);
  GlInfo mInfo;
};

class HeadlessContext final : public Context {
public:
  /// Throws penumbra::Error saying what was tried and how to get llvmpipe when no 4.5 core
  /// context can be made.
  explicit HeadlessContext(const ContextOptions& options = {});
  ~HeadlessContext() override;
  HeadlessContext(const HeadlessContext&) = delete;
  HeadlessContext& operator=(const HeadlessContext&) = delete;

private:
  struct Impl;
  std::unique_ptr<Impl> mImpl;
};

class WindowContext final : public Context {
public:
  WindowContext(int width, int height, const std::string& title, const ContextOptions& options = {});
  ~WindowContext() override;
  WindowContext(const WindowContext&) = delete;
  WindowContext& operator=(const WindowContext&) = delete;
  GLFWwindow* window() const { return mWindow; }

private:
  GLFWwindow* mWindow = nullptr;
};

}  // namespace penumbra::gl
