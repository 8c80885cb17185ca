// How much memory an image size needs, against how much there is: checked before rendering
// (Common.h: checkImageFits).
#include "Common.h"

#include "base/HostMemory.h"
#include "platform/Context.h"

#include <penumbra/Error.h>
#include <penumbra/Renderer.h>

#include <epoxy/gl.h>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>

namespace penumbra::app {
namespace {

constexpr uint64_t kKiB = 1024;
constexpr double kGiB = 1024.0 * 1024.0 * 1024.0;
// GL_NVX_gpu_memory_info and GL_ATI_meminfo enums (not in every GL header).
constexpr GLenum kGpuMemoryAvailableNvx = 0x9049;  // GPU_MEMORY_INFO_CURRENT_AVAILABLE_VIDMEM_NVX, KiB
constexpr GLenum kTextureFreeMemoryAti = 0x87FC;   // TEXTURE_FREE_MEMORY_ATI: {total free KiB, ...}

/// Free GPU memory where the driver tells it.
std::optional<uint64_t> availableGpuBytes() {
  GLint kib[4] = {0, 0, 0, 0};
  if (epoxy_has_gl_extension("GL_NVX_gpu_memory_info")) glGetIntegerv(kGpuMemoryAvailableNvx, kib);
  else if (epoxy_has_gl_extension("GL_ATI_meminfo")) glGetIntegerv(kTextureFreeMemoryAti, kib);
  else return std::nullopt;
  return static_cast<uint64_t>(kib[0]) * kKiB;
}

/// Whether the driver can make one width × height RGBA32F texture (the G-buffer's positions, the
/// largest target), asked with a proxy texture: nothing is allocated. llvmpipe refuses any single
/// texture over 1 GiB whatever the memory (16384² RGBA32F is 4 GiB).
bool driverCanMakeTarget(int width, int height) {
  glTexImage2D(GL_PROXY_TEXTURE_2D, 0, GL_RGBA32F, width, height, 0, GL_RGBA, GL_FLOAT, nullptr);
  GLint made = 0;
  glGetTexLevelParameteriv(GL_PROXY_TEXTURE_2D, 0, GL_TEXTURE_WIDTH, &made);
  while (glGetError() != GL_NO_ERROR) {}  // a refused size may also raise GL_INVALID_VALUE
  return made != 0;
}

[[noreturn]] void refuse(int width, int height, uint64_t needed, uint64_t available, const std::string& where) {
  // Memory grows with the pixel count: scale both sides by the square root of what is left.
  const double scale = std::sqrt(static_cast<double>(available) / static_cast<double>(needed));
  const int w = std::max(1, static_cast<int>(width * scale)), h = std::max(1, static_cast<int>(height * scale));
  throw Error(fmt::format("--size {}x{}: the image needs about {:.1f} GiB ({}), more than the {:.1f} GiB available; "
                          "{}x{} or smaller would fit",
                          width, height, needed / kGiB, where, available / kGiB, w, h));
}

}  // namespace

void checkImageFits(const gl::Context& context, int width, int height, uint64_t hostBytesPerPixel) {
  if (!driverCanMakeTarget(width, height)) {
    int w = width, h = height;
    while ((w > 1 || h > 1) && !driverCanMakeTarget(w, h)) w = std::max(1, w / 2), h = std::max(1, h / 2);
    throw Error(fmt::format("--size {}x{}: {} cannot make a render target that large (a {}x{} RGBA32F texture); "
                            "{}x{} or smaller would fit",
                            width, height, context.info().renderer, width, height, w, h));
  }
  const uint64_t pixels = static_cast<uint64_t>(width) * static_cast<uint64_t>(height);
  const uint64_t gpu = Renderer::screenBytes(width, height), host = hostBytesPerPixel * pixels;
  if (context.info().softwareRenderer) {
    const uint64_t available = availableHostBytes();
    if (gpu + host > available)
      refuse(width, height, gpu + host, available, fmt::format("{} keeps its textures in host memory, and the read-backs", context.info().renderer));
    return;
  }
  if (const uint64_t available = availableHostBytes(); host > available) refuse(width, height, host, available, "the read-backs");
  if (const std::optional<uint64_t> available = availableGpuBytes(); available && gpu > *available)
    refuse(width, height, gpu, *available, "the GPU's render targets");
}

}  // namespace penumbra::app
