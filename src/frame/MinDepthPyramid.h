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
  /// Where the context has GL_ARB_texture_filter_minmax (or the EXT) and `minFilter` is on, each
  /// texel over exactly 2x2 texels is one read through a minimum-reducing bilinear filter instead
  /// of four texel fetches: the same pyramid, in about two thirds of the time on llvmpipe.
  /// `maxLevels` > 0 builds only the first that many levels: a pool of pages (VirtualPages) needs
  /// the levels whose texels stay inside one tile, log2(page size) of them.
  void build(ShaderLibrary& shaders, const gl::Texture& map, bool minFilter = true, int maxLevels = 0);
  /// Whether build() can take the minimum in the filter here (needs a current context).
  static bool hasMinFilter();
  /// R32F 2D array, ceil(size/2)² at level 0 down to 1×1 (or maxLevels levels), one layer per map layer.
  const gl::Texture& pyramid() const { return mPyramid; }

private:
  gl::Texture mPyramid;
  gl::Sampler mMinSampler;  // bilinear, reduction GL_MIN; made on first use where supported
};

}  // namespace penumbra
