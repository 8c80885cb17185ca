#pragma once
// Penumbra's own renderer's scene on the GPU: one vertex buffer, one index buffer, one object
// table (ObjectGpu[] in a storage buffer), and one texture per material image (sRGB RGBA8), bound
// at PN_TEX_BASECOLOR for each draw (bindless-free: images of any size, no array layers to share).
// Uploaded once per scene. The G-buffer pass draws it; the shadow passes get the same buffers as
// CasterMesh records (casterMeshes), as an engine would give its own.
#include "gl/Objects.h"
#include "shared/Frame.h"

#include <penumbra/Casters.h>
#include <penumbra/Scene.h>

#include <vector>

namespace penumbra {

class GpuScene {
public:
  explicit GpuScene(const Scene& scene);
  /// Re-uploads the objects' transforms from `scene` (the scene this was made from, posed at
  /// another time: the same objects, meshes and materials).
  void setTransforms(const Scene& scene);
  /// Draws every object with the bound program (the G-buffer pass).
  void draw(GLuint program) const;
  /// The objects that cast shadows, as records over these buffers (alpha-masked materials with
  /// their texture), for Shadows::setCasters.
  std::vector<CasterMesh> casterMeshes(const Scene& scene) const;

private:
  struct Draw {
    GLsizei indexCount;
    size_t firstIndex;
    GLint baseVertex;
    bool castsShadow;
    GLuint texture;  ///< the material's base-colour texture, or mWhite
  };
  gl::Buffer mVertices, mIndices, mObjects;
  std::vector<gpu::ObjectGpu> mObjectData;  ///< what mObjects holds
  std::vector<gl::Texture> mTextures;  ///< by Scene::images index; empty where no material uses it
  gl::Texture mWhite;                  ///< 1×1 opaque white for untextured objects
  gl::VertexArray mVao;
  std::vector<Draw> mDraws;
};

}  // namespace penumbra
