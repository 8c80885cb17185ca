#pragma once
// Penumbra inside an engine (docs/embedding.md): a shadow technique run on the caller's OpenGL
// 4.5 context. The engine gives its camera, its depth and normal textures, its lights and its
// casters (meshes in its own buffers); Penumbra renders each light's shadow maps, prefilters them
// and writes one visibility layer per light (R32F, 1 = lit) that the engine samples in its own
// lighting.
// Penumbra creates no context, and restores the GL state it changes (RestoreState below).
//
//   penumbra::Shadows shadows;                        // a GL 4.5 context is current
//   shadows.setTechnique("csm", "pcss", {{"pcss.blockerSamples", "16"}});
//   shadows.setCasters(casters);                      // CasterMesh: the engine's buffers
//   shadows.render({.camera = penumbra::ShadowCamera::fromMatrices(view, proj, penumbra::DepthConvention::ZeroToOne),
//                   .surfaces = {.width = w, .height = h, .depth = depthTex, .normal = normalTex},
//                   .lights = lights});
//   glBindTextureUnit(7, shadows.visibilityTexture());  // V of the first light, 1 = lit
#include <penumbra/Casters.h>
#include <penumbra/Filter.h>
#include <penumbra/Image.h>
#include <penumbra/MapUpdates.h>
#include <penumbra/Projection.h>
#include <penumbra/Scene.h>
#include <penumbra/Timings.h>

#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace penumbra {

class ShaderLibrary;  // src/shader/ShaderLibrary.h

/// How the engine's depth texture stores depth: the glClipControl depth mode it rendered with.
enum class DepthConvention {
  NegativeOneToOne,  ///< GL's default: stored depth = ndc.z · 0.5 + 0.5
  ZeroToOne,         ///< glClipControl(…, GL_ZERO_TO_ONE): stored depth = ndc.z (reversed-Z too)
};

/// The camera of this frame, as the engine rendered it.
struct ShadowCamera {
  glm::mat4 viewFromWorld{1.0f};
  glm::mat4 clipFromView{1.0f};  ///< a perspective projection (symmetric frustum)
  DepthConvention depth = DepthConvention::ZeroToOne;
  /// The same camera as position, direction, field of view, near and far, and its aspect
  /// (width / height): what the light's views are fitted to (cascade splits, warps). Made by
  /// the two constructors below.
  Camera fit;
  float aspect = 1.0f;

  /// From the engine's matrices. The fitted camera is recovered from them (an infinite far plane
  /// becomes a far one that every projection clips to the scene's bounds). Throws a usage
  /// penumbra::Error if clipFromView is not a perspective projection.
  static ShadowCamera fromMatrices(const glm::mat4& viewFromWorld, const glm::mat4& clipFromView,
                                   DepthConvention depth);
  /// From Penumbra's own camera description (reversed-Z, zero to one: Camera::clipFromView).
  static ShadowCamera fromCamera(const Camera& camera, float aspect);
};

/// The surfaces to shadow, one texel per pixel: GL texture names the engine owns (2D textures,
/// width × height each). Their sampling state does not matter (Penumbra reads them with its own
/// sampler objects); depth textures may have compare mode on.
struct ShadowSurfaces {
  int width = 0, height = 0;
  /// Depth as rendered with the camera (any depth or single-channel float format). Pixels that
  /// hold the clear value of the far plane are background (V = 1).
  uint32_t depth = 0;
  /// World-space normals in xyz (any float, half or snorm format), facing the camera: the
  /// surface's geometric normal if the engine has one, its shading normal otherwise (biases are
  /// measured along it).
  uint32_t normal = 0;
  /// Optional: world positions (xyz m; w > 0.5 where there is geometry) read instead of
  /// reconstructing them from `depth`; Penumbra's own G-buffer has them. 0 = from depth.
  uint32_t position = 0;
};

/// A world point at which to evaluate a filter's visibility (Shadows::visibilityAt).
struct SurfaceSample {
  glm::vec3 position{0.0f};               ///< world (m)
  glm::vec3 geoNormal{0.0f, 1.0f, 0.0f};  ///< unit geometric normal (decides N·L and biases)
  glm::ivec2 pixel{0};                    ///< the pixel it was seen at (filters' per-pixel noise)
};

