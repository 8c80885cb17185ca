#pragma once
// tsm: trapezoidal shadow maps (Martin & Tan, "Anti-aliasing and continuity with trapezoidal
// shadow maps", EGSR 2004). In the light's image plane the visible receivers form a region that
// widens away from the camera; a trapezoid around it, narrow end at the camera and centred on the
// projected view axis (or on the line to the region's centroid where the axis' image points away
// from the receivers), is mapped onto the square map by a perspective warp, so the map spends its
// texels near the camera. The warp's strength follows the 80% rule: the point at the focus distance lands on the
// line 80% of the way across the map. The map still stores the light's linear depth; only the
// rasterisation and lookup positions are warped. Degenerates (falls back to `uniform`'s fit)
// when the camera looks along the light. Artifacts: texels are stretched along the trapezoid's
// sides; as the camera turns the trapezoid changes every frame (no snapping: edges crawl).
#include "techniques/projections/LightSpace.h"

#include "frame/Projection.h"

#include <span>
#include <vector>

namespace penumbra {

class TrapezoidalProjection final : public Projection {
public:
  TrapezoidalProjection();
  std::string_view id() const override { return "tsm"; }
  std::string_view description() const override {
    return "one map warped by a trapezoid around the view frustum in light space (80% focus rule)";
  }
  /// A point light shines every way: its views are the six cube faces of the uniform projection.
  std::string incompatibility(const Light& light) const override { return pointLightIncompatibility(light); }
  LightFrusta computeFrusta(const Camera& camera, float aspect, const Light& light, const SceneExtent& scene,
                            int mapSize) const override;
};

/// The warp of the light's image plane (normalised device xy of the unwarped light view) that
/// maps a trapezoid onto [-1,1]²: apex q, unit centre-line direction u, the top and base edges at
/// distances eta and eta + lambda from q along u, the sides at tangents tMin, tMax from the line.
/// Returned as a 4×4 acting on the unwarped light clip coordinates (clip z/w is set to 0.5: the
/// depth written is the linear light depth, not this).
glm::mat4 trapezoidWarp(const glm::vec2& q, const glm::vec2& u, float eta, float lambda, float tMin, float tMax);

/// The extent (smallest, largest) of `hull` along the unit direction u, measured from `top`.
glm::vec2 extentAlong(std::span<const glm::vec2> hull, const glm::vec2& top, const glm::vec2& u);

/// The trapezoid (a perspective frustum of the light's image plane) around the points `hull`,
/// centred on the line through `top` along the unit direction u: its top and base edges
/// perpendicular to u touch the region, its apex lies on the line `eta` before the top edge and
/// its sides are the widest tangents from the apex; `marginFraction` of the map is added on every
/// side, in warped units. Shared by tsm (η from the 80% rule) and lispsm (η = n_opt).
glm::mat4 trapezoidAround(std::span<const glm::vec2> hull, const glm::vec2& top, const glm::vec2& u, float eta,
                          float marginFraction);

/// The 80% rule: distance η of the apex behind the top edge so that a point δ past the top edge
/// (of a trapezoid of height λ) maps to `mapFraction` of the way across the map:
/// η = (1 − m)·λ·δ / (m·λ − δ). Returns +inf when δ ≥ m·λ (no warp is needed).
float trapezoidApexDistance(float lambda, float delta, float mapFraction);

/// The area centroid of the convex hull of `points` (Andrew's monotone chain, then the shoelace
/// sums); the mean of the points when the hull has no area (fewer than 3 points, or collinear;
/// (0, 0) for none).
glm::vec2 hullAreaCentroid(std::vector<glm::vec2> points);

}  // namespace penumbra
