#pragma once
// The GL state the core touches, saved before a frame and put back after it (RestoreState::All),
// and the state its passes assume, set at the start of every frame whatever the caller left
// (blending, scissor and stencil off, colour writes on, filled polygons, lower-left clip origin).
#include "gl/Objects.h"

#include <array>

namespace penumbra::core {

/// Units and binding points the core's passes use (shaders/shared/Bindings.h): every one of
/// them is saved and restored.
inline constexpr GLuint kSavedTextureUnits = 16;
inline constexpr GLuint kSavedImageUnits = 4;
inline constexpr GLuint kSavedUniformBuffers = 3;
inline constexpr GLuint kSavedStorageBuffers = 6;

class SavedGlState {
public:
  /// Reads the state (about 150 glGet calls).
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
  GLint mDepthFunc = GL_LESS, mClipOrigin = GL_LOWER_LEFT, mClipDepthMode = GL_NEGATIVE_ONE_TO_ONE;
  std::array<GLint, 2> mPolygonMode{GL_FILL, GL_FILL};
  GLboolean mDepthMask = GL_TRUE;
  std::array<GLboolean, 4> mColorMask{GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE};
  struct Switch {
    GLenum cap;
    GLboolean on;
  };
  std::array<Switch, 8> mSwitches{};
  GLint mUniformBuffer = 0, mStorageBuffer = 0;  // the generic bindings glBindBufferBase also sets
  std::array<IndexedBuffer, kSavedUniformBuffers> mUniformBuffers{};
  std::array<IndexedBuffer, kSavedStorageBuffers> mStorageBuffers{};
  std::array<ImageUnit, kSavedImageUnits> mImages{};
  std::array<TextureUnit, kSavedTextureUnits> mTextures{};
};

/// Sets what the core's passes assume and no pass sets itself (see above).
void setPassDefaults();

}  // namespace penumbra::core
