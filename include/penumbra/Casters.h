#pragma once
// Shadow casters as an engine has them: meshes in GL buffers it owns. Penumbra draws them into
// its shadow maps with its own programs, reading the buffers in place (it never copies or frees
// them); the caller keeps them alive and unchanged while Penumbra renders. Filters that bake the
// casters on the CPU (sdf) read the same meshes from the engine's memory (CasterGeometry).
#include <penumbra/Math.h>

#include <cstddef>
#include <cstdint>
#include <span>

namespace penumbra {

/// A vertex attribute offset that means "this mesh has no such attribute".
inline constexpr uint32_t kNoAttribute = 0xffffffffu;

/// How a caster's indices are stored: unsigned, 32 or 16 bits each (GL_UNSIGNED_INT,
/// GL_UNSIGNED_SHORT).
enum class IndexType : uint32_t { UInt32, UInt16 };

/// Bytes of one index of `type`.
constexpr uint32_t indexBytes(IndexType type) { return type == IndexType::UInt16 ? 2u : 4u; }

/// One placed mesh that casts shadows. Names are OpenGL object names (GLuint).
struct CasterMesh {
  uint32_t vertexBuffer = 0;    ///< GL buffer holding the vertices
  uint32_t stride = 12;         ///< bytes from one vertex to the next
  uint32_t positionOffset = 0;  ///< bytes to the position: 3 floats, object space (m)
  /// Bytes to the texture coordinate (2 floats) used by the alpha mask; kNoAttribute = none.
  uint32_t uvOffset = kNoAttribute;
  /// GL buffer of unsigned indices (`indexType`), three per triangle; 0 = draw `count` vertices
  /// in order.
  uint32_t indexBuffer = 0;
  IndexType indexType = IndexType::UInt32;
  uint32_t firstIndex = 0;      ///< first index (or first vertex, without an index buffer)
  uint32_t count = 0;           ///< indices (or vertices), a multiple of 3
  int32_t baseVertex = 0;       ///< added to every index
  glm::mat4 worldFromObject{1.0f};
  /// Object-space bounds of the vertices drawn: the light's views are fitted to them (an empty
  /// box makes the mesh invisible to the fitting, not to the shadow maps).
  Aabb objectBounds;
  /// Alpha-tested caster: a GL 2D texture whose alpha below `alphaCutoff` is a hole (read at the
  /// nearest texel of `uvOffset`'s coordinate, repeat wrapping). 0 = opaque.
  uint32_t alphaTexture = 0;
  float alphaCutoff = 0.5f;
  /// With cached maps (Shadows::setMapUpdates): a dynamic caster is drawn every frame over the
  /// cached static casters and left out of the light views' fit; a static one (false) is drawn
  /// into a map once and kept while the map's view and every static caster stay as they were (a
  /// static caster that moves invalidates the maps it was in). Without caching it changes nothing.
  bool dynamic = false;
  /// Light let through, per colour channel (linear RGB in [0, 1]): (0, 0, 0) = opaque, the
  /// default; (0.85, 0.45, 0.3) an amber pane. Each surface crossed multiplies the light by it.
  /// Techniques that only know opaque casters draw a translucent one as opaque; with the
  /// translucent add-on ("translucent.*", docs/translucent.md) its shadow is tinted instead.
  glm::vec3 transmittance{0.0f};
  bool translucent() const { return transmittance != glm::vec3(0.0f); }
};

/// One caster's triangles in the engine's memory, for filters that bake the casters on the CPU
/// (sdf: Shadows::setCasterGeometry). The same layout as a CasterMesh, over bytes instead of GL
/// buffers; read in place (never copied or kept), during the render() calls that bake.
struct CasterGeometry {
  std::span<const std::byte> vertices;  ///< vertex records, `stride` bytes apart
  uint32_t stride = 12;                 ///< bytes from one vertex to the next
  uint32_t positionOffset = 0;          ///< bytes to the position: 3 floats, object space (m)
  /// Indices (`indexType` each), three per triangle; empty = the vertices in order, three per
  /// triangle.
  std::span<const std::byte> indices;
  IndexType indexType = IndexType::UInt32;
  glm::mat4 worldFromObject{1.0f};

  size_t vertexCount() const { return stride ? vertices.size() / stride : 0; }
  /// Triangle t's corner c (0..2) in object space.
  glm::vec3 corner(size_t t, int c) const;
  size_t triangleCount() const { return (indices.empty() ? vertexCount() : indices.size() / indexBytes(indexType)) / 3; }
};

}  // namespace penumbra
