#pragma once
// lispsm: light-space perspective shadow maps (Wimmer, Scherzer & Purgathofer, EGSR 2004). A
// perspective frustum P is laid in light space with its axis along the camera's view direction
// projected onto the plane perpendicular to the light, so the light's rays stay parallel (the
// light keeps its direction after P's projection and the map is an ordinary orthographic view
// of P's post-perspective space): only the light's image plane is warped, by a perspective along
// that axis. P's near plane touches the receivers' region nearest the camera; its projection
// centre lies n before it, with Wimmer et al.'s optimum n_opt = (z0 + √(z0·z1)) / sin γ (z0 the
// nearest visible receiver's camera depth, z1 = z0 + d·sin γ, d the region's depth along P's
// axis, γ the angle between the view and the light directions), which spreads the aliasing error
// evenly over the view depth. As the camera turns toward the light (sin γ → 0) n_opt grows
// without bound and the map tends to `uniform`'s: the paper's answer to that degenerate case,
// where no warp can help (both look along one line). Penumbra takes the unwarped fit there. A
// spot light is warped in its own post-perspective space, where its rays are parallel (the
// paper's treatment of point lights). The map stores the light's linear depth; only
// rasterisation and lookup positions are warped. Artifacts: texel size still changes with the
// camera every frame (no snapping: edges crawl); texels stretch along P's sides.
#include "techniques/projections/LightSpace.h"

#include "frame/Projection.h"

#include <vector>

namespace penumbra {

/// Wimmer et al.'s optimal distance (m) from P's projection centre to its near plane: for the
/// nearest receiver depth z0 (m, > 0), the region's depth d (m) along P's axis and the sine of
/// the angle between the view direction and the light direction: (z0 + √(z0·(z0 + d·sin γ))) / sin γ.
/// +inf when sin γ <= 0 (view and light along one line: no warp).
float lispsmOptimalNear(float z0M, float depthM, float sinGamma);

/// What the projection decided for one light and camera.
struct LispsmWarp {
  glm::mat4 clipFromWorld{1.0f};
  bool degenerate = false;  ///< no warp (view ∥ light, or nothing visible): the caller keeps the unwarped fit
  float sinGamma = 0.0f;    ///< sine of the angle between the view and the light directions
  float nearM = 0.0f;       ///< z0: the nearest visible receiver's camera depth (m)
  float depthM = 0.0f;      ///< d: the receivers' region's depth along P's axis (m)
  float nOptM = 0.0f;       ///< n: P's projection centre before its near plane (m), n_opt × lispsm.nScale
};

/// The warp for receivers `body` (world points whose hull bounds them) seen by `camera` over
/// the unwarped view `base` (its viewFromWorld gives the light's image plane); `nScale` multiplies n_opt.
LispsmWarp computeLispsmWarp(const Camera& camera, const Light& light, std::span<const glm::vec3> body,
                             const ShadowView& base, float nScale, float marginFraction);

class LightSpacePerspectiveProjection final : public Projection {
public:
  LightSpacePerspectiveProjection();
  std::string_view id() const override { return "lispsm"; }
  std::string_view description() const override {
    return "one map warped by a perspective along the view direction in light space (Wimmer et al.'s n_opt)";
  }
  /// A point light shines every way: its views are the six cube faces of --projection uniform.
  std::string incompatibility(const Light& light) const override { return pointLightIncompatibility(light); }
  LightFrusta computeFrusta(const Camera& camera, float aspect, const Light& light, const SceneExtent& scene,
                            int mapSize) const override;
};

}  // namespace penumbra
