#pragma once
// A light as the scene, the engine and the ray-traced reference describe it: a sun, a spot or a
// point light with its size, cone and range, and its own shadow settings over the technique.
// Conventions (docs/design.md): metres, radians, linear RGB.
#include <penumbra/MapUpdates.h>
#include <penumbra/Math.h>

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace penumbra {

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

/// A light's own settings over the technique every light uses (Shadows::setTechnique; a scene
/// file's per-light "shadow" object, docs/scenes.md): merged into the light's technique when its
/// state is made, so the light gets its own maps of its own kind and size.
struct LightShadowSettings {
  /// Ids of this light's own projection and filter (Technique.h lists them); empty = the
  /// technique's. A cascaded sun beside point lights: the lights set projection = "uniform" (a
  /// point light's maps are the six faces of a cube, which only "uniform" makes).
  std::string projection, filter;
  int mapSize = 0;  ///< texels per side of this light's maps; 0 = the technique's (Technique::mapSize)
  /// "key" → "value" of parameters, for this light only: its projection's, its filter's and the
  /// add-ons'. A key of another technique (a "csm." key on a light that runs "uniform") is kept
  /// for when that technique runs, not an error; a key of none is refused.
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
  /// The engine's name for this light, the same from frame to frame: Penumbra keeps each light's
  /// maps, map-update schedule, budget share and accumulated V under it, so lights can be
  /// reordered, added or removed between frames. Unique among a frame's lights; 0 = none (the
  /// light is then known by its position in the frame's list).
  uint64_t id = 0;
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

}  // namespace penumbra
