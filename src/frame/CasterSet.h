#pragma once
// The shadow casters on the GPU as the shadow passes draw them: CasterMesh records (buffers the
// caller owns, penumbra/Casters.h) with one vertex array per buffer layout and the object table
// (ObjectGpu[] at PN_SSBO_OBJECTS) the shared vertex stage reads. Penumbra's own renderer hands
// its scene over in the same form (render/GpuScene.h), so there is one caster path.
#include "gl/Objects.h"

#include <penumbra/Casters.h>
#include <penumbra/Scene.h>

#include <span>
#include <vector>

namespace penumbra {

/// The casting objects of `scene` (Object::castsShadow), in order, as CasterGeometry over the
/// scene's own vertex and index vectors (valid while the scene is unchanged).
std::vector<CasterGeometry> casterGeometry(const Scene& scene);

/// Throws a usage Error naming caster geometry `i` when its records do not hold whole triangles
/// of positions within its vertices (a stride below 12 bytes, an index beyond the vertices, …).
void checkCasterGeometry(const CasterGeometry& geometry, size_t i);

class CasterSet {
public:
  /// Replaces the casters. Checks each record against the GL objects it names (buffers exist and
  /// hold the ranges drawn, textures exist) and throws a usage penumbra::Error naming the first
  /// bad one. Vertex arrays are kept across calls for layouts seen before.
  void set(std::span<const CasterMesh> casters);
  /// Draws the opaque casters with `opaqueProgram`, then the alpha-tested ones with
  /// `maskedProgram` (their texture at PN_TEX_BASECOLOR); PN_LOC_OBJECT set per draw (the
  /// object table's baseColor.rgb holds a translucent caster's transmittance, 1 for the
  /// others). Leaves the last program and vertex array bound.
  /// `which`: every caster, or only the static or only the dynamic ones (CasterMesh::dynamic).
  enum class Which { All, Static, Dynamic };
  /// Translucent casters (CasterMesh::transmittance): drawn like the others (as opaque, the
  /// default), left out (a map of the opaque casters alone) or drawn alone.
  enum class Translucent { AsOpaque, Skip, Only };
  /// `only`: when not empty, one entry per caster (in order); casters whose entry is 0 are skipped
  /// (a paged map's page draws the casters over it alone).
  void draw(GLuint opaqueProgram, GLuint maskedProgram, Which which = Which::All, Translucent translucent = Translucent::AsOpaque,
            std::span<const uint8_t> only = {}) const;
  /// Whether any caster is translucent.
  bool hasTranslucent() const { return mTranslucent; }
  /// A hash of the static casters (their records and placements, in order): it changes when one
  /// is added, removed, moved or altered. For cached maps.
  uint64_t staticKey() const { return mStaticKey; }
  /// The world bounds of each caster of `which`, in order (for SceneExtent).
  std::vector<SceneExtent::Body> bodies(Which which = Which::All) const;
  size_t size() const { return mDraws.size(); }
  /// Caster i (in order) as a paged map tracks it: its world bounds, whether it is dynamic and a
  /// hash of its record and placement (changes when it moves or changes).
  struct Placement {
    Aabb bounds;
    bool dynamic = false;
    uint64_t key = 0;
  };
  std::vector<Placement> placements() const;

private:
  struct Layout {
    GLuint vertexBuffer = 0, indexBuffer = 0;
    uint32_t stride = 0, positionOffset = 0, uvOffset = 0;
    bool operator==(const Layout&) const = default;
  };
  struct Draw {
    size_t vao;  ///< index into mVaos
    CasterMesh mesh;
  };
  size_t vaoFor(const Layout& layout);

  std::vector<Layout> mLayouts;
  std::vector<gl::VertexArray> mVaos;  ///< one per mLayouts entry
  std::vector<Draw> mDraws;
  gl::Buffer mObjects;
  uint64_t mStaticKey = 0;
  bool mTranslucent = false;
};

}  // namespace penumbra
