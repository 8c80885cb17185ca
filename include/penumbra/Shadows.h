#pragma once
// Penumbra inside an engine (docs/embedding.md): a shadow technique run on the caller's OpenGL
// 4.5 context. The engine gives its camera, its depth (and, if it has them, normal) textures, its
// lights and its casters (meshes in its own buffers); Penumbra renders each light's shadow maps,
// prefilters them and writes one visibility layer per light (R32F, 1 = lit) that the engine
// samples in its own lighting. Penumbra creates no context, sets every GL state its passes
// depend on, and puts back what it changed (RestoreState below). What tools need besides (debug
// images, shader reloads, V at world points) is in penumbra/ShadowsDebug.h.
//
//   penumbra::Shadows shadows;                        // a GL 4.5 context is current
//   shadows.setTechnique(penumbra::Technique("csm", "pcss", {{"pcss.blockerSamples", "16"}}));
//   shadows.setCasters(casters, {.bounds = groundBounds});   // CasterMesh: the engine's buffers
//   shadows.render({.camera = penumbra::ShadowCamera::fromMatrices(view, proj, penumbra::DepthConvention::ZeroToOne),
//                   .surfaces = {.width = w, .height = h, .depth = depthTex},
//                   .lights = lights});
//   glBindTextureUnit(7, shadows.visibilityArrayTexture());  // layer i: V of lights[i], 1 = lit
#include <penumbra/Camera.h>
#include <penumbra/Casters.h>
#include <penumbra/Error.h>
#include <penumbra/Light.h>
#include <penumbra/MapUpdates.h>
#include <penumbra/Technique.h>
#include <penumbra/Timings.h>

#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

namespace penumbra {

/// How the engine's depth texture stores depth: the glClipControl depth mode it rendered with.
enum class DepthConvention {
  NegativeOneToOne,  ///< GL's default: stored depth = ndc.z · 0.5 + 0.5
  ZeroToOne,         ///< glClipControl(…, GL_ZERO_TO_ONE): stored depth = ndc.z (reversed-Z too)
};

/// The camera of this frame, as the engine rendered it.
struct ShadowCamera {
  /// The engine's matrices, turned right-handed (the view looks down -Z) when they were not:
  /// clipFromView · viewFromWorld is the engine's own clipFromWorld either way.
  glm::mat4 viewFromWorld{1.0f};
  glm::mat4 clipFromView{1.0f};
  DepthConvention depth = DepthConvention::ZeroToOne;
  /// The same camera as position, direction, field of view (or orthographic height), near and
  /// far, and its aspect (width / height): what the light's views are fitted to (cascade splits,
  /// warps). Made by the two constructors below.
  Camera fit;
  float aspect = 1.0f;

