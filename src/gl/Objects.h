#pragma once
// RAII, move-only wrappers over OpenGL 4.5 DSA objects. Each object carries a debug label
// (glObjectLabel) so captures and debug messages name it. Destruction deletes the object.
#include <epoxy/gl.h>
#include <glm/glm.hpp>

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string_view>
#include <utility>

namespace penumbra::gl {

/// Live-object counter, for the "no GL object growth" checks.
int liveObjectCount();

/// GPU memory held for an owner (a shadow technique: docs/bench.md, "shadow_memory_mb"). Every
/// Texture and Buffer created on this thread while a MemoryAccount::Charge is in scope counts its
/// storage bytes (every mip level and layer; Texture::storageBytes, Buffer::size) against the
/// account until it is destroyed, wherever it lives meanwhile (moves keep the charge). So what
/// an owner keeps is measured where the storage is allocated, once, and no owner lists its own
/// resources by hand. Copies share the count.
class MemoryAccount {
public:
  MemoryAccount();
  /// Bytes of the charged textures and buffers alive now.
  std::int64_t bytes() const { return mBytes->load(); }

  /// While alive, objects created on this thread are charged to `account` (scopes nest: the
  /// innermost wins; the previous account is current again afterwards).
  class Charge {
  public:
    explicit Charge(const MemoryAccount& account);
    ~Charge();
    Charge(const Charge&) = delete;
    Charge& operator=(const Charge&) = delete;

