#include "render/GpuScene.h"

#include "shared/Bindings.h"
#include "shared/Frame.h"

#include <penumbra/Error.h>

#include <fmt/format.h>
#include <glm/gtc/matrix_inverse.hpp>

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

GpuScene::GpuScene(const Scene& scene) : mVao("scene vao") {
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
  std::vector<Vertex> vertices;
  std::vector<uint32_t> indices;
  std::vector<std::pair<size_t, size_t>> meshRanges;  // first vertex, first index
  for (const Mesh& m : scene.meshes) {
    meshRanges.emplace_back(vertices.size(), indices.size());
    vertices.insert(vertices.end(), m.vertices.begin(), m.vertices.end());
    indices.insert(indices.end(), m.indices.begin(), m.indices.end());
  }
  std::vector<gpu::ObjectGpu>& objects = mObjectData;
  for (const Object& o : scene.objects) {
    const Mesh& m = scene.meshes[o.mesh];
    const Material& mat = scene.materials[o.material];
    const GLuint texture = mat.baseColorTexture >= 0 ? mTextures[static_cast<size_t>(mat.baseColorTexture)].id() : mWhite.id();
    mDraws.push_back({static_cast<GLsizei>(m.indices.size()), meshRanges[o.mesh].second,
                      static_cast<GLint>(meshRanges[o.mesh].first), o.castsShadow, texture});
    gpu::ObjectGpu g{};
    g.worldFromObject = o.worldFromObject;
    g.normalFromObject = glm::mat4(glm::inverseTranspose(glm::mat3(o.worldFromObject)));
    g.baseColor = glm::vec4(mat.baseColor, mat.alphaMask ? mat.alphaCutoff : 0.0f);
    g.material = glm::ivec4(mat.baseColorTexture, mat.alphaMask ? 1 : 0, 0, 0);
    objects.push_back(g);
  }
  mVertices = gl::Buffer("scene vertices", vertices.size() * sizeof(Vertex), vertices.data(), 0);
  mIndices = gl::Buffer("scene indices", indices.size() * sizeof(uint32_t), indices.data(), 0);
  mObjects = gl::Buffer("scene objects", objects.size() * sizeof(gpu::ObjectGpu), objects.data(), GL_DYNAMIC_STORAGE_BIT);
  const GLuint vao = mVao.id();
  glVertexArrayVertexBuffer(vao, 0, mVertices.id(), 0, sizeof(Vertex));
  glVertexArrayElementBuffer(vao, mIndices.id());
  glEnableVertexArrayAttrib(vao, 0);
  glEnableVertexArrayAttrib(vao, 1);
  glEnableVertexArrayAttrib(vao, 2);
  glVertexArrayAttribFormat(vao, 0, 3, GL_FLOAT, GL_FALSE, offsetof(Vertex, position));
  glVertexArrayAttribFormat(vao, 1, 3, GL_FLOAT, GL_FALSE, offsetof(Vertex, normal));
  glVertexArrayAttribFormat(vao, 2, 2, GL_FLOAT, GL_FALSE, offsetof(Vertex, uv));
  for (GLuint a = 0; a < 3; ++a) glVertexArrayAttribBinding(vao, a, 0);
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

void GpuScene::draw(GLuint program) const {
  glBindVertexArray(mVao.id());
  mObjects.bindBase(GL_SHADER_STORAGE_BUFFER, PN_SSBO_OBJECTS);
  for (size_t i = 0; i < mDraws.size(); ++i) {
    const Draw& d = mDraws[i];
    glProgramUniform1i(program, PN_LOC_OBJECT, static_cast<GLint>(i));
    glBindTextureUnit(PN_TEX_BASECOLOR, d.texture);
    glDrawElementsBaseVertex(GL_TRIANGLES, d.indexCount, GL_UNSIGNED_INT,
                             reinterpret_cast<const void*>(d.firstIndex * sizeof(uint32_t)), d.baseVertex);
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
    CasterMesh m;
    m.vertexBuffer = mVertices.id();
    m.stride = sizeof(Vertex);
    m.positionOffset = offsetof(Vertex, position);
    m.uvOffset = offsetof(Vertex, uv);
    m.indexBuffer = mIndices.id();
    m.firstIndex = static_cast<uint32_t>(d.firstIndex);
    m.count = static_cast<uint32_t>(d.indexCount);
    m.baseVertex = d.baseVertex;
    m.worldFromObject = o.worldFromObject;
    m.objectBounds = scene.meshes[o.mesh].bounds();
    m.dynamic = moving[i] || o.dynamic;  // animated or declared dynamic (cached maps keep the rest)
    if (mat.alphaMask && mat.baseColorTexture >= 0) {
      m.alphaTexture = d.texture;
      m.alphaCutoff = mat.alphaCutoff;
    }
    out.push_back(m);
  }
  return out;
}

}  // namespace penumbra
