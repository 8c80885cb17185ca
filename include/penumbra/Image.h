#pragma once
// Plain image types shared by every floor: the colour images Penumbra writes and the G-buffer
// read back to the CPU (what the reference traces and the metrics compare). No GL.
#include <penumbra/Math.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace penumbra {

/// sRGB 8-bit RGBA, row 0 = top (ready for PNG).
struct ColorImage {
  int width = 0, height = 0;
  std::vector<uint8_t> rgba;
};

/// The G-buffer read back to the CPU, row 0 = bottom (GL order).
struct GBufferData {
  int width = 0, height = 0;
  std::vector<glm::vec4> position;   ///< xyz world (m); w = 1 where there is geometry, else 0
  std::vector<glm::vec4> geoNormal;  ///< xyz unit geometric normal (facing the camera side); w unused
  std::vector<glm::vec4> normal;     ///< xyz shading normal
  std::vector<glm::vec4> albedo;     ///< rgb base colour
  /// The triangle drawn at each pixel: (index into Scene::objects + 1, triangle index in that
  /// object's mesh); x = 0 where unknown (background, or a G-buffer not made by the renderer).
  /// May be empty: then unknown everywhere. The reference skips the receiver's own triangle.
  std::vector<glm::uvec2> triangle;
  bool covered(size_t i) const { return position[i].w > 0.5f; }
};

/// Flips rows (GL's bottom-up order ↔ image files' top-down order).
template <class T>
std::vector<T> flipRows(std::span<const T> pixels, int width, int height, int channels = 1) {
  std::vector<T> out(pixels.size());
  const size_t row = static_cast<size_t>(width) * static_cast<size_t>(channels);
  for (int y = 0; y < height; ++y)
    std::copy_n(pixels.begin() + static_cast<std::ptrdiff_t>(static_cast<size_t>(y) * row), row,
                out.begin() + static_cast<std::ptrdiff_t>(static_cast<size_t>(height - 1 - y) * row));
  return out;
}

}  // namespace penumbra