  private:
    std::shared_ptr<std::atomic<std::int64_t>> mPrevious;
  };

private:
  std::shared_ptr<std::atomic<std::int64_t>> mBytes;
};

namespace detail {
/// Bytes charged to the account that was current when charge() ran; released on destruction.
class ChargedBytes {
public:
  ChargedBytes() = default;
  ChargedBytes(ChargedBytes&& o) noexcept : mAccount(std::move(o.mAccount)), mBytes(std::exchange(o.mBytes, 0)) {}
  ChargedBytes& operator=(ChargedBytes&& o) noexcept {
    if (this != &o) {
      release();
      mAccount = std::move(o.mAccount);
      mBytes = std::exchange(o.mBytes, 0);
    }
    return *this;
  }
  ChargedBytes(const ChargedBytes&) = delete;
  ChargedBytes& operator=(const ChargedBytes&) = delete;
  ~ChargedBytes() { release(); }
  void charge(std::int64_t bytes);  ///< to the current account, if any
  void release();

private:
  std::shared_ptr<std::atomic<std::int64_t>> mAccount;
  std::int64_t mBytes = 0;
};
}  // namespace detail

class Handle {
public:
  Handle() = default;
  Handle(Handle&& o) noexcept : mId(std::exchange(o.mId, 0)) {}
  Handle& operator=(Handle&& o) noexcept {
    if (this != &o) { reset(); mId = std::exchange(o.mId, 0); }
    return *this;
  }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  GLuint id() const { return mId; }
  explicit operator bool() const { return mId != 0; }

protected:
  ~Handle() = default;
  virtual void destroy() = 0;
  void reset() { if (mId) { destroy(); mId = 0; } }
  void adopt(GLuint id);
  GLuint mId = 0;
};

class Buffer final : public Handle {
public:
  Buffer() = default;
  Buffer(std::string_view label, size_t bytes, const void* data = nullptr,
         GLbitfield flags = GL_DYNAMIC_STORAGE_BIT);
  ~Buffer() { reset(); }
  Buffer(Buffer&&) = default;
  Buffer& operator=(Buffer&&) = default;
  size_t size() const { return mSize; }
  void upload(const void* data, size_t bytes, size_t offset = 0);
  template <class T> void upload(const T& value) { upload(&value, sizeof(T)); }
  void download(void* data, size_t bytes, size_t offset = 0) const;
  void bindBase(GLenum target, GLuint index) const { glBindBufferBase(target, index, mId); }

private:
  void destroy() override;
  size_t mSize = 0;
  detail::ChargedBytes mCharge;
};

struct TextureDesc {
  GLenum target = GL_TEXTURE_2D;  ///< GL_TEXTURE_2D, GL_TEXTURE_2D_ARRAY or GL_TEXTURE_3D
  GLenum format = GL_RGBA8;       ///< sized internal format
  int width = 1, height = 1;
  int depth = 1;   ///< layers for arrays, depth for 3D
  int levels = 1;  ///< mip levels; 0 = a full chain
};

class Texture final : public Handle {
public:
  Texture() = default;
  Texture(std::string_view label, const TextureDesc& desc);
  ~Texture() { reset(); }
  Texture(Texture&&) = default;
  Texture& operator=(Texture&&) = default;
  const TextureDesc& desc() const { return mDesc; }
  int width() const { return mDesc.width; }
  int height() const { return mDesc.height; }
  int layers() const { return mDesc.depth; }
  int levels() const { return mDesc.levels; }
  /// Sets min/mag filter and clamp-to-edge wrapping.
  void setSampling(GLenum minFilter, GLenum magFilter, GLenum wrap = GL_CLAMP_TO_EDGE);
  /// Turns on hardware depth comparison (sampler2DShadow): lit when ref <= stored.
  void setCompare(bool on);
  void bindUnit(GLuint unit) const { glBindTextureUnit(unit, mId); }
  void bindImage(GLuint unit, GLenum access, int level = 0) const;
  /// Binds one layer of an array texture as a 2D image (image2D in the shader).
  void bindImageLayer(GLuint unit, GLenum access, int layer, int level = 0) const;
  /// A 2D texture that shows layer `layer` of a 2D array texture (glTextureView): the same
  /// storage, no copy. The view must not outlive `array`.
  static Texture layerView(std::string_view label, const Texture& array, int layer);
  /// Reads a whole level (all layers) as floats/bytes in `format`/`type`.
  void read(GLenum format, GLenum type, void* out, size_t bytes, int level = 0) const;
  /// Bytes of its storage: every level and layer at the bits per texel the driver reports for
  /// the format (red, green, blue, alpha, depth and stencil sizes of level 0).
  size_t storageBytes() const { return mStorageBytes; }

private:
  void destroy() override;
  TextureDesc mDesc;
  size_t mStorageBytes = 0;
  detail::ChargedBytes mCharge;
};

/// Sampling state kept apart from any texture: bound to a unit with glBindSampler, it overrides
/// the state of whatever texture is bound there, which itself stays as other passes expect.
struct SamplerDesc {
  GLenum minFilter = GL_LINEAR;    ///< GL_TEXTURE_MIN_FILTER
  GLenum magFilter = GL_LINEAR;    ///< GL_TEXTURE_MAG_FILTER
  GLenum wrap = GL_CLAMP_TO_EDGE;  ///< S, T and R
  bool compare = false;            ///< hardware depth comparison (sampler*Shadow): lit when ref <= stored
  /// GL_TEXTURE_REDUCTION_MODE_ARB: GL_WEIGHTED_AVERAGE_ARB (GL's own filter), or GL_MIN / GL_MAX
  /// of the texels the filter reads (GL_ARB_texture_filter_minmax: the caller checks for it).
  GLenum reduction = GL_WEIGHTED_AVERAGE_ARB;
};

class Sampler final : public Handle {
public:
  Sampler() = default;
  Sampler(std::string_view label, const SamplerDesc& desc);
  ~Sampler() { reset(); }
  Sampler(Sampler&&) = default;
  Sampler& operator=(Sampler&&) = default;
  void bindUnit(GLuint unit) const { glBindSampler(unit, mId); }
  /// Back to the bound texture's own sampling state.
  static void unbindUnit(GLuint unit) { glBindSampler(unit, 0); }

private:
  void destroy() override;
};

class Framebuffer final : public Handle {
public:
  Framebuffer() = default;
  explicit Framebuffer(std::string_view label);
  ~Framebuffer() { reset(); }
  Framebuffer(Framebuffer&&) = default;
  Framebuffer& operator=(Framebuffer&&) = default;
  /// Attaches `layer` of an array texture when layer >= 0, the whole texture otherwise.
  void attach(GLenum attachment, const Texture& texture, int level = 0, int layer = -1);
  /// Sets the draw buffers to COLOR_ATTACHMENT0..count-1 (0 = none) and checks completeness.
  void finish(int colorCount);

private:
  void destroy() override;
};

class VertexArray final : public Handle {
public:
  VertexArray() = default;
  explicit VertexArray(std::string_view label);
  ~VertexArray() { reset(); }
  VertexArray(VertexArray&&) = default;
  VertexArray& operator=(VertexArray&&) = default;

private:
  void destroy() override;
};

class Program final : public Handle {
public:
  Program() = default;
  /// Takes ownership of a linked program id; `compute`: whether it is a compute shader (run by
  /// glDispatchCompute) rather than a vertex and fragment pair (run by a draw).
  Program(std::string_view label, GLuint linkedProgram, bool compute = false);
  ~Program() { reset(); }
  Program(Program&&) = default;
  Program& operator=(Program&&) = default;
  void use() const { glUseProgram(mId); }
  bool isCompute() const { return mCompute; }

private:
  void destroy() override;
  bool mCompute = false;
};

class Query final : public Handle {
public:
  Query() = default;
  Query(std::string_view label, GLenum target);
  ~Query() { reset(); }
  Query(Query&&) = default;
  Query& operator=(Query&&) = default;

private:
  void destroy() override;
};

/// Maximum 2D texture size of the current context.
int maxTextureSize();

}  // namespace penumbra::gl