  /// From the engine's matrices: a perspective projection (symmetric or, jittered, nearly so;
  /// finite or infinite far plane, reversed-Z or not) or an orthographic one, with a right-handed
  /// view looking down -Z (OpenGL's convention) or a left-handed one looking down +Z (Direct3D's:
  /// clipFromView's w row then reads (0, 0, 1, 0)). An infinite far plane becomes a far one that
  /// every projection clips to the scene's bounds. Throws a usage penumbra::Error naming the
  /// matrix when it is neither kind, or not invertible.
  static ShadowCamera fromMatrices(const glm::mat4& viewFromWorld, const glm::mat4& clipFromView,
                                   DepthConvention depth);
  /// From Penumbra's own camera description (reversed-Z, zero to one: Camera::clipFromView).
  static ShadowCamera fromCamera(const Camera& camera, float aspect);
};

/// The surfaces to shadow, one texel per pixel: GL texture names the engine owns (2D textures,
/// width × height each). Their sampling state does not matter (Penumbra reads them with its own
/// sampler objects); depth textures may have compare mode on. Read during render() only.
struct ShadowSurfaces {
  int width = 0, height = 0;
  /// Depth as rendered with the camera (any depth or single-channel float format). Pixels that
  /// hold the clear value of the far plane are background (V = 1).
  uint32_t depth = 0;
  /// Optional: world-space normals in xyz (any float, half or snorm format), facing the camera:
  /// the surface's geometric normal if the engine has one, its shading normal otherwise (biases
  /// are measured along it). 0 = none: each pixel's geometric normal is reconstructed from its
  /// neighbours' depth (docs/embedding.md gives what that costs in accuracy).
  uint32_t normal = 0;
  /// Optional: world positions (xyz m; w > 0.5 where there is geometry) read instead of
  /// reconstructing them from `depth`; Penumbra's own G-buffer has them. 0 = from depth.
  uint32_t position = 0;
};

/// Where the casters' shadows may land besides on the casters: what the light's views are fitted
/// to, with the casters (Shadows::setCasters).
struct ShadowReceivers {
  /// World bounds (m) of surfaces that receive shadows but are not among the casters (a ground
  /// left out of them).
  std::span<const Aabb> bounds = {};
  /// True: the casters and `bounds` hold every surface the camera can see (Penumbra's own
  /// renderer: its scene is all there is). False (the default): Penumbra also measures, each
  /// frame, the bounds of the surfaces the camera sees (a reduction over ShadowSurfaces and a
  /// 24-byte read-back) and fits the views to them too, so that no visible surface falls outside
  /// the maps: ground that was not given still gets its shadows, and no pixel is darkened for
  /// lack of a map. Set it when you can: the views then do not follow the camera (cached maps
  /// stay valid) and the read-back is saved.
  bool complete = false;
};

/// What render() changes in the GL state and puts back.
enum class RestoreState {
  /// Every binding and switch Penumbra touches is read before and written back after: the
  /// framebuffers and viewport, depth range, program, vertex array; blend (and its factors and
  /// equations), scissor, stencil,
  /// logic op, polygon offset, rasterizer discard, primitive restart, sRGB, alpha to coverage,
  /// clip distances 0–7, depth test, clamp, function and mask, colour mask, face culling and
  /// front face, polygon mode, clip control; texture units 0–15 (2D, 2D array, 3D targets) and
  /// their samplers, image units 0–3, uniform buffers 0–2 and storage buffers 0–5 (indexed
  /// bindings), the pixel pack and unpack parameters and buffers, the active texture unit.
  /// About 216 glGet calls a frame.
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
  /// The lights, 1..kMaxShadowedLights, each with its own maps and visibility layer (layer i =
  /// lights[i]). Penumbra keeps each light's state under Light::id from frame to frame. A light's
  /// `shadow` settings are merged into the technique for it (its own projection, filter, map size
  /// and parameters). Light::castsShadow false: its layer is 1 everywhere it is not behind itself.
  std::span<const Light> lights;
  /// Texels that every light's maps together may hold (0 = no budget): each light then gets a
  /// share by its importance on screen, never more than its technique asks for (lightReports()
  /// says what).
  int64_t mapBudgetTexels = 0;
  RestoreState restore = RestoreState::All;
  /// With temporal accumulation on (the technique's "temporal.*", docs/temporal.md): this frame
  /// does not continue the last one (a camera cut, a teleport), so no V of earlier frames is
  /// reused. Penumbra keeps the previous frame's camera and surfaces itself; a light's history is
  /// also dropped when the surfaces' size or the light's technique changes.
  bool cameraCut = false;
};

/// What one light got in the last frame.
struct LightShadowReport {
  uint64_t id = 0;           ///< Light::id
  int requestedMapSize = 0;  ///< its technique's map size (its own settings merged)
  int mapSize = 0;           ///< what the budget gave it (= requested without a budget)
  int views = 0;             ///< maps: 1, a cascade each, 6 for a point light's cube
  double importance = 0.0;   ///< its share of the screen, in (0, 1] (the budget's weight)
  MapUpdates updates;        ///< the policy its maps followed (its own, or Shadows')
  int keptMaps = 0;          ///< MapUpdates::Budget: its maps left as an earlier frame drew them
  int staleness = 0;         ///< the oldest of its maps (frames since drawn; 0 = all drawn this frame)
  /// A paged projection (virtual; 0 otherwise): its pages in this frame. Pages are drawn where
  /// this frame's pixels need them and kept across frames until their casters or the light move.
  struct Pages {
    int needed = 0;       ///< pages this frame's pixels need
    int drawn = 0;        ///< pages drawn this frame
    int resident = 0;     ///< valid pages the pool holds after the frame
    int missing = 0;      ///< needed pages the full pool could not hold (coarser levels served them)
    int poolPages = 0;    ///< the pool's capacity
    int64_t poolBytes = 0;  ///< the pool's memory (with the static casters' copy under cached map updates)
  } pages;
  int64_t texels() const { return static_cast<int64_t>(views) * mapSize * mapSize; }
};

/// Runs a technique (projection × filter) on the caller's context. Not thread-safe; every call
/// needs the same GL 4.5 context current as at construction.
class Shadows {
public:
  /// Needs a current OpenGL 4.5 core context (throws penumbra::Error otherwise). Starts with
  /// Technique(): the uniform projection and the hard filter.
  Shadows();
  /// Deletes every GL object Penumbra created (the context must still be current).
  ~Shadows();
  Shadows(const Shadows&) = delete;
  Shadows& operator=(const Shadows&) = delete;

