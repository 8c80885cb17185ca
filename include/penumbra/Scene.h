#pragma once
// The scene: meshes, materials, object instances, lights and a camera. Pure data, no GL.
// Conventions (docs/design.md): right-handed world, metres, +Y up.
#include <penumbra/Animation.h>
#include <penumbra/Camera.h>
#include <penumbra/Light.h>
#include <penumbra/Math.h>
#include <penumbra/Params.h>

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace penumbra {

/// An indexed triangle list in object space. Vertices are shared: each attribute array holds one
/// entry per unique vertex (a grid point is one vertex for the six triangles around it), and
/// `indices` names three of them per triangle. A mesh carries only the attributes it uses: the
/// renderer uploads what is present, nothing else.
struct Mesh {
  std::string name;
  std::vector<glm::vec3> positions;
  /// Unit shading normals, one per position; empty = flat: every triangle is shaded by its own
  /// plane (a model without normals, as OBJ and glTF define it), with no vertex split for it.
  std::vector<glm::vec3> normals;
  /// Texture coordinates, one per position (uv (0,0) = an image's first stored row); empty = none
  /// (a mesh whose materials have no texture needs none).
  std::vector<glm::vec2> uvs;
  std::vector<uint32_t> indices;  ///< three per triangle
  size_t vertexCount() const { return positions.size(); }
  size_t triangleCount() const { return indices.size() / 3; }
  /// Appends one vertex with every attribute (procedural shapes).
  uint32_t addVertex(const glm::vec3& position, const glm::vec3& normal, const glm::vec2& uv);
  /// Bytes its arrays hold (the name aside).
  size_t byteSize() const;
  Aabb bounds() const;
  /// True when at least one triangle has a non-zero area (a mesh of degenerate triangles, whose
  /// corners lie on one line, draws no pixel and casts no shadow).
  bool hasArea() const;
};

/// RGBA8 texture in memory (row 0 = top), used for base colour and alpha masks.
struct Image {
  int width = 0, height = 0;
  std::vector<uint8_t> rgba;
};

struct Material {
  std::string name;
  glm::vec3 baseColor{0.8f};   ///< linear RGB albedo, each in [0, 1]
  float roughness = 0.5f;      ///< [0, 1]; drives the Blinn-Phong exponent
  int baseColorTexture = -1;   ///< index into Scene::images, -1 = none
  bool alphaMask = false;      ///< alpha-tested: texels with alpha < alphaCutoff are holes
  float alphaCutoff = 0.5f;
  /// The share of light, per colour, that passes through the surface (linear RGB, each in
  /// [0, 1]): (0, 0, 0) = opaque, the default; (0.9, 0.3, 0.2) a red glass. A translucent caster
  /// tints and dims the light behind it instead of stopping it (docs/scenes.md, "Translucent
  /// casters"); the surface itself is drawn and receives shadows like any other.
  glm::vec3 transmittance{0.0f};
  bool translucent() const { return transmittance != glm::vec3(0.0f); }
};

/// One placed mesh.
struct Object {
  std::string name;
  uint32_t mesh = 0;
  uint32_t material = 0;
  glm::mat4 worldFromObject{1.0f};
  bool castsShadow = true;
  /// Declared a dynamic caster though it does not move (cached shadow maps draw it every frame
  /// instead of keeping it in a map's static layer: a caster the application moves itself).
  /// Animated objects are dynamic whatever this says (SceneAnimation::movingObjects).
  bool dynamic = false;
};

/// The shadow technique a scene asks for; CLI options override it.
struct ShadowSettings {
  std::string projection = "uniform";
  std::string filter = "hard";
  int mapSize = 2048;  ///< shadow-map resolution (texels per side)
  /// "key" → "value" as written (numbers or choice names); applied by the parameter system.
  std::vector<std::pair<std::string, std::string>> params;
};

/// What the projections need of a scene: each object's world bounds and whether it casts. An
/// engine fills it from its own meshes (Penumbra never needs their vertices for it).
struct SceneExtent {
  struct Body {
    Aabb bounds;  ///< world space (m)
    bool castsShadow = true;
  };
  std::vector<Body> bodies;
  Aabb bounds() const;        ///< of every body
  Aabb casterBounds() const;  ///< of the bodies that cast shadows
};

struct Scene {
  std::string name;
  std::filesystem::path sourceFile;  ///< empty for built-in scenes
  std::vector<Mesh> meshes;
  std::vector<Material> materials;
  std::vector<Image> images;
  std::vector<Object> objects;
  std::vector<Light> lights;
  Camera camera;
  ShadowSettings shadow;
  glm::vec3 ambient{0.08f};  ///< constant ambient radiance (linear RGB), each in [0, kMaxRadiance]
  /// Keyframes over time (penumbra/Animation.h); the members above are the pose at time 0 (or at
  /// the time poseScene last set).
  SceneAnimation animation;

  const Light& light() const;  ///< the shadow-casting light (the first one); throws if none
  Aabb bounds() const;         ///< world bounds of every object
  Aabb casterBounds() const;   ///< world bounds of shadow casters
  SceneExtent extent() const;  ///< every object's world bounds (one pass over the vertices)
  size_t triangleCount() const;
  /// Throws penumbra::Error if indices are out of range, positions not finite, no triangle has
  /// an area, the camera defines no view, etc.
  void validate() const;
};

// Procedural shapes (object space, outward normals, counter-clockwise front faces).
Mesh makePlane(float sizeX, float sizeZ);                   ///< XZ plane through the origin, normal +Y
/// makePlane cut into cells × cells quads that share their vertices (edges between triangles of
/// one surface, as a tessellated terrain has them); cells ≥ 1.
Mesh makeGrid(float sizeX, float sizeZ, int cells);
Mesh makeBox(const glm::vec3& size);                         ///< centred at the origin
Mesh makeSphere(float radius, int slices = 32, int stacks = 16);
Mesh makeCylinder(float radius, float height, int slices = 24);  ///< axis +Y, base at y = 0
Mesh makeCone(float radius, float height, int slices = 24);      ///< axis +Y, base at y = 0

/// Adds a mesh + material + object in one call; returns the object's index.
uint32_t addObject(Scene& scene, std::string name, Mesh mesh, const glm::vec3& color,
                   const glm::mat4& worldFromObject = glm::mat4(1.0f), bool castsShadow = true);

}  // namespace penumbra