/// What render() changes in the GL state and puts back.
enum class RestoreState {
  /// Every binding and switch Penumbra touches is read before and written back after: the
  /// framebuffer and viewport, program, vertex array, depth test, function, mask and clamp, face
  /// culling, texture units 0–15 (2D, 2D array, 3D targets) and their samplers, image units 0–3,
  /// uniform buffers 0–2 and storage buffers 0–5 (indexed bindings), the active texture unit.
  /// About 150 glGet calls a frame.
  All,
  /// Nothing is read back: after render() those bindings and switches hold whatever Penumbra
  /// left (for engines that set their own state before every pass).
  None,
};

/// Most lights one Shadows object shadows in a frame.
inline constexpr size_t kMaxShadowedLights = kMaxLights;

struct ShadowFrameInputs {
  ShadowCamera camera;
  ShadowSurfaces surfaces;
  /// The lights, 1..kMaxShadowedLights, each with its own maps and visibility layer (in this
  /// order). Light::castsShadow false: its layer is 1 everywhere it is not behind itself. A
  /// light's `shadow` settings override the map size and the technique's parameters for it.
  std::span<const Light> lights;
  int mapSize = 2048;  ///< texels per side of each shadow map (a light's own mapSize wins), 1..GL_MAX_TEXTURE_SIZE
  /// Texels that every light's maps together may hold (0 = no budget): each light then gets a
  /// share by its importance on screen, never more than it asks for (lightReports() says what).
  int64_t mapBudgetTexels = 0;
  RestoreState restore = RestoreState::All;
  /// With temporal accumulation on (addOns(), docs/temporal.md): this frame does not continue the
  /// last one (a camera cut, a teleport), so no V of earlier frames is reused. Penumbra keeps the
  /// previous frame's camera and surfaces itself; the history is also dropped when the surfaces'
  /// size, the light count or the technique or its parameters change.
  bool cameraCut = false;
};

/// What one light got in the last frame.
struct LightShadowReport {
  int requestedMapSize = 0;  ///< the light's own mapSize, or the frame's
  int mapSize = 0;           ///< what the budget gave it (= requested without a budget)
  int views = 0;             ///< maps: 1, a cascade each, 6 for a point light's cube
  double importance = 0.0;   ///< its share of the screen, in (0, 1] (the budget's weight)
  MapUpdates updates;        ///< the policy its maps followed (its own, or Shadows')
  int keptMaps = 0;          ///< MapUpdates::Budget: its maps left as an earlier frame drew them
  int staleness = 0;         ///< the oldest of its maps (frames since drawn; 0 = all drawn this frame)
  int64_t texels() const { return static_cast<int64_t>(views) * mapSize * mapSize; }
};

/// Runs one technique (projection × filter) on the caller's context. Not thread-safe; every call
/// needs the same GL 4.5 context current as at construction.
class Shadows {
public:
  /// Needs a current OpenGL 4.5 core context (throws penumbra::Error otherwise). Starts with
  /// the uniform projection and the hard filter.
  Shadows();
  /// Deletes every GL object Penumbra created (the context must still be current).
  ~Shadows();
  Shadows(const Shadows&) = delete;
  Shadows& operator=(const Shadows&) = delete;

  /// Replaces the technique, the one every light uses (with its own overrides). With a `light`,
  /// throws a usage Error (and keeps the old technique) if the pair cannot work with it; render()
  /// checks the pair against every light every frame.
  void setTechnique(std::unique_ptr<Projection> projection, std::unique_ptr<Filter> filter,
                    const Light* light = nullptr);
  /// By id (penumbra list names them) with "key" → "value" parameters (the projection's, the
  /// filter's and the add-ons'); usage Errors name what is unknown or out of range.
  void setTechnique(std::string_view projectionId, std::string_view filterId,
                    const std::vector<std::pair<std::string, std::string>>& params = {});
  /// The technique every light uses: parameters set here reach every light's copy at the next
  /// render(), under the light's own overrides.
  Projection& projection();
  Filter& filter();
  /// The add-ons any filter can take (Registry.h's addOnGroups), each off by default: contact
  /// shadows ("contact.*", docs/contact.md; setParam("contact.shadows", "on")) and temporal
  /// accumulation ("temporal.*", docs/temporal.md; setParam("temporal.accumulate", "on")).
  Parameterized& addOns();

