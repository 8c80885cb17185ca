#pragma once
// A light's views as its shadow maps were drawn: one for a sun's or a spot's map, a cascade each,
// six cube faces for a point light (ShadowsDebug.h's frusta() hands them out; the projections
// make them).
#include <penumbra/Math.h>

#include <vector>

namespace penumbra {

/// A point light's cube faces, in the order the shaders pick them (common/shadow.glsl's
/// cubeFace): +X, −X, +Y, −Y, +Z, −Z. Its views are these faces (uniform), or each face's levels,
/// face after face (virtual).
inline constexpr int kCubeFaces = 6;

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

}  // namespace penumbra
