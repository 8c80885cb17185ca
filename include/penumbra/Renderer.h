#pragma once
// Penumbra's own renderer (docs/design.md): a G-buffer pass, the shadows of the engine-facing
// core (penumbra/Shadows.h: projection → shadow pass → prefilter → visibility) on that G-buffer,
// then the lit pass. It is the core's first client and knows no technique.
#include "frame/Filter.h"

#include <penumbra/Image.h>
#include <penumbra/Scene.h>
#include <penumbra/ShadowViews.h>
#include <penumbra/Shadows.h>
#include <penumbra/ShadowsDebug.h>
#include <penumbra/Technique.h>
#include <penumbra/Timings.h>

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <utility>
#include <vector>

namespace penumbra {

class ShaderLibrary;

struct RenderOptions {
  int width = 640, height = 360;  ///< output size in pixels
  /// Texels all lights' maps share (every cascade and cube face counted); 0 = no budget, each
  /// light gets its technique's map size (Technique::mapSize, or its own override). See
  /// ShadowFrameInputs::mapBudgetTexels.
  int64_t shadowBudgetTexels = 0;
  /// What the lit pass writes to the colour image: PN_VIEW_SHADED (0, the default),
  /// PN_VIEW_VISIBILITY, PN_VIEW_CASCADES or PN_VIEW_TEXEL_DENSITY (shaders/shared/Enums.h).
  int debugView = 0;
  /// The camera jumped since the last frame (a cut, a teleport, a new view): temporal
  /// accumulation drops its history (ShadowFrameInputs::cameraCut).
  bool cameraCut = false;
  /// Record which triangle each pixel shows (GBufferData::triangle: one more G-buffer attachment,
  /// 8 bytes a pixel written every frame). The reference needs them to skip each receiver's own
  /// triangle, so every path that traces it keeps the default; a frame only displayed (penumbra
  /// render) turns them off. Off, readGBuffer() leaves GBufferData::triangle empty.
  bool triangleIds = true;
};

class Renderer {
public:
  /// Needs a current OpenGL 4.5 core context (the platform's, or the caller's).
  Renderer();
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  /// GPU bytes of what a frame of width × height allocates per pixel (G-buffer, colour, the
  /// core's visibility), for a check before rendering. Shadow maps and filter tables come on top.
  static uint64_t screenBytes(int width, int height);

  /// Uploads the scene's geometry (once per scene, not per frame) and keeps the scene (scene()):
  /// give it with std::move where the caller needs no copy of its own (a large model's meshes are
  /// then held once).
  void setScene(Scene scene);
  /// The technique every light runs (a light's own shadow settings merged in). Throws a usage
  /// Error, and keeps the technique it had, when a light of the scene cannot be shadowed with it.
  void setTechnique(const Technique& technique);
  const Technique& technique() const;
  /// Renders one frame. Throws Error on GL failures or an oversized shadow map.
  void render(const RenderOptions& options);
  /// Replaces the camera and the lights between frames without re-uploading geometry (the
  /// viewer moves them every frame). Throws a usage Error if `lights` is empty.
  void setCameraAndLights(const Camera& camera, const std::vector<Light>& lights);
  /// Moves to `posed`: the scene given to setScene posed at another time (poseScene): its
  /// camera, lights and object transforms; the geometry stays uploaded, the transforms and the
  /// casters' placements are re-sent. Throws Error if the object count differs.
  void setPose(const Scene& posed);

  const Scene& scene() const;
  /// The views of light `light` in the last frame.
  const LightFrusta& frusta(size_t light = 0) const;
  /// Lights of the last frame (the scene's, each with its own maps and visibility layer).
  size_t lightCount() const;
  /// gbuffer, shadow, prefilter, visibility, lit: the last frame's passes in the order they ran.
  const PassTimings& timings() const;
  ShaderLibrary& shaders();
  /// The core this renderer runs its shadows with.
  Shadows& shadows();

  /// Re-runs the lit pass of the last frame with other visibilities, one per light (width ×
  /// height each, row 0 = bottom; e.g. the reference's) and returns the image. `perLightRgb`:
  /// where a light's entry is not empty, its V per channel (the reference's visibilityRgb)
  /// shades it instead. The frame's own V and image are left as they were.
  ColorImage shadeWithVisibility(const std::vector<std::vector<float>>& perLight,
                                 const std::vector<std::vector<glm::vec3>>& perLightRgb = {});
  /// The same for a frame of one light.
  ColorImage shadeWithVisibility(std::span<const float> visibility);

  /// V of the active filter at world points, with the last frame's shadow maps, views and
  /// camera: the visibility pass run over a point list instead of the G-buffer (the filter's own
  /// computeVisibility, in FrameContext's points mode). 0 for points facing away from the light.
  /// For measurements that keep world points fixed while the camera moves (shimmer).
  std::vector<float> visibilityAt(std::span<const SurfaceSample> points, size_t light = 0);
  /// Runs a compute shader (a shader-library key) once per pixel of the last frame, with the
  /// frame and shadow blocks and the G-buffer bound, writing an r32f image at PN_IMG_OUTPUT;
  /// returns it (width × height, row 0 = bottom). For screen-space measurements such as the
  /// texel density (comparison/TexelDensity.h).
  std::vector<float> computeScreenScalar(const std::string& computeShader);

  /// Visibility of light `light` in the last frame, width × height floats, row 0 = bottom (the
  /// mean of the channels where V has colour: Shadows::visibilityHasColour).
  std::vector<float> readVisibility(size_t light = 0) const;
  /// The same per colour channel; empty when the last frame's V has one channel.
  std::vector<glm::vec3> readVisibilityRgb(size_t light = 0) const;
  /// The last frame's G-buffer; `triangle` is empty unless that frame had RenderOptions::triangleIds.
  GBufferData readGBuffer() const;
  ColorImage readColor() const;
  /// The last frame's colour on the GPU (RGBA8 holding sRGB-encoded values, row 0 = bottom),
  /// for display without a read-back. An empty texture before the first render().
  const gl::Texture& colorTexture() const;
  /// Every intermediate a viewer can show, by name: light `light`'s visibility, the G-buffer,
  /// then that light's filter maps (Shadows::debugImages(light)). Renderer-level debug outputs
  /// belong in this list too.
  std::vector<DebugImage> debugImages(size_t light = 0) const;
  /// Writes every intermediate (G-buffer, shadow maps, visibility, colour) as images into dir.
  void dump(const std::string& dir) const;

  struct Impl;

private:
  /// The lit pass, reading the core's visibility array, or `visibility` (an array of one
  /// channel, or of RGB where `colour`).
  void runLitPass(const gl::Texture* visibility = nullptr, bool colour = false);
  std::unique_ptr<Impl> mImpl;
};

}  // namespace penumbra