  /// The casters (validated: buffers exist and hold the ranges drawn) and the world bounds of
  /// the receivers that cast no shadow (a ground that is not in `casters`): the light's views
  /// are fitted to both. Cheap to call every frame with moved transforms.
  void setCasters(std::span<const CasterMesh> casters, std::span<const Aabb> receiverBounds = {});
  /// The casters' triangles on the CPU, for filters that bake them (sdf); nullptr = none. The
  /// scene must outlive its use.
  void setCasterGeometry(const Scene* scene);

  /// When the shadow maps are drawn again (MapUpdates; every map every frame by default), for
  /// every light that does not set its own (LightShadowSettings::updates).
  void setMapUpdates(const MapUpdates& updates);
  const MapUpdates& mapUpdates() const;
  /// What the map updates did since the last setMapUpdates, over every light (lightReports()
  /// gives each light's in the last frame). A map's staleness in a frame is the number of frames
  /// since it was last updated (0: updated in that frame).
  struct MapCacheStats {
    size_t restored = 0;  ///< maps whose static casters' depth was restored from their cache
    size_t rendered = 0;  ///< maps whose static casters were drawn (and stored in their cache)
    size_t kept = 0;      ///< MapUpdates::Budget: maps left as an earlier frame drew them
    int maxStaleness = 0;         ///< the most any map reached (frames)
    double meanStaleness = 0.0;   ///< over every map of every shadowed light in every frame
  };
  MapCacheStats mapCacheStats() const;

  /// Renders the shadow maps, prefilters them and writes the visibility texture.
  void render(const ShadowFrameInputs& inputs);

  /// Lights of the last frame.
  size_t lightCount() const;
  /// V of light `light` for the last frame: an R32F 2D texture of the surfaces' size, 1 = lit,
  /// 0 where the surface faces away from the light, 1 on background pixels. Owned by Penumbra
  /// (a view of one layer of visibilityArrayTexture()).
  uint32_t visibilityTexture(size_t light = 0) const;
  /// Every light's V: an R32F 2D array texture, layer i = light i.
  uint32_t visibilityArrayTexture() const;
  /// The same, read back (row 0 = bottom).
  std::vector<float> readVisibility(size_t light = 0) const;
  /// V of `light` at world points with the last frame's maps (the visibility pass over a point
  /// list). With temporal accumulation on, V as accumulated instead: the last frame's visibility
  /// layer, bilinear at the point's position on screen (points off screen read the pass's V).
  std::vector<float> visibilityAt(std::span<const SurfaceSample> points, size_t light = 0);

  /// Binds Penumbra's frame and shadow-view blocks (PN_UBO_FRAME, PN_UBO_SHADOW of
  /// shaders/shared/Bindings.h) for `light` as the last render() filled them, for a pass of the
  /// caller's that includes shaders/common/shadow.glsl (a debug view of the cascades, say).
  void bindFrameBlocks(size_t light = 0) const;

  /// The last frame's views of `light` as its maps were drawn (with MapUpdates::Budget, a kept
  /// map's view is the one an earlier frame drew it with).
  const LightFrusta& frusta(size_t light = 0) const;
  /// What each light got in the last frame (map size, views, importance).
  const std::vector<LightShadowReport>& lightReports() const;
  /// "shadow", "prefilter", "visibility" (and "contact", "temporal" when on) of the last frame,
  /// each the sum over the lights
  const PassTimings& timings() const;
  /// GPU memory the technique keeps now, in bytes: every texture and buffer its filters (one copy
  /// per light) and the contact pass, when on, created during their passes and still hold (shadow
  /// maps, moment, mip, summed-area and pyramid storage, baked fields, debug images), counted where
  /// GL storage is allocated. The visibility array, the uniform blocks and the caller's surfaces
  /// are not the technique's.
  std::size_t techniqueMemoryBytes() const;
  /// Every intermediate of the last frame a viewer can show for `light`: its visibility, then its
  /// filter's maps.
  std::vector<DebugImage> debugImages(size_t light = 0) const;
  /// The programs Penumbra compiled (for tools that reload shader sources while running).
  ShaderLibrary& shaders();

  struct Impl;

private:
  std::unique_ptr<Impl> mImpl;
};

}  // namespace penumbra
