#pragma once
// Shows any texture in a region of the window: the colour output, the visibility, the G-buffer,
// or whatever a filter lists in Filter::debugImages() (2D, 2D array or 3D; depth or colour).
// A channel (or rgb), a layer/slice and a mip level are mapped to grey or Turbo over a fixed
// range or the range measured on the GPU over the shown pixels. Also reads the window back for
// screenshots.
#include "gl/Objects.h"
#include "shader/ShaderLibrary.h"

#include <penumbra/Renderer.h>

#include <string>

namespace penumbra::viewer {

struct DisplaySettings {
  int layer = 0;     ///< array layer (cascade) or 3D slice
  int level = 0;     ///< mip level
  int channel = 0;   ///< 0..3 = r, g, b, a; kChannelRgb = rgb together
  bool turbo = false;     ///< colour map instead of grey (single channels)
  bool autoRange = true;  ///< measure min/max over the shown pixels; else [lo, hi]
  float lo = 0.0f, hi = 1.0f;
  static constexpr int kChannelRgb = 4;
};

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
  /// Returns the range that was mapped to [0, 1].
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