  /// The technique every light runs, with the light's own settings merged in (Light::shadow).
  /// Each light's state (its maps, prefiltered textures and history) is made from its technique
  /// at its next frame; a light whose technique changes gets new maps (its filter's kind
  /// changed) or new values (only parameters changed). render() checks every light against its
  /// technique every frame.
  void setTechnique(const Technique& technique);
  const Technique& technique() const;

  /// The casters (validated: buffers exist and hold the ranges drawn) and where their shadows
  /// may land: the light's views are fitted to both. Cheap to call every frame with moved
  /// transforms.
  void setCasters(std::span<const CasterMesh> casters, const ShadowReceivers& receivers = {});
  /// The casters' triangles on the CPU, for filters that bake them (sdf), in the engine's memory:
  /// read (not copied) by the render() calls that bake, so keep them alive and unchanged until
  /// the next call. An empty span says there are no caster triangles (sdf then shadows nothing);
  /// without any call, sdf is refused.
  void setCasterGeometry(std::span<const CasterGeometry> casters);

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
  /// Every light's V for the last frame: an R32F 2D array texture of the surfaces' size (RGBA32F
  /// where V has colour: visibilityHasColour), layer i = lights[i], 1 = lit, 0 where the surface faces away from the light, 1 on background
  /// pixels. Owned by Penumbra. The name stays the same from frame to frame; it is remade (a new
  /// name; the old one deleted) by the render() whose surfaces' size or light count differs from
  /// the frame before, and deleted by ~Shadows().
  uint32_t visibilityArrayTexture() const;
  /// V of lights[light] alone: a 2D texture viewing that layer (glTextureView). Lives and is
  /// remade as visibilityArrayTexture() is.
  uint32_t visibilityTexture(size_t light = 0) const;
  /// The same, read back (row 0 = bottom). Where V has colour (visibilityHasColour) the mean of
  /// its three channels.
  std::vector<float> readVisibility(size_t light = 0) const;
  /// Whether the last frame's V has colour: some light's technique tints it by translucent
  /// casters (the "translucent.*" add-on, CasterMesh::transmittance; docs/translucent.md). The
  /// visibility array is then RGBA32F (RGB = V per channel, alpha 1) instead of R32F; a scene
  /// without translucent casters, or a technique without the add-on, keeps one channel.
  bool visibilityHasColour() const;
  /// V of lights[light] per channel (row 0 = bottom); empty when V has no colour.
  std::vector<glm::vec3> readVisibilityRgb(size_t light = 0) const;

  /// What each light got in the last frame (in the lights' order).
  const std::vector<LightShadowReport>& lightReports() const;
  /// "shadow", "prefilter", "visibility" (and "receivers", "contact", "temporal" when they run)
  /// of the last frame, each the sum over the lights
  const PassTimings& timings() const;
  /// GPU memory the technique keeps now, in bytes: every texture and buffer its lights' filters
  /// and add-ons created during their passes and still hold (shadow maps, moment, mip,
  /// summed-area and pyramid storage, baked fields, accumulated V, debug images), counted where
  /// GL storage is allocated. The visibility array, the uniform blocks and the caller's surfaces
  /// are not the technique's.
  std::size_t techniqueMemoryBytes() const;

  struct Impl;

private:
  friend struct ShadowsAccess;  // core/ShadowsAccess.h: the tools' way in (ShadowsDebug.h)
  std::unique_ptr<Impl> mImpl;
};

}  // namespace penumbra
