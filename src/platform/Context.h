#pragma once
// OpenGL 4.5 core contexts: headless through EGL (Mesa llvmpipe's surfaceless platform, then the
// EGL device platform for NVIDIA GPUs) and windowed through GLFW (the viewer).
#include <memory>
#include <string>
#include <vector>

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

/// One headless platform that HeadlessContext tried and why it gave no context.
struct PlatformAttempt {
  std::string platform;  ///< "EGL surfaceless", "EGL device", "EGL device 0", ...
  std::string why;       ///< e.g. "extension EGL_EXT_platform_device missing"
};

/// The platforms HeadlessContext tries, in order: Mesa's surfaceless platform (llvmpipe), then
/// the EGL device platform (NVIDIA GPUs).
inline constexpr const char* kHeadlessPlatforms[] = {"EGL surfaceless", "EGL device"};

/// The one-line error when no headless context could be made: every platform of
/// kHeadlessPlatforms with why it failed (from `attempts`; "not tried" if none is recorded),
/// then how to get Mesa's llvmpipe.
std::string headlessContextError(const std::vector<PlatformAttempt>& attempts);

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
