#pragma once
// The renderer runs the frame of DESIGN.md: projection → shadow pass → prefilter → G-buffer →
// visibility → lit. It knows no technique: the Projection and Filter objects do that work.
#include <penumbra/Filter.h>
#include <penumbra/Projection.h>
#include <penumbra/Scene.h>

#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace penumbra {

namespace gl { class Context; }
class ShaderLibrary;

struct RenderOptions {
  int width = 640, height = 360;  ///< output size in pixels
  int shadowMapSize = 2048;       ///< texels per side of each shadow map
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

  const Scene& scene() const;
  Projection& projection() { return *mProjection; }
  Filter& filter() { return *mFilter; }
  const LightFrusta& frusta() const { return mFrusta; }
  const PassTimings& timings() const { return mTimings; }
  ShaderLibrary& shaders() { return *mShaders; }
  gl::Context& context() { return mContext; }

  /// Visibility of the last frame, width × height floats, row 0 = bottom.
  std::vector<float> readVisibility() const;
  GBufferData readGBuffer() const;
  ColorImage readColor() const;
  /// Writes every intermediate (G-buffer, shadow maps, visibility, colour) as images into dir.
  void dump(const std::string& dir) const;

  struct Impl;

private:
  gl::Context& mContext;
  std::unique_ptr<ShaderLibrary> mShaders;
  std::unique_ptr<Projection> mProjection;
  std::unique_ptr<Filter> mFilter;
  LightFrusta mFrusta;
  PassTimings mTimings;
  std::unique_ptr<Impl> mImpl;
};

}  // namespace penumbra
