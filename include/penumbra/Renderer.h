#pragma once
// The renderer runs the frame of DESIGN.md: projection → shadow pass → prefilter → G-buffer →
// visibility → lit. It knows no technique: the Projection and Filter objects do that work.
#include <penumbra/Filter.h>
#include <penumbra/Projection.h>
#include <penumbra/Scene.h>

#include <memory>
#include <span>
#include <string>
#include <utility>
#include <vector>

namespace penumbra {

namespace gl { class Context; }
class ShaderLibrary;

struct RenderOptions {
  int width = 640, height = 360;  ///< output size in pixels
  int shadowMapSize = 2048;       ///< texels per side of each shadow map
  /// What the lit pass writes to the colour image: PN_VIEW_SHADED (0, the default),
  /// PN_VIEW_VISIBILITY, PN_VIEW_CASCADES or PN_VIEW_TEXEL_DENSITY (shaders/shared/Enums.h).
  int debugView = 0;
};

/// A world point at which to evaluate a filter's visibility (Renderer::visibilityAt).
struct SurfaceSample {
  glm::vec3 position{0.0f};               ///< world (m)
  glm::vec3 geoNormal{0.0f, 1.0f, 0.0f};  ///< unit geometric normal (decides N·L and biases)
  glm::ivec2 pixel{0};                    ///< the pixel it was seen at (filters' per-pixel noise)
};

/// Per-pass times of the last frame, in order.
struct PassTimings {
  std::vector<std::pair<std::string, double>> ms;  ///< pass name → milliseconds
  std::string clock;                               ///< "gl-timer-query" or "glFinish+steady_clock"
  double get(std::string_view pass) const;
  double total() const;
};

/// The G-buffer read back to the CPU, row 0 = bottom (GL order).
struct GBufferData {
  int width = 0, height = 0;
  std::vector<glm::vec4> position;   ///< xyz world (m); w = 1 where there is geometry, else 0
  std::vector<glm::vec4> geoNormal;  ///< xyz unit geometric normal (facing the camera side); w unused
  std::vector<glm::vec4> normal;     ///< xyz shading normal
  std::vector<glm::vec4> albedo;     ///< rgb base colour
  bool covered(size_t i) const { return position[i].w > 0.5f; }
};

/// sRGB 8-bit RGBA, row 0 = top (ready for PNG).
struct ColorImage {
  int width = 0, height = 0;
  std::vector<uint8_t> rgba;
};

class Renderer {
public:
  explicit Renderer(gl::Context& context);
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  /// Uploads the scene's geometry (once per scene, not per frame).
  void setScene(const Scene& scene);
  /// Throws a usage Error if the pair cannot work for the scene's light.
  void setTechnique(std::unique_ptr<Projection> projection, std::unique_ptr<Filter> filter);
  /// Renders one frame. Throws Error on GL failures or an oversized shadow map.
  void render(const RenderOptions& options);
  /// Replaces the camera and the lights between frames without re-uploading geometry (the
  /// viewer moves them every frame). Throws a usage Error if `lights` is empty.
  void setCameraAndLights(const Camera& camera, const std::vector<Light>& lights);

  const Scene& scene() const;
  Projection& projection() { return *mProjection; }
  Filter& filter() { return *mFilter; }
  const LightFrusta& frusta() const { return mFrusta; }
  const PassTimings& timings() const { return mTimings; }
  ShaderLibrary& shaders() { return *mShaders; }
  gl::Context& context() { return mContext; }

  /// Re-runs the lit pass of the last frame with another visibility (width × height, row 0 =
  /// bottom; e.g. the reference's) and returns the image. The frame's own V is restored after.
  ColorImage shadeWithVisibility(std::span<const float> visibility);

  /// V of the active filter at world points, with the last frame's shadow maps, views and
  /// camera: the visibility pass run over a point list instead of the G-buffer (the filter's own
  /// computeVisibility, in FrameContext's points mode). 0 for points facing away from the light.
  /// For measurements that keep world points fixed while the camera moves (shimmer).
  std::vector<float> visibilityAt(std::span<const SurfaceSample> points);
  /// Runs a compute shader (a shader-library key) once per pixel of the last frame, with the
  /// frame and shadow blocks and the G-buffer bound, writing an r32f image at PN_IMG_OUTPUT;
  /// returns it (width × height, row 0 = bottom). For screen-space measurements such as the
  /// texel density (metrics/TexelDensity.h).
  std::vector<float> computeScreenScalar(const std::string& computeShader);

  /// Visibility of the last frame, width × height floats, row 0 = bottom.
  std::vector<float> readVisibility() const;
  GBufferData readGBuffer() const;
  ColorImage readColor() const;
  /// The last frame's colour on the GPU (RGBA8 holding sRGB-encoded values, row 0 = bottom),
  /// for display without a read-back. An empty texture before the first render().
  const gl::Texture& colorTexture() const;
  /// Every intermediate a viewer can show, by name: the visibility, the G-buffer, then the
  /// filter's own (Filter::debugImages()). Renderer-level debug outputs belong in this list too.
  std::vector<DebugImage> debugImages() const;
  /// Writes every intermediate (G-buffer, shadow maps, visibility, colour) as images into dir.
  void dump(const std::string& dir) const;

  struct Impl;

private:
  void runLitPass();
  gl::Context& mContext;
  std::unique_ptr<ShaderLibrary> mShaders;
  std::unique_ptr<Projection> mProjection;
  std::unique_ptr<Filter> mFilter;
  LightFrusta mFrusta;
  PassTimings mTimings;
  std::unique_ptr<Impl> mImpl;
};

}  // namespace penumbra
