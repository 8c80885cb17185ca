#pragma once
// Penumbra's own renderer's scene on the GPU: the meshes' shared vertices in one interleaved
// buffer per vertex layout (position; + normal; + uv; + both: a mesh uploads only the attributes
// it has and its materials read, so a flat, untextured mesh costs 12 bytes a vertex), one index
// buffer, one object table (ObjectGpu[] in a storage buffer), and one texture per material image
// (sRGB RGBA8), bound at PN_TEX_BASECOLOR for each draw (bindless-free: images of any size, no
// array layers to share). Uploaded once per scene, mesh by mesh (no CPU copy of the whole scene
// is made on the way). The G-buffer pass draws it; the shadow passes get the same buffers as
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
  /// Draws every object with the bound program (the G-buffer pass). With `firstTriangleLocation`
  /// (a uint uniform of the program, or -1) the program learns each draw's first triangle in its
  /// mesh, as a mesh drawn in pieces (gl/Draw.h) needs for triangle ids.
  void draw(GLuint program, GLint firstTriangleLocation = -1) const;
  /// The objects that cast shadows, as records over these buffers (alpha-masked materials with
  /// their texture), for Shadows::setCasters.
  std::vector<CasterMesh> casterMeshes(const Scene& scene) const;

private:
  /// One vertex layout: its attributes, interleaved in one buffer, position first.
  struct Layout {
    bool normal = false, uv = false;
    uint32_t stride() const { return 12u + (normal ? 12u : 0u) + (uv ? 8u : 0u); }
    uint32_t uvOffset() const { return 12u + (normal ? 12u : 0u); }
    gl::Buffer vertices;
    gl::VertexArray vao;
  };
  static constexpr size_t kLayouts = 4;  ///< index = (normal ? 1 : 0) + (uv ? 2 : 0)
  struct Draw {
    GLsizei indexCount;
    size_t firstIndex;
    GLint baseVertex;  ///< in its layout's buffer
    size_t layout;
    bool castsShadow;
    GLuint texture;  ///< the material's base-colour texture, or mWhite
  };
  Layout mLayouts[kLayouts];
  gl::Buffer mIndices, mObjects;
  std::vector<gpu::ObjectGpu> mObjectData;  ///< what mObjects holds
  std::vector<gl::Texture> mTextures;  ///< by Scene::images index; empty where no material uses it
  gl::Texture mWhite;                  ///< 1×1 opaque white for untextured objects
  std::vector<Draw> mDraws;
};

}  // namespace penumbra
