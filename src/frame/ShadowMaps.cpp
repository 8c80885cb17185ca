#include "frame/ShadowMaps.h"

#include "gl/Debug.h"

#include <penumbra/Error.h>

#include <fmt/format.h>

namespace penumbra {

void ShadowMapArray::ensure(const std::string& label, int size, int layers, GLenum colorFormat, int colorLevels) {
  if (size == mSize && layers == mLayers && colorFormat == mColorFormat && colorLevels == mColorLevels && mDepth) return;
  const int maxSize = gl::maxTextureSize();
  if (size > maxSize)
    throw Error(fmt::format("shadow map of {}x{} exceeds this driver's maximum texture size {}", size, size, maxSize));
  mFbos.clear();
  mColor = {};
  mCacheDepth = {};
  mCacheColor = {};
  mCacheKeys.assign(static_cast<size_t>(layers), 0);
  mDrawn.assign(static_cast<size_t>(layers), false);
  mDepth = gl::Texture(label + " depth", {GL_TEXTURE_2D_ARRAY, GL_DEPTH_COMPONENT32F, size, size, layers, 1});
  mDepth.setSampling(GL_NEAREST, GL_NEAREST);
  if (colorFormat != 0) {
    mColor = gl::Texture(label + " color", {GL_TEXTURE_2D_ARRAY, colorFormat, size, size, layers, colorLevels});
    mColor.setSampling(mColor.levels() > 1 ? GL_LINEAR_MIPMAP_LINEAR : GL_LINEAR, GL_LINEAR);
  }
  // Maps too large for the memory fail here, naming their size (a light's own shadow.mapSize
  // may have asked for it, not --shadow-map).
  gl::throwIfGlError(fmt::format("the {}: {} maps of {}²", label, layers, size).c_str());
  for (int i = 0; i < layers; ++i) {
    gl::Framebuffer fb(fmt::format("{} layer {}", label, i));
    fb.attach(GL_DEPTH_ATTACHMENT, mDepth, 0, i);
    if (colorFormat != 0) fb.attach(GL_COLOR_ATTACHMENT0, mColor, 0, i);
    fb.finish(colorFormat != 0 ? 1 : 0);
    mFbos.push_back(std::move(fb));
  }
  mSize = size;
  mLayers = layers;
  mColorFormat = colorFormat;
  mColorLevels = colorLevels;
}

void ShadowMapArray::copyLayer(const gl::Texture& from, const gl::Texture& to, int layer) {
  glCopyImageSubData(from.id(), GL_TEXTURE_2D_ARRAY, 0, 0, 0, layer, to.id(), GL_TEXTURE_2D_ARRAY, 0, 0, 0, layer, mSize, mSize, 1);
}

bool ShadowMapArray::restoreCached(int layer, uint64_t key) {
  const auto l = static_cast<size_t>(layer);
  if (!mCacheDepth || l >= mCacheKeys.size() || mCacheKeys[l] != key || key == 0) return false;
  copyLayer(mCacheDepth, mDepth, layer);
  if (mColor) copyLayer(mCacheColor, mColor, layer);
  return true;
}

void ShadowMapArray::storeCached(int layer, uint64_t key) {
  if (!mCacheDepth) {
    mCacheDepth = gl::Texture("cached shadow map depth", {GL_TEXTURE_2D_ARRAY, mDepth.desc().format, mSize, mSize, mLayers, 1});
    if (mColor) mCacheColor = gl::Texture("cached shadow map color", {GL_TEXTURE_2D_ARRAY, mColorFormat, mSize, mSize, mLayers, 1});
  }
  copyLayer(mDepth, mCacheDepth, layer);
  if (mColor) copyLayer(mColor, mCacheColor, layer);
  mCacheKeys[static_cast<size_t>(layer)] = key;
}

}  // namespace penumbra
