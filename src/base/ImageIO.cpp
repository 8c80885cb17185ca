// PNG files through stb (the stb_image and stb_image_write implementations live here, once;
// stb_image decodes PNG only, base/StbImageFormats.h says why).
#include "base/AtomicFile.h"
#include "base/StbImageFormats.h"

#include <penumbra/Error.h>
#include <penumbra/ImageIO.h>

#include <fmt/format.h>

#include <cerrno>
#include <cstring>

#define STB_IMAGE_WRITE_IMPLEMENTATION
#define STB_IMAGE_IMPLEMENTATION
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#pragma GCC diagnostic ignored "-Wunused-function"
#include <stb_image.h>
#include <stb_image_write.h>
#pragma GCC diagnostic pop

namespace penumbra {

void writePng(const std::filesystem::path& path, int width, int height, std::span<const uint8_t> rgba) {
  PN_CHECK(rgba.size() == static_cast<size_t>(width) * static_cast<size_t>(height) * 4,
           fmt::format("{}: pixel count does not match {}x{}", path.string(), width, height));
  AtomicFile file(path);
  errno = 0;
  if (!stbi_write_png(file.temporary().c_str(), width, height, 4, rgba.data(), width * 4))
    throw Error(fmt::format("{}: cannot write the PNG ({})", path.string(), errno != 0 ? std::strerror(errno) : "write failed"));
  file.commit();
}

std::vector<uint8_t> readPng(const std::filesystem::path& path, int& width, int& height) {
  int channels = 0;
  stbi_uc* data = stbi_load(path.c_str(), &width, &height, &channels, 4);
  if (!data) throw Error(fmt::format("{}: cannot read the PNG ({})", path.string(), stbi_failure_reason()));
  std::vector<uint8_t> out(data, data + static_cast<size_t>(width) * static_cast<size_t>(height) * 4);
  stbi_image_free(data);
  return out;
}

}  // namespace penumbra
