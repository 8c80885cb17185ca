#include "gl/Objects.h"

#include "gl/Debug.h"

#include <penumbra/Error.h>

#include <algorithm>
#include <atomic>
#include <initializer_list>
#include <fmt/format.h>

namespace penumbra::gl {
namespace {
std::atomic<int> gLiveObjects{0};

GLenum labelNamespace(GLenum target) { return target; }

void label(GLenum ns, GLuint id, std::string_view text) {
  if (!text.empty()) glObjectLabel(labelNamespace(ns), id, static_cast<GLsizei>(text.size()), text.data());
}
}  // namespace

int liveObjectCount() { return gLiveObjects.load(); }

// ---- MemoryAccount ------------------------------------------------------------------------
namespace {
thread_local std::shared_ptr<std::atomic<std::int64_t>> tCurrentAccount;
}  // namespace

MemoryAccount::MemoryAccount() : mBytes(std::make_shared<std::atomic<std::int64_t>>(0)) {}

MemoryAccount::Charge::Charge(const MemoryAccount& account) : mPrevious(std::exchange(tCurrentAccount, account.mBytes)) {}
MemoryAccount::Charge::~Charge() { tCurrentAccount = std::move(mPrevious); }

namespace detail {
void ChargedBytes::charge(std::int64_t bytes) {
  release();
  if (!tCurrentAccount) return;
  mAccount = tCurrentAccount;
  mBytes = bytes;
  *mAccount += bytes;
}
void ChargedBytes::release() {
  if (mAccount) *mAccount -= mBytes;
  mAccount.reset();
  mBytes = 0;
}
}  // namespace detail

void Handle::adopt(GLuint id) {
  mId = id;
  if (id) ++gLiveObjects;
}

// ---- Buffer -----------------------------------------------------------------------------
Buffer::Buffer(std::string_view name, size_t bytes, const void* data, GLbitfield flags) : mSize(bytes) {
  GLuint id = 0;
  glCreateBuffers(1, &id);
  adopt(id);
  glNamedBufferStorage(id, static_cast<GLsizeiptr>(bytes), data, flags);
  label(GL_BUFFER, id, name);
  mCharge.charge(static_cast<std::int64_t>(bytes));
}
void Buffer::destroy() { glDeleteBuffers(1, &mId); --gLiveObjects; }
void Buffer::upload(const void* data, size_t bytes, size_t offset) {
  PN_ASSERT(offset + bytes <= mSize);
  glNamedBufferSubData(mId, static_cast<GLintptr>(offset), static_cast<GLsizeiptr>(bytes), data);
}
void Buffer::download(void* data, size_t bytes, size_t offset) const {
  PN_ASSERT(offset + bytes <= mSize);
  glGetNamedBufferSubData(mId, static_cast<GLintptr>(offset), static_cast<GLsizeiptr>(bytes), data);
}

// ---- Texture ----------------------------------------------------------------------------
Texture::Texture(std::string_view name, const TextureDesc& desc) : mDesc(desc) {
  PN_CHECK(desc.width > 0 && desc.height > 0 && desc.depth > 0, "texture size must be positive");
  const int maxSize = maxTextureSize();
  PN_CHECK(desc.width <= maxSize && desc.height <= maxSize,
           fmt::format("texture '{}' of {}x{} exceeds the driver's maximum of {}", name, desc.width,
                       desc.height, maxSize));
  if (mDesc.levels == 0) {
    int levels = 1;
    for (int s = std::max(desc.width, desc.height); s > 1; s /= 2) ++levels;
    mDesc.levels = levels;
  }
  GLuint id = 0;
  glCreateTextures(desc.target, 1, &id);
  adopt(id);
  if (desc.target == GL_TEXTURE_2D)
    glTextureStorage2D(id, mDesc.levels, desc.format, desc.width, desc.height);
  else
    glTextureStorage3D(id, mDesc.levels, desc.format, desc.width, desc.height, desc.depth);
  label(GL_TEXTURE, id, name);
  setSampling(mDesc.levels > 1 ? GL_LINEAR_MIPMAP_LINEAR : GL_LINEAR, GL_LINEAR);
  GLint bitsPerTexel = 0;
  for (const GLenum component : {GL_TEXTURE_RED_SIZE, GL_TEXTURE_GREEN_SIZE, GL_TEXTURE_BLUE_SIZE, GL_TEXTURE_ALPHA_SIZE,
                                 GL_TEXTURE_DEPTH_SIZE, GL_TEXTURE_STENCIL_SIZE}) {
    GLint bits = 0;
    glGetTextureLevelParameteriv(id, 0, component, &bits);
    bitsPerTexel += bits;
  }
  size_t texels = 0;
  for (int level = 0; level < mDesc.levels; ++level) {
    const size_t w = static_cast<size_t>(std::max(1, desc.width >> level));
    const size_t h = static_cast<size_t>(std::max(1, desc.height >> level));
    // A 3D texture's depth halves with each level; an array keeps its layers.
    const size_t d = static_cast<size_t>(desc.target == GL_TEXTURE_3D ? std::max(1, desc.depth >> level) : desc.depth);
    texels += w * h * d;
  }
  mStorageBytes = texels * static_cast<size_t>(bitsPerTexel) / 8;
  mCharge.charge(static_cast<std::int64_t>(mStorageBytes));
}
void Texture::destroy() { glDeleteTextures(1, &mId); --gLiveObjects; }
void Texture::setSampling(GLenum minFilter, GLenum magFilter, GLenum wrap) {
  glTextureParameteri(mId, GL_TEXTURE_MIN_FILTER, static_cast<GLint>(minFilter));
  glTextureParameteri(mId, GL_TEXTURE_MAG_FILTER, static_cast<GLint>(magFilter));
  glTextureParameteri(mId, GL_TEXTURE_WRAP_S, static_cast<GLint>(wrap));
  glTextureParameteri(mId, GL_TEXTURE_WRAP_T, static_cast<GLint>(wrap));
  glTextureParameteri(mId, GL_TEXTURE_WRAP_R, static_cast<GLint>(wrap));
}
void Texture::setCompare(bool on) {
  glTextureParameteri(mId, GL_TEXTURE_COMPARE_MODE, on ? GL_COMPARE_REF_TO_TEXTURE : GL_NONE);
  glTextureParameteri(mId, GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
}
void Texture::bindImage(GLuint unit, GLenum access, int level) const {
  const GLboolean layered = mDesc.target == GL_TEXTURE_2D ? GL_FALSE : GL_TRUE;
  glBindImageTexture(unit, mId, level, layered, 0, access, mDesc.format);
}
void Texture::bindImageLayer(GLuint unit, GLenum access, int layer, int level) const {
  glBindImageTexture(unit, mId, level, GL_FALSE, layer, access, mDesc.format);
}
Texture Texture::layerView(std::string_view name, const Texture& array, int layer) {
  PN_CHECK(array.desc().target == GL_TEXTURE_2D_ARRAY && layer >= 0 && layer < array.layers(),
           fmt::format("texture view '{}': layer {} of a {}-layer array", name, layer, array.layers()));
  Texture t;
  t.mDesc = array.desc();
  t.mDesc.target = GL_TEXTURE_2D;
  t.mDesc.depth = 1;
  GLuint id = 0;
  glGenTextures(1, &id);  // a view needs a name without storage: glCreateTextures would give it one
  glTextureView(id, GL_TEXTURE_2D, array.id(), t.mDesc.format, 0, static_cast<GLuint>(t.mDesc.levels),
                static_cast<GLuint>(layer), 1);
  t.adopt(id);
  label(GL_TEXTURE, id, name);
  return t;
}
void Texture::read(GLenum format, GLenum type, void* out, size_t bytes, int level) const {
  glGetTextureImage(mId, level, format, type, static_cast<GLsizei>(bytes), out);
}

// ---- Sampler ----------------------------------------------------------------------------
Sampler::Sampler(std::string_view name, const SamplerDesc& desc) {
  GLuint id = 0;
  glCreateSamplers(1, &id);
  adopt(id);
  label(GL_SAMPLER, id, name);
  glSamplerParameteri(id, GL_TEXTURE_MIN_FILTER, static_cast<GLint>(desc.minFilter));
  glSamplerParameteri(id, GL_TEXTURE_MAG_FILTER, static_cast<GLint>(desc.magFilter));
  for (GLenum wrap : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R})
    glSamplerParameteri(id, wrap, static_cast<GLint>(desc.wrap));
  glSamplerParameteri(id, GL_TEXTURE_COMPARE_MODE, desc.compare ? GL_COMPARE_REF_TO_TEXTURE : GL_NONE);
  glSamplerParameteri(id, GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
  if (desc.reduction != GL_WEIGHTED_AVERAGE_ARB)  // not set otherwise: contexts without the extension
    glSamplerParameteri(id, GL_TEXTURE_REDUCTION_MODE_ARB, static_cast<GLint>(desc.reduction));
}
void Sampler::destroy() { glDeleteSamplers(1, &mId); --gLiveObjects; }

// ---- Framebuffer ------------------------------------------------------------------------
Framebuffer::Framebuffer(std::string_view name) {
  GLuint id = 0;
  glCreateFramebuffers(1, &id);
  adopt(id);
  label(GL_FRAMEBUFFER, id, name);
}
void Framebuffer::destroy() { glDeleteFramebuffers(1, &mId); --gLiveObjects; }
void Framebuffer::attach(GLenum attachment, const Texture& texture, int level, int layer) {
  if (layer >= 0)
    glNamedFramebufferTextureLayer(mId, attachment, texture.id(), level, layer);
  else
    glNamedFramebufferTexture(mId, attachment, texture.id(), level);
}
void Framebuffer::finish(int colorCount) {
  GLenum buffers[8];
  PN_ASSERT(colorCount <= 8);
  for (int i = 0; i < colorCount; ++i) buffers[i] = GL_COLOR_ATTACHMENT0 + static_cast<GLenum>(i);
  if (colorCount == 0)
    glNamedFramebufferDrawBuffer(mId, GL_NONE);
  else
    glNamedFramebufferDrawBuffers(mId, colorCount, buffers);
  const GLenum status = glCheckNamedFramebufferStatus(mId, GL_FRAMEBUFFER);
  if (status == GL_FRAMEBUFFER_COMPLETE) return;
  // A texture whose storage could not be allocated leaves its framebuffer incomplete: report the
  // driver's error (out of memory, with advice) rather than the status it caused.
  throwIfGlError("a framebuffer's attachments");
  throw Error(fmt::format("framebuffer incomplete (status 0x{:04x})", status));
}

// ---- VertexArray, Program, Query ---------------------------------------------------------
VertexArray::VertexArray(std::string_view name) {
  GLuint id = 0;
  glCreateVertexArrays(1, &id);
  adopt(id);
  label(GL_VERTEX_ARRAY, id, name);
}
void VertexArray::destroy() { glDeleteVertexArrays(1, &mId); --gLiveObjects; }

Program::Program(std::string_view name, GLuint linkedProgram, bool compute) : mCompute(compute) {
  adopt(linkedProgram);
  label(GL_PROGRAM, linkedProgram, name);
}
void Program::destroy() { glDeleteProgram(mId); --gLiveObjects; }

Query::Query(std::string_view name, GLenum target) {
  GLuint id = 0;
  glCreateQueries(target, 1, &id);
  adopt(id);
  label(GL_QUERY, id, name);
}
void Query::destroy() { glDeleteQueries(1, &mId); --gLiveObjects; }

int maxTextureSize() {
  GLint v = 0;
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &v);
  return v;
}

}  // namespace penumbra::gl
