#include "renderer/GpuScene.h"

#include "gl/Draw.h"
#include "shared/Bindings.h"
#include "shared/Frame.h"

#include <penumbra/Error.h>

#include <fmt/format.h>
#include <glm/gtc/matrix_inverse.hpp>

#include <algorithm>

namespace penumbra {
namespace {

// sRGB storage: the shaders read linear colour (texelFetch decodes), alpha stays linear. One
// level: materials are sampled at the nearest texel (material.glsl), like the reference does.
gl::Texture uploadImage(const std::string& label, int width, int height, const uint8_t* rgba) {
  gl::Texture t(label, {GL_TEXTURE_2D, GL_SRGB8_ALPHA8, width, height, 1, 1});
  glTextureSubImage2D(t.id(), 0, 0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, rgba);
  t.setSampling(GL_NEAREST, GL_NEAREST, GL_REPEAT);
  return t;
}

}  // namespace

GpuScene::GpuScene(const Scene& scene) {
  const uint8_t white[4] = {255, 255, 255, 255};
  mWhite = uploadImage("white texture", 1, 1, white);
  mTextures.resize(scene.images.size());
  const int maxSide = gl::maxTextureSize();
  for (const Material& mat : scene.materials) {
    if (mat.baseColorTexture < 0) continue;
    const auto i = static_cast<size_t>(mat.baseColorTexture);
    if (mTextures[i]) continue;
    const Image& im = scene.images[i];
    PN_CHECK(im.width > 0 && im.height > 0 && im.width <= maxSide && im.height <= maxSide &&
                 im.rgba.size() == 4 * static_cast<size_t>(im.width) * static_cast<size_t>(im.height),
             fmt::format("image {} of material '{}' is {}x{} with {} bytes (each side 1..{}, RGBA8)", i, mat.name,
                         im.width, im.height, im.rgba.size(), maxSide));
    mTextures[i] = uploadImage(fmt::format("image {}", i), im.width, im.height, im.rgba.data());
  }
  // Which attributes each mesh uploads: its normals when it has them (none: the G-buffer shades
  // each triangle by its plane), its uvs when an object draws it with a textured material.
  std::vector<uint8_t> wantsUv(scene.meshes.size(), 0);
  for (const Object& o : scene.objects)
    if (scene.materials[o.material].baseColorTexture >= 0) wantsUv[o.mesh] = 1;
  std::vector<size_t> meshLayout(scene.meshes.size());
  std::vector<GLint> meshBase(scene.meshes.size());
  std::vector<size_t> meshFirstIndex(scene.meshes.size());
  size_t vertexCounts[kLayouts] = {}, indexCount = 0;
  for (size_t i = 0; i < scene.meshes.size(); ++i) {
    const Mesh& m = scene.meshes[i];
    const bool uv = wantsUv[i] && !m.uvs.empty();
    meshLayout[i] = (m.normals.empty() ? 0 : 1) + (uv ? 2 : 0);
    meshBase[i] = static_cast<GLint>(vertexCounts[meshLayout[i]]);
    meshFirstIndex[i] = indexCount;
    vertexCounts[meshLayout[i]] += m.vertexCount();
    indexCount += m.indices.size();
  }
  mIndices = gl::Buffer("scene indices", std::max<size_t>(indexCount, 1) * sizeof(uint32_t));
  for (size_t l = 0; l < kLayouts; ++l) {
    Layout& layout = mLayouts[l];
    layout.normal = (l & 1) != 0;
    layout.uv = (l & 2) != 0;
    if (vertexCounts[l] == 0) continue;
    layout.vertices = gl::Buffer(fmt::format("scene vertices {}", l), vertexCounts[l] * layout.stride());
    layout.vao = gl::VertexArray(fmt::format("scene vao {}", l));
    const GLuint vao = layout.vao.id();
    glVertexArrayVertexBuffer(vao, 0, layout.vertices.id(), 0, static_cast<GLsizei>(layout.stride()));
    glVertexArrayElementBuffer(vao, mIndices.id());
    glEnableVertexArrayAttrib(vao, 0);
    glVertexArrayAttribFormat(vao, 0, 3, GL_FLOAT, GL_FALSE, 0);
    glVertexArrayAttribBinding(vao, 0, 0);
    if (layout.normal) {  // absent: the attribute reads the constant 0 that draw() sets, "flat"
      glEnableVertexArrayAttrib(vao, 1);
      glVertexArrayAttribFormat(vao, 1, 3, GL_FLOAT, GL_FALSE, 12);
      glVertexArrayAttribBinding(vao, 1, 0);
    }
    if (layout.uv) {
      glEnableVertexArrayAttrib(vao, 2);
      glVertexArrayAttribFormat(vao, 2, 2, GL_FLOAT, GL_FALSE, layout.uvOffset());
      glVertexArrayAttribBinding(vao, 2, 0);
    }
  }
  // Interleaved a slice at a time: the upload's scratch stays small whatever the mesh.
  constexpr size_t kSliceVertices = size_t(1) << 16;
  std::vector<float> scratch;
  for (size_t i = 0; i < scene.meshes.size(); ++i) {
    const Mesh& m = scene.meshes[i];
    Layout& layout = mLayouts[meshLayout[i]];
    const size_t stride = layout.stride(), first = static_cast<size_t>(meshBase[i]);
    if (!m.indices.empty()) mIndices.upload(m.indices.data(), m.indices.size() * sizeof(uint32_t), meshFirstIndex[i] * sizeof(uint32_t));
    if (!layout.normal && !layout.uv) {
      if (m.vertexCount() > 0) layout.vertices.upload(m.positions.data(), m.vertexCount() * stride, first * stride);
      continue;
    }
    for (size_t begin = 0; begin < m.vertexCount(); begin += kSliceVertices) {
      const size_t end = std::min(m.vertexCount(), begin + kSliceVertices);
      scratch.clear();
      for (size_t v = begin; v < end; ++v) {
        scratch.insert(scratch.end(), {m.positions[v].x, m.positions[v].y, m.positions[v].z});
        if (layout.normal) scratch.insert(scratch.end(), {m.normals[v].x, m.normals[v].y, m.normals[v].z});
        if (layout.uv) scratch.insert(scratch.end(), {m.uvs[v].x, m.uvs[v].y});
      }
      layout.vertices.upload(scratch.data(), scratch.size() * sizeof(float), (first + begin) * stride);
    }
  }
  std::vector<gpu::ObjectGpu>& objects = mObjectData;
  for (const Object& o : scene.objects) {
    const Mesh& m = scene.meshes[o.mesh];
    const Material& mat = scene.materials[o.material];
    const GLuint texture = mat.baseColorTexture >= 0 ? mTextures[static_cast<size_t>(mat.baseColorTexture)].id() : mWhite.id();
    mDraws.push_back({static_cast<GLsizei>(m.indices.size()), meshFirstIndex[o.mesh], meshBase[o.mesh], meshLayout[o.mesh],
                      o.castsShadow, texture});
    gpu::ObjectGpu g{};
    g.worldFromObject = o.worldFromObject;
    g.normalFromObject = glm::mat4(glm::inverseTranspose(glm::mat3(o.worldFromObject)));
    g.baseColor = glm::vec4(mat.baseColor, mat.alphaMask ? mat.alphaCutoff : 0.0f);
    g.material = glm::ivec4(mat.baseColorTexture, mat.alphaMask ? 1 : 0, 0, 0);
    objects.push_back(g);
  }
  mObjects = gl::Buffer("scene objects", objects.size() * sizeof(gpu::ObjectGpu), objects.data(), GL_DYNAMIC_STORAGE_BIT);
}

void GpuScene::setTransforms(const Scene& scene) {
  PN_CHECK(scene.objects.size() == mObjectData.size(),
           fmt::format("GpuScene::setTransforms: {} objects for a scene of {}", scene.objects.size(), mObjectData.size()));
  for (size_t i = 0; i < mObjectData.size(); ++i) {
    const glm::mat4& m = scene.objects[i].worldFromObject;
    mObjectData[i].worldFromObject = m;
    mObjectData[i].normalFromObject = glm::mat4(glm::inverseTranspose(glm::mat3(m)));
  }
  mObjects.upload(mObjectData.data(), mObjectData.size() * sizeof(gpu::ObjectGpu));
}

void GpuScene::draw(GLuint program, GLint firstTriangleLocation) const {
  // What a layout without normals or uvs reads: a zero normal (flat, gbuffer.frag.glsl) and uv 0.
  glVertexAttrib3f(1, 0.0f, 0.0f, 0.0f);
  glVertexAttrib2f(2, 0.0f, 0.0f);
  mObjects.bindBase(GL_SHADER_STORAGE_BUFFER, PN_SSBO_OBJECTS);
  size_t bound = kLayouts;
  for (size_t i = 0; i < mDraws.size(); ++i) {
    const Draw& d = mDraws[i];
    if (d.layout != bound) glBindVertexArray(mLayouts[d.layout].vao.id());
    bound = d.layout;
    glProgramUniform1i(program, PN_LOC_OBJECT, static_cast<GLint>(i));
    glBindTextureUnit(PN_TEX_BASECOLOR, d.texture);
    gl::drawTriangles(GL_UNSIGNED_INT, d.firstIndex, d.indexCount, d.baseVertex, [&](size_t firstTriangle) {
      if (firstTriangleLocation >= 0)
        glProgramUniform1ui(program, firstTriangleLocation, static_cast<GLuint>(firstTriangle));
    });
  }
  glBindVertexArray(0);
}

std::vector<CasterMesh> GpuScene::casterMeshes(const Scene& scene) const {
  std::vector<CasterMesh> out;
  const std::vector<bool> moving = scene.animation.movingObjects(scene.objects.size());
  for (size_t i = 0; i < mDraws.size(); ++i) {
    const Draw& d = mDraws[i];
    if (!d.castsShadow || d.indexCount == 0) continue;
    const Object& o = scene.objects[i];
    const Material& mat = scene.materials[o.material];
    const Layout& layout = mLayouts[d.layout];
    CasterMesh m;
    m.vertexBuffer = layout.vertices.id();
    m.stride = layout.stride();
    m.positionOffset = 0;
    m.uvOffset = layout.uv ? layout.uvOffset() : kNoAttribute;
    m.indexBuffer = mIndices.id();
    m.firstIndex = static_cast<uint32_t>(d.firstIndex);
    m.count = static_cast<uint32_t>(d.indexCount);
    m.baseVertex = d.baseVertex;
    m.worldFromObject = o.worldFromObject;
    m.objectBounds = scene.meshes[o.mesh].bounds();
    m.dynamic = moving[i] || o.dynamic;  // animated or declared dynamic (cached maps keep the rest)
    m.transmittance = mat.transmittance;
    if (mat.alphaMask && mat.baseColorTexture >= 0 && layout.uv) {
      m.alphaTexture = d.texture;
      m.alphaCutoff = mat.alphaCutoff;
    }
    out.push_back(m);
  }
  return out;
}

}  // namespace penumbra
