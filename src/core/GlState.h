#pragma once
// The GL state the core touches, saved before a frame and put back after it (RestoreState::All),
// and the state its passes assume, set at the start of every frame whatever the caller left:
// blending, scissor, stencil, logic op, polygon offset, rasterizer discard, primitive restart,
// sRGB conversion, alpha to coverage and user clip planes off; colour writes on, filled polygons, the
// full depth range, lower-left clip origin; pixel transfers tightly packed from client memory
// (no pixel buffer bound, no row length or skips).
#include "gl/Objects.h"

#include <array>

namespace penumbra::core {

/// Units and binding points the core's passes use (shaders/shared/Bindings.h): every one of
/// them is saved and restored.
inline constexpr GLuint kSavedTextureUnits = 16;
inline constexpr GLuint kSavedImageUnits = 4;
inline constexpr GLuint kSavedUniformBuffers = 3;
inline constexpr GLuint kSavedStorageBuffers = 6;
/// User clip planes (GL_CLIP_DISTANCEi) switched off for the passes: GL 4.5 guarantees 8.
inline constexpr GLuint kClipDistances = 8;

/// How pixels move between client memory and textures (glPixelStore): what texture uploads
/// (the sdf field) and read-backs (readVisibility) depend on, with the pixel buffers bound.
class PixelTransferState {
public:
  /// Reads the pack and unpack parameters and the pixel buffer bindings.
  PixelTransferState();
  /// Writes them back.
  void restore() const;
  /// Tight rows (alignment 1 is not needed: every format Penumbra moves has 4-byte texels, so
  /// the default 4 holds), no row length, skips or byte swapping, no pixel buffer bound.
  static void setDefaults();

private:
  static constexpr size_t kParams = 7;
  std::array<GLint, kParams> mPack{}, mUnpack{};
  GLint mPackBuffer = 0, mUnpackBuffer = 0;
};

/// Pixel transfers of the caller's: defaults while in scope, the caller's state after.
class PixelTransferScope {
public:
  PixelTransferScope() { PixelTransferState::setDefaults(); }
  ~PixelTransferScope() { mSaved.restore(); }
  PixelTransferScope(const PixelTransferScope&) = delete;
  PixelTransferScope& operator=(const PixelTransferScope&) = delete;

private:
  PixelTransferState mSaved;
};

class SavedGlState {
public:
  /// Reads the state (about 190 glGet calls).
  SavedGlState();
  /// Writes it back.
  void restore() const;

private:
  struct IndexedBuffer {
    GLint buffer = 0;
    GLint64 start = 0, size = 0;
  };
  struct ImageUnit {
    GLint texture = 0, level = 0, layered = 0, layer = 0, access = GL_READ_ONLY, format = GL_R32F;
  };
  struct TextureUnit {
    GLint texture2D = 0, texture2DArray = 0, texture3D = 0, sampler = 0;
  };
  GLint mDrawFramebuffer = 0, mReadFramebuffer = 0, mProgram = 0, mVertexArray = 0, mActiveTexture = GL_TEXTURE0;
  std::array<GLint, 4> mViewport{};
  std::array<GLdouble, 2> mDepthRange{0.0, 1.0};
  GLint mDepthFunc = GL_LESS, mClipOrigin = GL_LOWER_LEFT, mClipDepthMode = GL_NEGATIVE_ONE_TO_ONE, mFrontFace = GL_CCW;
  std::array<GLint, 2> mPolygonMode{GL_FILL, GL_FILL};
  GLboolean mDepthMask = GL_TRUE;
  std::array<GLboolean, 4> mColorMask{GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE};
  // Blend factors (source and destination, colour then alpha) and equations (colour, alpha).
  std::array<GLint, 4> mBlendFunc{GL_ONE, GL_ZERO, GL_ONE, GL_ZERO};
  std::array<GLint, 2> mBlendEquation{GL_FUNC_ADD, GL_FUNC_ADD};
  struct Switch {
    GLenum cap;
    GLboolean on;
  };
  std::array<Switch, 13 + kClipDistances> mSwitches{};
  GLint mUniformBuffer = 0, mStorageBuffer = 0;  // the generic bindings glBindBufferBase also sets
  std::array<IndexedBuffer, kSavedUniformBuffers> mUniformBuffers{};
  std::array<IndexedBuffer, kSavedStorageBuffers> mStorageBuffers{};
  std::array<ImageUnit, kSavedImageUnits> mImages{};
  std::array<TextureUnit, kSavedTextureUnits> mTextures{};
  PixelTransferState mPixelTransfer;
};

/// Sets what the core's passes assume and no pass sets itself (see above).
void setPassDefaults();

}  // namespace penumbra::core
