#include "frame/CasterSet.h"

#include "base/Hash.h"
#include "gl/Draw.h"

#include "shared/Bindings.h"
#include "shared/Frame.h"

#include <penumbra/Error.h>

#include <fmt/format.h>
#include <glm/gtc/matrix_inverse.hpp>

#include <algorithm>
#include <cstdint>
#include <cstddef>
#include <cstring>

namespace penumbra {
namespace {

constexpr uint32_t kPositionBytes = 3 * sizeof(float);
constexpr uint32_t kUvBytes = 2 * sizeof(float);
// Vertex-buffer binding points of a caster's vertex array: the position stream and the uv stream
// are two bindings of the same buffer, each at its own offset, so any offset works (attribute
// relative offsets are limited to GL_MAX_VERTEX_ATTRIB_RELATIVE_OFFSET, as little as 2047 bytes).
constexpr GLuint kPositionBinding = 0, kUvBinding = 1;
// The shared vertex stage's attribute locations (passes/geometry.vert.glsl).
constexpr GLuint kPositionAttribute = 0, kUvAttribute = 2;

GLint64 bufferBytes(uint32_t buffer) {
  GLint64 bytes = 0;
  glGetNamedBufferParameteri64v(buffer, GL_BUFFER_SIZE, &bytes);
  return bytes;
}

void check(const CasterMesh& m, size_t i) {
  const auto fail = [i](const std::string& why) { throw usageError(fmt::format("caster {}: {}", i, why)); };
  if (m.vertexBuffer == 0 || !glIsBuffer(m.vertexBuffer)) fail(fmt::format("vertexBuffer {} is not a GL buffer", m.vertexBuffer));
  if (m.stride < kPositionBytes) fail(fmt::format("stride {} is below the 12 bytes of a position", m.stride));
  if (m.count == 0 || m.count % 3 != 0) fail(fmt::format("count {} is not a positive multiple of 3", m.count));
  const GLint64 vertexBytes = bufferBytes(m.vertexBuffer);
  if (m.indexBuffer != 0) {
    if (!glIsBuffer(m.indexBuffer)) fail(fmt::format("indexBuffer {} is not a GL buffer", m.indexBuffer));
    if (m.indexType != IndexType::UInt32 && m.indexType != IndexType::UInt16)
      fail(fmt::format("indexType {} is neither IndexType::UInt32 nor IndexType::UInt16", static_cast<uint32_t>(m.indexType)));
    const GLint64 needed = (static_cast<GLint64>(m.firstIndex) + m.count) * static_cast<GLint64>(indexBytes(m.indexType));
    if (needed > bufferBytes(m.indexBuffer))
      fail(fmt::format("indices {}..{} lie beyond index buffer {} ({} bytes)", m.firstIndex, m.firstIndex + m.count - 1,
                       m.indexBuffer, bufferBytes(m.indexBuffer)));
  } else {
    const GLint64 last = static_cast<GLint64>(m.firstIndex) + m.count - 1;
    const GLint64 needed = last * m.stride + m.positionOffset + kPositionBytes;
    if (needed > vertexBytes)
      fail(fmt::format("vertices {}..{} lie beyond vertex buffer {} ({} bytes)", m.firstIndex, last, m.vertexBuffer, vertexBytes));
  }
  if (m.positionOffset + kPositionBytes > vertexBytes) fail(fmt::format("positionOffset {} lies beyond the vertex buffer", m.positionOffset));
  for (int c = 0; c < 3; ++c)
    if (!(m.transmittance[c] >= 0.0f && m.transmittance[c] <= 1.0f))
      fail(fmt::format("transmittance ({}, {}, {}) is outside [0, 1]", m.transmittance.r, m.transmittance.g, m.transmittance.b));
  if (m.alphaTexture != 0) {
    if (!glIsTexture(m.alphaTexture)) fail(fmt::format("alphaTexture {} is not a GL texture", m.alphaTexture));
    if (m.uvOffset == kNoAttribute) fail("an alphaTexture needs a uvOffset (the texture coordinate it is read at)");
    if (m.uvOffset + kUvBytes > vertexBytes) fail(fmt::format("uvOffset {} lies beyond the vertex buffer", m.uvOffset));
  }
}

bool isOf(const CasterMesh& m, CasterSet::Which which) {
  return which == CasterSet::Which::All || (which == CasterSet::Which::Dynamic) == m.dynamic;
}

}  // namespace

glm::vec3 CasterGeometry::corner(size_t t, int c) const {
  size_t vertex = 3 * t + static_cast<size_t>(c);
  if (!indices.empty()) {
    if (indexType == IndexType::UInt16) {
      uint16_t i = 0;
      std::memcpy(&i, indices.data() + vertex * sizeof(uint16_t), sizeof(i));
      vertex = i;
    } else {
      uint32_t i = 0;
      std::memcpy(&i, indices.data() + vertex * sizeof(uint32_t), sizeof(i));
      vertex = i;
    }
  }
  glm::vec3 p(0.0f);
  std::memcpy(&p, vertices.data() + vertex * stride + positionOffset, sizeof(p));
  return p;
}

std::vector<CasterGeometry> casterGeometry(const Scene& scene) {
  std::vector<CasterGeometry> out;
  for (const Object& o : scene.objects) {
    if (!o.castsShadow) continue;
    const Mesh& mesh = scene.meshes[o.mesh];
    CasterGeometry g;
    g.vertices = std::as_bytes(std::span<const glm::vec3>(mesh.positions));
    g.stride = sizeof(glm::vec3);
    g.positionOffset = 0;
    g.indices = std::as_bytes(std::span<const uint32_t>(mesh.indices));
    g.indexType = IndexType::UInt32;
    g.worldFromObject = o.worldFromObject;
    out.push_back(g);
  }
  return out;
}

void checkCasterGeometry(const CasterGeometry& g, size_t i) {
  const auto fail = [i](const std::string& why) { throw usageError(fmt::format("caster geometry {}: {}", i, why)); };
  if (g.stride < kPositionBytes) fail(fmt::format("stride {} is below the 12 bytes of a position", g.stride));
  if (g.positionOffset + kPositionBytes > g.stride)
    fail(fmt::format("positionOffset {} + 12 bytes lies beyond the stride {}", g.positionOffset, g.stride));
  if (g.vertices.size() % g.stride != 0) fail(fmt::format("{} vertex bytes are not whole records of {}", g.vertices.size(), g.stride));
  const size_t count = g.indices.empty() ? g.vertexCount() : g.indices.size() / indexBytes(g.indexType);
  if (count % 3 != 0) fail(fmt::format("{} {} are not whole triangles", count, g.indices.empty() ? "vertices" : "indices"));
  if (!g.indices.empty() && g.indices.size() % indexBytes(g.indexType) != 0) fail("the index bytes are not whole indices");
  for (size_t k = 0; k < (g.indices.empty() ? 0 : count); ++k) {
    uint32_t index = 0;
    if (g.indexType == IndexType::UInt16) {
      uint16_t i16 = 0;
      std::memcpy(&i16, g.indices.data() + k * sizeof(uint16_t), sizeof(i16));
      index = i16;
    } else {
      std::memcpy(&index, g.indices.data() + k * sizeof(uint32_t), sizeof(index));
    }
    if (index >= g.vertexCount()) fail(fmt::format("index {} ({}) is beyond its {} vertices", k, index, g.vertexCount()));
  }
}

size_t CasterSet::vaoFor(const Layout& layout) {
  for (size_t i = 0; i < mLayouts.size(); ++i)
    if (mLayouts[i] == layout) return i;
  gl::VertexArray vao(fmt::format("casters vao {}", mLayouts.size()));
  const GLuint id = vao.id();
  glVertexArrayVertexBuffer(id, kPositionBinding, layout.vertexBuffer, layout.positionOffset, static_cast<GLsizei>(layout.stride));
  glEnableVertexArrayAttrib(id, kPositionAttribute);
  glVertexArrayAttribFormat(id, kPositionAttribute, 3, GL_FLOAT, GL_FALSE, 0);
  glVertexArrayAttribBinding(id, kPositionAttribute, kPositionBinding);
  if (layout.uvOffset != kNoAttribute) {
    glVertexArrayVertexBuffer(id, kUvBinding, layout.vertexBuffer, layout.uvOffset, static_cast<GLsizei>(layout.stride));
    glEnableVertexArrayAttrib(id, kUvAttribute);
    glVertexArrayAttribFormat(id, kUvAttribute, 2, GL_FLOAT, GL_FALSE, 0);
    glVertexArrayAttribBinding(id, kUvAttribute, kUvBinding);
  }
  if (layout.indexBuffer != 0) glVertexArrayElementBuffer(id, layout.indexBuffer);
  mLayouts.push_back(layout);
  mVaos.push_back(std::move(vao));
  return mLayouts.size() - 1;
}

void CasterSet::set(std::span<const CasterMesh> casters) {
  for (size_t i = 0; i < casters.size(); ++i) check(casters[i], i);
  // Vertex arrays of layouts no caster uses any more would keep names of buffers the caller may
  // delete: start over when the set of layouts shrinks.
  std::vector<Layout> wanted;
  for (const CasterMesh& m : casters) {
    const Layout l{m.vertexBuffer, m.indexBuffer, m.stride, m.positionOffset, m.alphaTexture ? m.uvOffset : kNoAttribute};
    if (std::find(wanted.begin(), wanted.end(), l) == wanted.end()) wanted.push_back(l);
  }
  for (const Layout& l : mLayouts)
    if (std::find(wanted.begin(), wanted.end(), l) == wanted.end()) {
      mLayouts.clear();
      mVaos.clear();
      break;
    }
  mDraws.clear();
  std::vector<gpu::ObjectGpu> objects;
  objects.reserve(casters.size());
  for (const CasterMesh& m : casters) {
    const Layout l{m.vertexBuffer, m.indexBuffer, m.stride, m.positionOffset, m.alphaTexture ? m.uvOffset : kNoAttribute};
    mDraws.push_back({vaoFor(l), m});
    gpu::ObjectGpu g{};
    g.worldFromObject = m.worldFromObject;
    g.normalFromObject = glm::mat4(glm::inverseTranspose(glm::mat3(m.worldFromObject)));
    const bool masked = m.alphaTexture != 0;
    g.baseColor = glm::vec4(m.translucent() ? m.transmittance : glm::vec3(1.0f), masked ? m.alphaCutoff : 0.0f);
    // material.z: 1 for a translucent caster, which the shadow passes' dither reads (common/material.glsl).
    g.material = glm::ivec4(masked ? 0 : -1, masked ? 1 : 0, m.translucent() ? 1 : 0, 0);
    objects.push_back(g);
  }
  mTranslucent = std::any_of(casters.begin(), casters.end(), [](const CasterMesh& m) { return m.translucent(); });
  Hasher statics;
  for (const Draw& d : mDraws) {
    const CasterMesh& m = d.mesh;
    if (m.dynamic) continue;
    for (const uint32_t v : {m.vertexBuffer, m.stride, m.positionOffset, m.uvOffset, m.indexBuffer, m.firstIndex, m.count,
                             static_cast<uint32_t>(m.baseVertex), m.alphaTexture})
      statics.value(v);
    if (m.indexType != IndexType::UInt32) statics.value(static_cast<uint32_t>(m.indexType));
    statics.value(m.worldFromObject);
    statics.value(m.alphaCutoff);
    if (m.translucent()) statics.value(m.transmittance);
  }
  mStaticKey = statics.digest();
  const size_t bytes = std::max<size_t>(1, objects.size()) * sizeof(gpu::ObjectGpu);
  if (mObjects.size() < bytes) mObjects = gl::Buffer("caster objects", bytes);
  if (!objects.empty()) mObjects.upload(objects.data(), objects.size() * sizeof(gpu::ObjectGpu));
}

void CasterSet::draw(GLuint opaqueProgram, GLuint maskedProgram, Which which, Translucent translucent,
                     std::span<const uint8_t> only) const {
  mObjects.bindBase(GL_SHADER_STORAGE_BUFFER, PN_SSBO_OBJECTS);
  for (const bool masked : {false, true}) {
    const GLuint program = masked ? maskedProgram : opaqueProgram;
    glUseProgram(program);
    for (size_t i = 0; i < mDraws.size(); ++i) {
      const CasterMesh& m = mDraws[i].mesh;
      if ((m.alphaTexture != 0) != masked) continue;
      if (!isOf(m, which) || (!only.empty() && only[i] == 0)) continue;
      if (translucent != Translucent::AsOpaque && m.translucent() != (translucent == Translucent::Only)) continue;
      glBindVertexArray(mVaos[mDraws[i].vao].id());
      glProgramUniform1i(program, PN_LOC_OBJECT, static_cast<GLint>(i));
      if (masked) glBindTextureUnit(PN_TEX_BASECOLOR, m.alphaTexture);
      if (m.indexBuffer != 0)
        gl::drawTriangles(m.indexType == IndexType::UInt16 ? GL_UNSIGNED_SHORT : GL_UNSIGNED_INT, m.firstIndex, m.count,
                          m.baseVertex);
      else
        gl::drawTriangleArrays(m.firstIndex, m.count);
    }
  }
}

std::vector<CasterSet::Placement> CasterSet::placements() const {
  std::vector<Placement> out;
  out.reserve(mDraws.size());
  for (const Draw& d : mDraws) {
    const CasterMesh& m = d.mesh;
    Hasher h;
    for (const uint32_t v : {m.vertexBuffer, m.stride, m.positionOffset, m.uvOffset, m.indexBuffer, m.firstIndex, m.count,
                             static_cast<uint32_t>(m.baseVertex), m.alphaTexture, static_cast<uint32_t>(m.indexType)})
      h.value(v);
    h.value(m.worldFromObject);
    h.value(m.alphaCutoff);
    out.push_back({m.objectBounds.transformed(m.worldFromObject), m.dynamic, h.digest()});
  }
  return out;
}

std::vector<SceneExtent::Body> CasterSet::bodies(Which which) const {
  std::vector<SceneExtent::Body> out;
  out.reserve(mDraws.size());
  for (const Draw& d : mDraws)
    if (isOf(d.mesh, which)) out.push_back({d.mesh.objectBounds.transformed(d.mesh.worldFromObject), true});
  return out;
}

}  // namespace penumbra
