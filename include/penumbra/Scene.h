#pragma once
// The scene: meshes, materials, object instances, lights and a camera. Pure data, no GL.
// Conventions (docs/design.md): right-handed world, metres, +Y up.
#include <penumbra/Animation.h>
#include <penumbra/MapUpdates.h>
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

/// Largest angular radius of a sun (rad): beyond it the cone of directions is no longer a
/// "distant light" and the reference's cone sampling degenerates.
inline constexpr float kMaxSunAngularRadiusRad = 0.5f;

/// Largest light colour component and ambient radiance (linear RGB), for scene files and glTF
/// alike: colour × intensity × the BRDF then stays far inside float range (a colour of 1e38
/// overflowed to a black image).
inline constexpr float kMaxRadiance = 1e6f;

/// A sun (a direction), a spot (a sphere shining into a cone) or a point light (a sphere shining
/// everywhere).
enum class LightType { Directional, Spot, Point };

/// What a scene file may set per light, over the scene's technique (docs/scenes.md).
struct LightShadowSettings {
  int mapSize = 0;  ///< texels per side of this light's maps; 0 = the technique's (--shadow-map)
  /// "key" → "value" of technique parameters, for this light only: those of the projection and
  /// filter in use apply (Shadows), another registered technique's wait until it runs (a scene
  /// written for several techniques); a key of none is an error.
  std::vector<std::pair<std::string, std::string>> params;
  /// When this light's maps are drawn again; none = Shadows::setMapUpdates' policy. A light's own
  /// budget updates that many of its own maps a frame; the lights that follow Shadows' budget
  /// share it.
  std::optional<MapUpdates> updates;
};

/// Largest spot cone half angle (rad): a cone near a hemisphere has no useful single frustum
/// (a point light shadows every direction instead).
inline constexpr float kMaxSpotConeRad = 1.4f;
/// A spot's narrowest outer half angle (degrees), as scene files and the viewer accept it.
inline constexpr float kMinSpotConeDeg = 1.0f;
/// A spot given only its outer angle fades over the cone's last degrees (the look of earlier
/// scene files): inner = outer − this.
inline constexpr float kDefaultSpotFadeDeg = 5.0f;
/// A spot or point light's largest sphere radius (m).
inline constexpr float kMaxLightSphereM = 100.0f;
/// Largest light intensity (Light::intensity), for scene files and the viewer alike.
inline constexpr float kMaxLightIntensity = 1e6f;
/// Shadow-map sizes (texels per side) that scene files and the viewer accept, for the scene's
/// technique and for a light's own (LightShadowSettings::mapSize).
inline constexpr int kMinMapSizeTexels = 16, kMaxMapSizeTexels = 16384;

struct Light {
  LightType type = LightType::Directional;
  glm::vec3 position{0.0f, 10.0f, 0.0f};   ///< spot and point, metres
  glm::vec3 direction{0.0f, -1.0f, 0.0f};  ///< unit, from the light toward the scene (sun, spot)
  glm::vec3 color{1.0f};                   ///< linear RGB, each in [0, kMaxRadiance]
  float intensity = 3.0f;                  ///< irradiance scale (sun) or intensity at 1 m (spot, point)
  /// Spot: the cone's outer half angle (no light beyond it), (0, kMaxSpotConeRad] …
  float coneAngleRad = 0.6f;
  /// … and its inner half angle (full light within it), [0, coneAngleRad]; between the two the
  /// light falls off smoothly (smoothstep of the cosine).
  float innerConeAngleRad = 0.5f;
  /// Spot and point: no light and no shadow beyond this distance (m), where the light has faded
  /// smoothly to 0 (glTF's KHR_lights_punctual window); 0 = unlimited (inverse square only).
  float rangeM = 0.0f;
  /// Physical size for soft shadows: spot and point = sphere radius in metres, sun = angular
  /// radius in radians. 0 = a point/delta light (hard shadows).
  float size = 0.0f;
  bool castsShadow = true;     ///< false: the light shines but casts no shadow (V = 1)
  LightShadowSettings shadow;  ///< per-light overrides of the scene's technique
};

/// The light type's name in scene files: "sun", "spot" or "point".
const char* lightTypeName(LightType type);

/// The light kind's bit of ParamDesc::lights (kSunLightBit, kSpotLightBit, kPointLightBit).
unsigned lightKindBit(LightType type);

/// Spot and point lights have a position (their light comes from a sphere there).
inline bool isPositional(const Light& l) { return l.type != LightType::Directional; }

/// The light's unshadowed strength toward a receiver at `ws` relative to its value without
/// falloff: the spot's cone falloff times the range window, in [0, 1] (1 for a sun).
float lightFalloff(const Light& light, const glm::vec3& ws);

/// Most lights a scene holds: each one gets its own shadow maps and visibility layer
/// (penumbra/Shadows.h: kMaxShadowedLights is this limit). Scene files and models with more are
/// refused by name.
inline constexpr size_t kMaxLights = 16;

/// Every world-space coordinate (vertices, the camera's position and target) stays within ±1e6 m
/// (as the scene file's shape sizes): beyond that the float maths of the shadow passes stops
/// meaning anything.
inline constexpr float kMaxCoordinateM = 1e6f;

struct Camera {
  glm::vec3 position{0.0f, 2.0f, 6.0f};
  glm::vec3 target{0.0f};
  glm::vec3 up{0.0f, 1.0f, 0.0f};
  float fovYRad = 0.8f;   ///< vertical field of view
  float nearM = 0.05f;
  float farM = 200.0f;

  /// "" when the camera defines a view; otherwise what is wrong: the target on the position, an
  /// up vector that is zero, not finite or along the view direction (a camera looking straight
  /// down with the default up renders nothing meaningful). Scene files, --camera and
  /// Scene::validate() check it.
  std::string viewProblem() const;
  glm::mat4 viewFromWorld() const;
  /// Reversed-Z, [0,1] clip depth (glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE)): near → 1, far → 0.
  glm::mat4 clipFromView(float aspect) const;
  glm::vec3 forward() const { return glm::normalize(target - position); }
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
