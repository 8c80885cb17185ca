#pragma once
// The aliasing axis: where the light's view(s) are placed and how they are warped. A projection
// holds no GPU storage: an instance is its parameter values (a light's, made from its technique:
// makeProjection) and a pure function of them. Pure C++ (no GL), so every projection is
// unit-testable on the CPU.
#include <penumbra/Camera.h>
#include <penumbra/Light.h>
#include <penumbra/Params.h>
#include <penumbra/Scene.h>
#include <penumbra/ShadowViews.h>

#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace penumbra {

/// What the camera's pixels hold, measured on demand for projections fitted to them (sdsm): the
/// core answers with a GPU reduction over the covered pixels that face the light, the pixels the
/// visibility pass will look up. Each call is one pass over the screen and a read back.
class PixelBounds {
public:
  virtual ~PixelBounds() = default;
  /// The nearest and farthest camera view depth (m) of those pixels; (+inf, −inf) when there is none.
  virtual glm::vec2 depthRange() = 0;
  /// For each slice i of camera depth [sliceNearM[i], sliceFarM[i]] (m; slices may overlap, at most
  /// 8): the bounds of those pixels' positions after `spaceFromWorld` (an affine map, e.g. a sun's
  /// light view). An empty Aabb for a slice that holds no pixel.
  virtual std::vector<Aabb> sliceBounds(const glm::mat4& spaceFromWorld, std::span<const float> sliceNearM,
                                        std::span<const float> sliceFarM) = 0;
};

/// How a paged projection's views are stored (frame/VirtualPages, docs/virtual.md): each view is a
/// virtual map of virtualSize² texels cut into pages of pageSize² texels, of which only the pages
/// this frame's pixels need are drawn, into a pool of poolPages tiles kept across frames.
struct PageLayout {
  int virtualSize = 16384;  ///< texels per side of each view's virtual map (a multiple of pageSize)
  int pageSize = 128;       ///< texels per side of a page
  int poolPages = 2048;     ///< pages the pool holds (its fixed memory: poolPages · pageSize² depths)
  float marginTexels = 4.0f;  ///< texels around each pixel's texel whose pages are marked with it
  float levelBias = 0.0f;     ///< levels added to each pixel's choice (+ = coarser, fewer pages)
  float grazingLevels = 1.0f;  ///< at most this many levels finer where the camera grazes a surface
  int pagesPerSide() const { return virtualSize / pageSize; }
  bool operator==(const PageLayout&) const = default;
};

class Projection : public Parameterized {
public:
  using Parameterized::Parameterized;
  virtual std::string_view id() const = 0;
  virtual std::string_view description() const = 0;
  /// Empty when this projection can place views for `light`; otherwise the reason, shown to the
  /// user (a pair that cannot work is refused, never rendered wrong).
  virtual std::string incompatibility(const Light& light) const {
    (void)light;
    return {};
  }
  /// The light's view(s) for this camera. `aspect` = width / height of the image; `mapSize` =
  /// texels per side of each map (fits add margins and snap in whole texels).
  virtual LightFrusta computeFrusta(const Camera& camera, float aspect, const Light& light,
                                    const SceneExtent& scene, int mapSize) const = 0;
  /// The same with the camera's pixels at hand, which is how the core places views every frame:
  /// projections fitted to what the pixels need (sdsm) measure them here; the others ignore
  /// `pixels` (and measure nothing). computeFrusta alone (CPU callers: map budgets, tests) gives
  /// such a projection's fit to the scene's geometry instead, with the same view count.
  virtual LightFrusta computeFrustaFromPixels(const Camera& camera, float aspect, const Light& light,
                                              const SceneExtent& scene, int mapSize, PixelBounds& pixels) const {
    (void)pixels;
    return computeFrusta(camera, aspect, light, scene, mapSize);
  }
  /// A paged projection's storage: its views are virtual maps (of layout.virtualSize texels, not
  /// the technique's map size) drawn page by page where pixels need them. None: whole maps.
  virtual std::optional<PageLayout> pageLayout() const { return std::nullopt; }
};

}  // namespace penumbra
