#include "render/GpuScene.h"

#include "shared/Bindings.h"
#include "shared/Frame.h"

#include <glm/gtc/matrix_inverse.hpp>

namespace penumbra {

GpuScene::GpuScene(const Scene& scene) : mVao("scene vao") {
  std::vector<Vertex> vertices;
  std::vector<uint32_t> indices;
  std::vector<std::pair<size_t, size_t>> meshRanges;  // first vertex, first index
  for (const Mesh& m : scene.meshes) {
    meshRanges.emplace_back(vertices.size(), indices.size());
    vertices.insert(vertices.end(), m.vertices.begin(), m.vertices.end());
    indices.insert(indices.end(), m.indices.begin(), m.indices.end());
  }
  std::vector<gpu::ObjectGpu> objects;
  for (const Object& o : scene.objects) {
    const Mesh& m = scene.meshes[o.mesh];
    const Material& mat = scene.materials[o.material];
    mDraws.push_back({static_cast<GLsizei>(m.indices.size()), meshRanges[o.mesh].second,
                      static_cast<GLint>(meshRanges[o.mesh].first), o.castsShadow});
    gpu::ObjectGpu g{};
    g.worldFromObject = o.worldFromObject;
    g.normalFromObject = glm::mat4(glm::inverseTranspose(glm::mat3(o.worldFromObject)));
    g.baseColor = glm::vec4(mat.baseColor, mat.alphaMask ? mat.alphaCutoff : 0.0f);
    g.material = glm::ivec4(mat.baseColorTexture, mat.alphaMask ? 1 : 0, 0, 0);
    objects.push_back(g);
  }
  mVertices = gl::Buffer("scene vertices", vertices.size() * sizeof(Vertex), vertices.data(), 0);
  mIndices = gl::Buffer("scene indices", indices.size() * sizeof(uint32_t), indices.data(), 0);
  mObjects = gl::Buffer("scene objects", objects.size() * sizeof(gpu::ObjectGpu), objects.data(), 0);
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

void GpuScene::draw(GLuint program, bool castersOnly) const {
  glBindVertexArray(mVao.id());
  mObjects.bindBase(GL_SHADER_STORAGE_BUFFER, PN_SSBO_OBJECTS);
  for (size_t i = 0; i < mDraws.size(); ++i) {
    const Draw& d = mDraws[i];
    if (castersOnly && !d.castsShadow) continue;
    glProgramUniform1i(program, PN_LOC_OBJECT, static_cast<GLint>(i));
    glDrawElementsBaseVertex(GL_TRIANGLES, d.indexCount, GL_UNSIGNED_INT,
                             reinterpret_cast<const void*>(d.firstIndex * sizeof(uint32_t)), d.baseVertex);
  }
  glBindVertexArray(0);
}

}  // namespace penumbra
