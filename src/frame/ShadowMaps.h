#pragma once
// A layered shadow-map target (one layer per shadow view / cascade) with one framebuffer per
// layer: a depth texture, and optionally a colour texture (moments) rendered with it.
#include "gl/Objects.h"

#include <cstdint>
#include <string>
#include <vector>

namespace penumbra {

class ShadowMapArray {
public:
  /// (Re)creates the textures when size, layer count or formats change; cheap otherwise.
  /// colorFormat 0 = depth only. colorLevels 0 = a full mip chain on the colour texture.
  void ensure(const std::string& label, int size, int layers, GLenum colorFormat = 0, int colorLevels = 1);
  const gl::Texture& depth() const { return mDepth; }
  const gl::Texture& color() const { return mColor; }
  gl::Framebuffer& framebuffer(int layer) { return mFbos[static_cast<size_t>(layer)]; }
  int size() const { return mSize; }
  int layers() const { return mLayers; }

  /// Cached maps: when layer `layer`'s cache was stored under `key`, copies it into the layer
  /// (depth, and colour level 0) and returns true; otherwise false.
  bool restoreCached(int layer, uint64_t key);
  /// Copies the layer as it is now into its cache, under `key`.
  void storeCached(int layer, uint64_t key);
  /// Whether the layer was drawn since its textures were (re)made: a map kept across frames
  /// (MapUpdates::Budget) needs one.
  bool drawn(int layer) const { return layer < static_cast<int>(mDrawn.size()) && mDrawn[static_cast<size_t>(layer)]; }
  void markDrawn(int layer) { mDrawn[static_cast<size_t>(layer)] = true; }

private:
  void copyLayer(const gl::Texture& from, const gl::Texture& to, int layer);
  gl::Texture mDepth, mColor;
  gl::Texture mCacheDepth, mCacheColor;  ///< made on the first storeCached, with the maps' formats
  std::vector<uint64_t> mCacheKeys;      ///< per layer; 0 = nothing cached
  std::vector<bool> mDrawn;              ///< per layer
  std::vector<gl::Framebuffer> mFbos;
  int mSize = 0, mLayers = 0, mColorLevels = 1;
  GLenum mColorFormat = 0;
};

}  // namespace penumbra
