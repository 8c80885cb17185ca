#pragma once
// The aliasing axis: where the light's view(s) are placed and how they are warped.
// Pure C++ (no GL), so every projection is unit-testable on the CPU.
#include <penumbra/Params.h>
#include <penumbra/Scene.h>

#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace penumbra {

/// One rendered shadow map's view of the light.
struct ShadowView {
  glm::mat4 viewFromWorld{1.0f};  ///< light view space: looking down -Z
  glm::mat4 clipFromWorld{1.0f};  ///< rasterisation and lookup: NDC xy in [-1,1] → map uv
  /// Linear light-space depth in [0,1] = dot(depthPlane, vec4(wsPosition, 1)): the distance
  /// along the light axis mapped from [nearM, farM]. Linear for ortho and perspective views.
  glm::vec4 depthPlane{0.0f};
  bool perspective = false;
  /// clipFromWorld is warped (psm, tsm): a projective map in the light's image plane on top of
  /// the plain light view, so texel size varies over the map. `extent` then describes the unwarped
  /// fit; shaders take the local texel size from clipFromWorld's derivatives (common/shadow.glsl).
  bool warped = false;
  float nearM = 0.0f, farM = 1.0f;  ///< along the light axis, metres
  /// Ortho: world size (m) of the map's x and y extent. Perspective: the extent at unit
  /// distance from the light, i.e. 2·tan(half fov) on each axis.
  glm::vec2 extent{1.0f};
  float splitFarM = 1e30f;  ///< camera view depth (m) where this view's cascade ends
};

struct LightFrusta {
  std::vector<ShadowView> views;  ///< 1 for uniform/psm/tsm, one per cascade for csm
  float blendBandM = 0.0f;        ///< csm: width of the blend band between cascades
};

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
};

}  // namespace penumbra
