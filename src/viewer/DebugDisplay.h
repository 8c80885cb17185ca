#pragma once
// Shows any texture in a region of the window: the colour output, the visibility, the G-buffer,
// or whatever a filter lists in Filter::debugImages() (2D, 2D array or 3D; depth or colour).
// A channel (or rgb), a layer/slice and a mip level are mapped to grey or Turbo over a fixed
// range or the range measured on the GPU over the shown pixels. A 2D array of several layers
// (cascades, a point light's six cube faces) is shown as a grid of every layer over one range,
// or one layer of it. Also reads the window back for screenshots.
#include "gl/Objects.h"
#include "shader/ShaderLibrary.h"

#include <penumbra/Renderer.h>

#include <optional>
#include <string>
#include <vector>

namespace penumbra::viewer {

struct DisplaySettings {
  int layer = 0;     ///< array layer (cascade) or 3D slice, when not allLayers
  /// 2D arrays of several layers: every layer side by side (layerCells()), over one range.
  bool allLayers = true;
  int level = 0;     ///< mip level
  int channel = 0;   ///< 0..3 = r, g, b, a; kChannelRgb = rgb together
  bool turbo = false;     ///< colour map instead of grey (single channels)
  bool autoRange = true;  ///< measure min/max over the shown pixels; else [lo, hi]
  float lo = 0.0f, hi = 1.0f;
  /// The image's "nothing here" value (DebugImage::noData): left out of the measured range and
  /// drawn in kNoDataColor. Set from the image, not by the user.
  std::optional<float> noData;
  static constexpr int kChannelRgb = 4;
};

/// Where draw() puts the layers of an array of `layers` layers of width × height texels shown
/// with allLayers in `rect` (x, y = lower-left window pixel): the grid of columns × rows that
/// shows them largest, layer 0 top left, in reading order, each cell letterboxed.
std::vector<glm::ivec4> layerCells(const glm::ivec4& rect, int width, int height, int layers);

/// Why a texture cannot be shown ("" when it can): integer formats, multisample, missing.
std::string displayProblem(const gl::Texture& texture);

class DebugDisplay {
public:
  explicit DebugDisplay(ShaderLibrary& shaders);
  DebugDisplay(const DebugDisplay&) = delete;
  DebugDisplay& operator=(const DebugDisplay&) = delete;

  /// Draws `texture` into `rect` (x, y = lower-left window pixel; z, w = size) of the default
  /// framebuffer, letterboxed to the texture's aspect ratio. Settings out of the texture's
  /// range are clamped. With `clip`, only its part of the window is drawn (a split view's half).
  /// Returns the range that was mapped to [0, 1] (with allLayers: over every layer shown).
  glm::vec2 draw(const gl::Texture& texture, DisplaySettings settings, const glm::ivec4& rect,
                 const glm::ivec4* clip = nullptr);

private:
  ShaderLibrary& mShaders;
  gl::Buffer mBlock, mRange;
  gl::VertexArray mVao;
  gl::Sampler mSampler;  // nearest, no depth compare: shows stored values, whatever the texture's own state
};

/// Reads a region of the default framebuffer's back buffer as an image (row 0 = top).
ColorImage readWindow(const glm::ivec4& rect);

}  // namespace penumbra::viewer
