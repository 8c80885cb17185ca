#pragma once
// Min-depth pyramids of shadow maps (passes/min_depth.comp.glsl): level k holds the smallest
// linear depth over each block of 2^(k+1) x 2^(k+1) map texels, so the nearest surface inside any
// box of the map is at most four reads (common/penumbra.glsl: minDepthOverBox). The soft-shadow
// filters use it to tighten their blocker search: no blocker can be nearer than that surface.
#include "gl/Objects.h"

namespace penumbra {

class ShaderLibrary;

class MinDepthPyramid {
public:
  /// Rebuilds the pyramid of every layer of `map` (a 2D array; linear depth in channel r).
  void build(ShaderLibrary& shaders, const gl::Texture& map);
  /// R32F 2D array, ceil(size/2)² at level 0 down to 1×1, one layer per map layer.
  const gl::Texture& pyramid() const { return mPyramid; }

private:
  gl::Texture mPyramid;
};

}  // namespace penumbra
