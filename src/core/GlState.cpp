#include "core/GlState.h"

namespace penumbra::core {
namespace {

// Switches the passes assume off (blend … rasterizer discard) or set themselves (depth test,
// clamp, culling): all are saved.
constexpr GLenum kSwitches[] = {GL_BLEND, GL_SCISSOR_TEST, GL_STENCIL_TEST, GL_POLYGON_OFFSET_FILL,
                                GL_RASTERIZER_DISCARD, GL_DEPTH_TEST, GL_DEPTH_CLAMP, GL_CULL_FACE};
static_assert(std::size(kSwitches) == 8, "SavedGlState::mSwitches holds one entry per switch");

GLint getInt(GLenum what) {
  GLint v = 0;
  glGetIntegerv(what, &v);
  return v;
}

GLint getIndexed(GLenum what, GLuint index) {
  GLint v = 0;
  glGetIntegeri_v(what, index, &v);
  return v;
}

GLint64 getIndexed64(GLenum what, GLuint index) {
  GLint64 v = 0;
  glGetInteger64i_v(what, index, &v);
  return v;
}

void restoreIndexed(GLenum target, GLuint index, GLint buffer, GLint64 start, GLint64 size) {
  // A range of size 0 was bound with glBindBufferBase (or not at all).
  if (buffer != 0 && size > 0)
    glBindBufferRange(target, index, static_cast<GLuint>(buffer), static_cast<GLintptr>(start), static_cast<GLsizeiptr>(size));
  else
    glBindBufferBase(target, index, static_cast<GLuint>(buffer));
}

}  // namespace

SavedGlState::SavedGlState() {
  mDrawFramebuffer = getInt(GL_DRAW_FRAMEBUFFER_BINDING);
  mReadFramebuffer = getInt(GL_READ_FRAMEBUFFER_BINDING);
  mProgram = getInt(GL_CURRENT_PROGRAM);
  mVertexArray = getInt(GL_VERTEX_ARRAY_BINDING);
  mActiveTexture = getInt(GL_ACTIVE_TEXTURE);
  glGetIntegerv(GL_VIEWPORT, mViewport.data());
  mDepthFunc = getInt(GL_DEPTH_FUNC);
  mClipOrigin = getInt(GL_CLIP_ORIGIN);
  mClipDepthMode = getInt(GL_CLIP_DEPTH_MODE);
  glGetIntegerv(GL_POLYGON_MODE, mPolygonMode.data());
  glGetBooleanv(GL_DEPTH_WRITEMASK, &mDepthMask);
  glGetBooleanv(GL_COLOR_WRITEMASK, mColorMask.data());
  for (size_t i = 0; i < std::size(kSwitches); ++i) mSwitches[i] = {kSwitches[i], glIsEnabled(kSwitches[i])};
  mUniformBuffer = getInt(GL_UNIFORM_BUFFER_BINDING);
  mStorageBuffer = getInt(GL_SHADER_STORAGE_BUFFER_BINDING);
  for (GLuint i = 0; i < kSavedUniformBuffers; ++i)
    mUniformBuffers[i] = {getIndexed(GL_UNIFORM_BUFFER_BINDING, i), getIndexed64(GL_UNIFORM_BUFFER_START, i),
                          getIndexed64(GL_UNIFORM_BUFFER_SIZE, i)};
  for (GLuint i = 0; i < kSavedStorageBuffers; ++i)
    mStorageBuffers[i] = {getIndexed(GL_SHADER_STORAGE_BUFFER_BINDING, i), getIndexed64(GL_SHADER_STORAGE_BUFFER_START, i),
                          getIndexed64(GL_SHADER_STORAGE_BUFFER_SIZE, i)};
  for (GLuint i = 0; i < kSavedImageUnits; ++i)
    mImages[i] = {getIndexed(GL_IMAGE_BINDING_NAME, i), getIndexed(GL_IMAGE_BINDING_LEVEL, i),
                  getIndexed(GL_IMAGE_BINDING_LAYERED, i), getIndexed(GL_IMAGE_BINDING_LAYER, i),
                  getIndexed(GL_IMAGE_BINDING_ACCESS, i), getIndexed(GL_IMAGE_BINDING_FORMAT, i)};
  for (GLuint i = 0; i < kSavedTextureUnits; ++i) {
    glActiveTexture(GL_TEXTURE0 + i);
    mTextures[i] = {getInt(GL_TEXTURE_BINDING_2D), getInt(GL_TEXTURE_BINDING_2D_ARRAY), getInt(GL_TEXTURE_BINDING_3D),
                    getInt(GL_SAMPLER_BINDING)};
  }
  glActiveTexture(static_cast<GLenum>(mActiveTexture));
}

void SavedGlState::restore() const {
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, static_cast<GLuint>(mDrawFramebuffer));
  glBindFramebuffer(GL_READ_FRAMEBUFFER, static_cast<GLuint>(mReadFramebuffer));
  // A program the caller deleted while it was current lived on only while current: once the
  // core used its own, it is gone and cannot be made current again.
  glUseProgram(glIsProgram(static_cast<GLuint>(mProgram)) ? static_cast<GLuint>(mProgram) : 0);
  glBindVertexArray(static_cast<GLuint>(mVertexArray));
  glViewport(mViewport[0], mViewport[1], mViewport[2], mViewport[3]);
  glDepthFunc(static_cast<GLenum>(mDepthFunc));
  glClipControl(static_cast<GLenum>(mClipOrigin), static_cast<GLenum>(mClipDepthMode));
  // GL 4.5 core takes one mode for both faces; the query reports it twice.
  glPolygonMode(GL_FRONT_AND_BACK, static_cast<GLenum>(mPolygonMode[0]));
  glDepthMask(mDepthMask);
  glColorMask(mColorMask[0], mColorMask[1], mColorMask[2], mColorMask[3]);
  for (const Switch& s : mSwitches) (s.on ? glEnable : glDisable)(s.cap);
  for (GLuint i = 0; i < kSavedUniformBuffers; ++i)
    restoreIndexed(GL_UNIFORM_BUFFER, i, mUniformBuffers[i].buffer, mUniformBuffers[i].start, mUniformBuffers[i].size);
  for (GLuint i = 0; i < kSavedStorageBuffers; ++i)
    restoreIndexed(GL_SHADER_STORAGE_BUFFER, i, mStorageBuffers[i].buffer, mStorageBuffers[i].start, mStorageBuffers[i].size);
  glBindBuffer(GL_UNIFORM_BUFFER, static_cast<GLuint>(mUniformBuffer));
  glBindBuffer(GL_SHADER_STORAGE_BUFFER, static_cast<GLuint>(mStorageBuffer));
  for (GLuint i = 0; i < kSavedImageUnits; ++i) {
    const ImageUnit& u = mImages[i];
    glBindImageTexture(i, static_cast<GLuint>(u.texture), u.level, u.layered ? GL_TRUE : GL_FALSE, u.layer,
                       static_cast<GLenum>(u.access), static_cast<GLenum>(u.format));
  }
  for (GLuint i = 0; i < kSavedTextureUnits; ++i) {
    glActiveTexture(GL_TEXTURE0 + i);
    glBindTexture(GL_TEXTURE_2D, static_cast<GLuint>(mTextures[i].texture2D));
    glBindTexture(GL_TEXTURE_2D_ARRAY, static_cast<GLuint>(mTextures[i].texture2DArray));
    glBindTexture(GL_TEXTURE_3D, static_cast<GLuint>(mTextures[i].texture3D));
    glBindSampler(i, static_cast<GLuint>(mTextures[i].sampler));
  }
  glActiveTexture(static_cast<GLenum>(mActiveTexture));
}

void setPassDefaults() {
  glDisable(GL_BLEND);
  glDisable(GL_SCISSOR_TEST);
  glDisable(GL_STENCIL_TEST);
  glDisable(GL_POLYGON_OFFSET_FILL);
  glDisable(GL_RASTERIZER_DISCARD);
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
  // Maps are addressed with uv = ndc·½ + ½ from the bottom row; the depth mode does not matter
  // (shadow passes write gl_FragDepth with depth clamping on).
  GLint depthMode = GL_NEGATIVE_ONE_TO_ONE;
  glGetIntegerv(GL_CLIP_DEPTH_MODE, &depthMode);
  glClipControl(GL_LOWER_LEFT, static_cast<GLenum>(depthMode));
}

}  // namespace penumbra::core
