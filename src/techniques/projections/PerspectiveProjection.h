#pragma once
// psm: perspective shadow maps (Stamminger & Drettakis, SIGGRAPH 2002). The shadow map is taken
// in the camera's post-perspective space (PPS), where near objects are already large: there the
// sun becomes a point light (or stays a direction when it is perpendicular to the view axis) and
// an ordinary map from it spends texels like the screen does. A virtual camera slid back behind
// the real one keeps every caster that can shadow a visible receiver in front of it, and sets
// the warp's strength (its near/far ratio). Light behind the camera: its PPS image lies beyond
// the far plane with rays converging on it, so the map looks from it toward the scene with the
// depth order reversed ("inverted depth test"); Penumbra stores the real light's linear depth,
// so only the rasterisation is warped and the comparison stays the same. When the warp
// degenerates (a view wider than kMaxHalfAngle from the PPS light even after sliding back) the
// projection falls back to `uniform`'s fit. Artifacts: quality depends strongly on the light
// direction; the map changes with every camera move (edges crawl).
#include "techniques/projections/LightSpace.h"

#include "frame/Projection.h"

#include <span>

namespace penumbra {

/// Where the light lands in the camera's post-perspective space.
enum class PsmLightCase {
  InFront,        ///< a point light beyond the far plane, rays leaving it
  Behind,         ///< beyond the far plane with rays converging on it: inverted depth order
  Perpendicular,  ///< at infinity: a directional light in PPS (orthographic map)
};

/// The case for this light and a camera with this orientation (sun: sign of the light's
/// direction along the view axis; spot: which side of the camera plane the light is on).
PsmLightCase psmLightCase(const Camera& camera, const Light& light);

struct PsmWarp {
  glm::mat4 clipFromWorld{1.0f};
  PsmLightCase lightCase = PsmLightCase::InFront;
  bool degenerate = false;  ///< no usable warp: the caller falls back to an unwarped fit
  float slideBackM = 0.0f;  ///< how far the virtual camera sits behind the real one
};

/// The warp for receivers `receivers` and casters `casters` (world points whose hulls bound
/// them): virtual camera slid back by slideBackM, or more: until all of `scene` is in front of
/// it (geometry behind the virtual eye would wrap through infinity into the map), then doubled
/// until the PPS view is narrow enough.
PsmWarp computePsmWarp(const Camera& camera, const Light& light, std::span<const glm::vec3> receivers,
                       std::span<const glm::vec3> casters, const Aabb& scene, float slideBackM, float marginFraction);

class PerspectiveProjection final : public Projection {
public:
  PerspectiveProjection();
  std::string_view id() const override { return "psm"; }
  std::string_view description() const override {
    return "one map taken in the camera's post-perspective space (virtual camera slide-back)";
  }
  /// A point light shines every way: its views are the six cube faces of the uniform projection.
  std::string incompatibility(const Light& light) const override { return pointLightIncompatibility(light); }
  LightFrusta computeFrusta(const Camera& camera, float aspect, const Light& light, const SceneExtent& scene,
                            int mapSize) const override;
};

}  // namespace penumbra
