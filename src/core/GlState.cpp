#include "core/GlState.h"

namespace penumbra::core {
namespace {

// Switches the passes assume off (blend … alpha to coverage, clip distances) or set themselves
// (depth test, clamp, culling): all are saved. Dithering is left alone: it applies to fixed-point
// colour only, and every target Penumbra draws is depth or float.
constexpr GLenum kSwitches[] = {GL_BLEND, GL_SCISSOR_TEST, GL_STENCIL_TEST, GL_POLYGON_OFFSET_FILL, GL_RASTERIZER_DISCARD,
                                GL_COLOR_LOGIC_OP, GL_PRIMITIVE_RESTART, GL_PRIMITIVE_RESTART_FIXED_INDEX, GL_FRAMEBUFFER_SRGB,
                                GL_SAMPLE_ALPHA_TO_COVERAGE, GL_DEPTH_TEST, GL_DEPTH_CLAMP, GL_CULL_FACE,
                                GL_CLIP_DISTANCE0, GL_CLIP_DISTANCE1, GL_CLIP_DISTANCE2, GL_CLIP_DISTANCE3,
                                GL_CLIP_DISTANCE4, GL_CLIP_DISTANCE5, GL_CLIP_DISTANCE6, GL_CLIP_DISTANCE7};
// The first ones are off in every pass (setPassDefaults); depth test, clamp and culling are set by
// the passes that draw geometry.
constexpr size_t kSwitchesOff = 10;  // blend … alpha to coverage
static_assert(std::size(kSwitches) == 13 + kClipDistances, "SavedGlState::mSwitches holds one entry per switch");

// glPixelStore parameters, pack then unpack, in the same order, with their defaults.
constexpr GLenum kPackParams[] = {GL_PACK_ALIGNMENT, GL_PACK_ROW_LENGTH, GL_PACK_IMAGE_HEIGHT, GL_PACK_SKIP_PIXELS,
                                  GL_PACK_SKIP_ROWS, GL_PACK_SKIP_IMAGES, GL_PACK_SWAP_BYTES};
constexpr GLenum kUnpackParams[] = {GL_UNPACK_ALIGNMENT, GL_UNPACK_ROW_LENGTH, GL_UNPACK_IMAGE_HEIGHT, GL_UNPACK_SKIP_PIXELS,
                                    GL_UNPACK_SKIP_ROWS, GL_UNPACK_SKIP_IMAGES, GL_UNPACK_SWAP_BYTES};
constexpr GLint kPixelDefaults[] = {4, 0, 0, 0, 0, 0, GL_FALSE};

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

PixelTransferState::PixelTransferState() {
  for (size_t i = 0; i < kParams; ++i) {
    mPack[i] = getInt(kPackParams[i]);
    mUnpack[i] = getInt(kUnpackParams[i]);
  }
  mPackBuffer = getInt(GL_PIXEL_PACK_BUFFER_BINDING);
  mUnpackBuffer = getInt(GL_PIXEL_UNPACK_BUFFER_BINDING);
}

void PixelTransferState::restore() const {
  for (size_t i = 0; i < kParams; ++i) {
    glPixelStorei(kPackParams[i], mPack[i]);
    glPixelStorei(kUnpackParams[i], mUnpack[i]);
  }
  glBindBuffer(GL_PIXEL_PACK_BUFFER, static_cast<GLuint>(mPackBuffer));
  glBindBuffer(GL_PIXEL_UNPACK_BUFFER, static_cast<GLuint>(mUnpackBuffer));
}

void PixelTransferState::setDefaults() {
  static_assert(std::size(kPackParams) == kParams && std::size(kUnpackParams) == kParams && std::size(kPixelDefaults) == kParams);
  for (size_t i = 0; i < kParams; ++i) {
    glPixelStorei(kPackParams[i], kPixelDefaults[i]);
    glPixelStorei(kUnpackParams[i], kPixelDefaults[i]);
  }
  glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
  glBindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
}

SavedGlState::SavedGlState() {
  mDrawFramebuffer = getInt(GL_DRAW_FRAMEBUFFER_BINDING);
  mReadFramebuffer = getInt(GL_READ_FRAMEBUFFER_BINDING);
  mProgram = getInt(GL_CURRENT_PROGRAM);
  mVertexArray = getInt(GL_VERTEX_ARRAY_BINDING);
  mActiveTexture = getInt(GL_ACTIVE_TEXTURE);
  glGetIntegerv(GL_VIEWPORT, mViewport.data());
  glGetDoublev(GL_DEPTH_RANGE, mDepthRange.data());
  mFrontFace = getInt(GL_FRONT_FACE);
  mDepthFunc = getInt(GL_DEPTH_FUNC);
  mClipOrigin = getInt(GL_CLIP_ORIGIN);
  mClipDepthMode = getInt(GL_CLIP_DEPTH_MODE);
  glGetIntegerv(GL_POLYGON_MODE, mPolygonMode.data());
  glGetBooleanv(GL_DEPTH_WRITEMASK, &mDepthMask);
  glGetBooleanv(GL_COLOR_WRITEMASK, mColorMask.data());
  mBlendFunc = {getInt(GL_BLEND_SRC_RGB), getInt(GL_BLEND_DST_RGB), getInt(GL_BLEND_SRC_ALPHA), getInt(GL_BLEND_DST_ALPHA)};
  mBlendEquation = {getInt(GL_BLEND_EQUATION_RGB), getInt(GL_BLEND_EQUATION_ALPHA)};
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
  glDepthRange(mDepthRange[0], mDepthRange[1]);
  glFrontFace(static_cast<GLenum>(mFrontFace));
  glDepthFunc(static_cast<GLenum>(mDepthFunc));
  glClipControl(static_cast<GLenum>(mClipOrigin), static_cast<GLenum>(mClipDepthMode));
  // GL 4.5 core takes one mode for both faces; the query reports it twice.
  glPolygonMode(GL_FRONT_AND_BACK, static_cast<GLenum>(mPolygonMode[0]));
  glDepthMask(mDepthMask);
  glColorMask(mColorMask[0], mColorMask[1], mColorMask[2], mColorMask[3]);
  glBlendFuncSeparate(static_cast<GLenum>(mBlendFunc[0]), static_cast<GLenum>(mBlendFunc[1]), static_cast<GLenum>(mBlendFunc[2]),
                      static_cast<GLenum>(mBlendFunc[3]));
  glBlendEquationSeparate(static_cast<GLenum>(mBlendEquation[0]), static_cast<GLenum>(mBlendEquation[1]));
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
  mPixelTransfer.restore();
}

void setPassDefaults() {
  for (size_t i = 0; i < kSwitchesOff; ++i) glDisable(kSwitches[i]);
  for (GLuint i = 0; i < kClipDistances; ++i) glDisable(GL_CLIP_DISTANCE0 + i);
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
  glFrontFace(GL_CCW);
  // Shadow passes write linear light depth through the window depth: all of [0, 1] of it.
  glDepthRange(0.0, 1.0);
  PixelTransferState::setDefaults();
  // Maps are addressed with uv = ndc·½ + ½ from the bottom row; the depth mode does not matter
  // (shadow passes write gl_FragDepth with depth clamping on).
  GLint depthMode = GL_NEGATIVE_ONE_TO_ONE;
  glGetIntegerv(GL_CLIP_DEPTH_MODE, &depthMode);
  glClipControl(GL_LOWER_LEFT, static_cast<GLenum>(depthMode));
}

}  // namespace penumbra::core
