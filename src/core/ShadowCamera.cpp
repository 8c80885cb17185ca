#include <penumbra/Error.h>
#include <penumbra/Shadows.h>

#include <fmt/format.h>
#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>

namespace penumbra {
namespace {

// A projection's w row is (0, 0, ∓1, 0) for a perspective camera (−1: OpenGL's right-handed view
// looking down -Z; +1: a left-handed one looking down +Z) and (0, 0, 0, 1) for an orthographic
// one; this much slack absorbs the rounding of any matrix library.
constexpr float kRowTolerance = 1e-5f;
// The far distance given to an infinite (or effectively infinite) far plane: far beyond any
// coordinate Penumbra accepts, so every projection clips to the scene's bounds instead.
constexpr float kFarthestFarM = 4.0f * kMaxCoordinateM;
// An orthographic view volume that reaches behind its eye (a negative near plane, as editors'
// top views have) is fitted from an eye moved back along the view axis, to this fraction of the
// volume's depth before the volume's near plane: the projections measure distances from the eye.
constexpr float kOrthoEyeBackFraction = 0.01f;

bool near(float a, float b) { return std::abs(a - b) < kRowTolerance; }

/// The distances along the (right-handed) view axis where ndc.z reaches the two ends of the
/// convention's range, the nearer first; ends the projection never reaches (an infinite far
/// plane) give kFarthestFarM.
glm::vec2 depthRange(const glm::mat4& p, DepthConvention depth, bool orthographic) {
  const float ends[2] = {depth == DepthConvention::ZeroToOne ? 0.0f : -1.0f, 1.0f};
  glm::vec2 range(kFarthestFarM, -kFarthestFarM);
  for (const float ndc : ends) {
    // Perspective: ndc.z(d) = (p[3][2] − p[2][2]·d) / d. Orthographic: ndc.z(d) = p[3][2] − p[2][2]·d.
    const float d = orthographic ? (p[3][2] - ndc) / p[2][2] : p[3][2] / (ndc + p[2][2]);
    const float distanceM = std::isfinite(d) && (orthographic || d > 0.0f) ? std::clamp(d, -kFarthestFarM, kFarthestFarM) : kFarthestFarM;
    range = {std::min(range.x, distanceM), std::max(range.y, distanceM)};
  }
  return range;
}

}  // namespace

ShadowCamera ShadowCamera::fromMatrices(const glm::mat4& viewFromWorld, const glm::mat4& clipFromView,
                                        DepthConvention depth) {
  glm::mat4 view = viewFromWorld, p = clipFromView;
  const bool wRowXY = near(p[0][3], 0.0f) && near(p[1][3], 0.0f);
  const bool perspectiveRH = wRowXY && near(p[2][3], -1.0f) && near(p[3][3], 0.0f);
  const bool perspectiveLH = wRowXY && near(p[2][3], 1.0f) && near(p[3][3], 0.0f);
  const bool orthographic = wRowXY && near(p[2][3], 0.0f) && near(p[3][3], 1.0f);
  if (!(perspectiveRH || perspectiveLH || orthographic) || !(p[0][0] > 0.0f && p[1][1] > 0.0f) || !std::isfinite(p[2][2]) ||
      !std::isfinite(p[3][2]) || (orthographic && p[2][2] == 0.0f))
    throw usageError("ShadowCamera::fromMatrices: clipFromView is neither a perspective projection (w row (0, 0, -1, 0) or, "
                     "left-handed, (0, 0, 1, 0)) nor an orthographic one (w row (0, 0, 0, 1)), with positive x and y scales");
  const glm::mat4 worldFromView0 = glm::inverse(view);
  if (!(std::isfinite(worldFromView0[3][0]) && std::isfinite(worldFromView0[3][1]) && std::isfinite(worldFromView0[3][2])))
    throw usageError("ShadowCamera::fromMatrices: viewFromWorld is not invertible");
  // A left-handed view (looking down +Z) becomes right-handed: the view's z and the projection's
  // z column flip together, so clipFromView · viewFromWorld is the engine's own.
  const glm::mat4 flipZ = glm::scale(glm::mat4(1.0f), glm::vec3(1.0f, 1.0f, -1.0f));
  // An orthographic volume wholly behind a view looking down -Z is one looking down +Z.
  if (perspectiveLH || (orthographic && depthRange(p, depth, true).y <= 0.0f)) {
    view = flipZ * view;
    p = p * flipZ;
  }
  glm::vec2 range = depthRange(p, depth, orthographic);
  ShadowCamera c;
  c.depth = depth;
  c.aspect = p[1][1] / p[0][0];
  if (orthographic) {
    // The fitted camera stands on the volume's axis (an off-centre volume moves it sideways) and,
    // when the volume reaches behind the eye, moves back until it does not: the same clip space.
    const float x = -p[3][0] / p[0][0], y = -p[3][1] / p[1][1];
    const float back = range.x > 0.0f ? 0.0f : range.x - kOrthoEyeBackFraction * (range.y - range.x);
    const glm::mat4 move = glm::translate(glm::mat4(1.0f), glm::vec3(-x, -y, back));
    view = move * view;
    p = p * glm::inverse(move);
    range -= back;
    c.fit.orthoHalfHeightM = 1.0f / p[1][1];
  }
  const glm::mat4 worldFromView = glm::inverse(view);
  c.viewFromWorld = view;
  c.clipFromView = p;
  c.fit.position = glm::vec3(worldFromView[3]);
  c.fit.target = c.fit.position - glm::normalize(glm::vec3(worldFromView[2]));
  c.fit.up = glm::normalize(glm::vec3(worldFromView[1]));
  c.fit.fovYRad = orthographic ? c.fit.fovYRad : 2.0f * std::atan(1.0f / p[1][1]);
  if (!(range.x > 0.0f && range.x < range.y))
    throw usageError(fmt::format("ShadowCamera::fromMatrices: clipFromView's near and far planes ({} m, {} m) are not in front "
                                 "of the camera",
                                 range.x, range.y));
  c.fit.nearM = range.x;
  c.fit.farM = range.y;
  return c;
}

ShadowCamera ShadowCamera::fromCamera(const Camera& camera, float aspect) {
  ShadowCamera c;
  c.viewFromWorld = camera.viewFromWorld();
  c.clipFromView = camera.clipFromView(aspect);
  c.depth = DepthConvention::ZeroToOne;
  c.fit = camera;
  c.aspect = aspect;
  return c;
}

}  // namespace penumbra
