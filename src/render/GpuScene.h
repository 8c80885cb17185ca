#pragma once
// The scene's geometry on the GPU: one vertex buffer, one index buffer, one object table
// (ObjectGpu[] in a storage buffer). Uploaded once per scene.
#include "gl/Objects.h"

#include <penumbra/Scene.h>

#include <vector>

namespace penumbra {

class GpuScene {
public:
  explicit GpuScene(const Scene& scene);
  /// Draws objects with the bound program; `castersOnly` skips objects that cast no shadow.
  void draw(GLuint program, bool castersOnly) const;

private:
  struct Draw {
    GLsizei indexCount;
    size_t firstIndex;
    GLint baseVertex;
    bool castsShadow;
  };
  gl::Buffer mVertices, mIndices, mObjects;
  gl::VertexArray mVao;
  std::vector<Draw> mDraws;
};

}  // namespace penumbra
