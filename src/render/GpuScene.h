#pragma once
// The scene's geometry on the GPU: one vertex buffer, one index buffer, one object table
// (ObjectGpu[] in a storage buffer), and one texture per material image (sRGB RGBA8), bound at
// PN_TEX_BASECOLOR for each draw (bindless-free: images of any size, no array layers to share).
// Uploaded once per scene.
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
    GLuint texture;  ///< the material's base-colour texture, or mWhite
  };
  gl::Buffer mVertices, mIndices, mObjects;
  std::vector<gl::Texture> mTextures;  ///< by Scene::images index; empty where no material uses it
  gl::Texture mWhite;                  ///< 1×1 opaque white for untextured objects
  gl::VertexArray mVao;
  std::vector<Draw> mDraws;
};

}  // namespace penumbra
