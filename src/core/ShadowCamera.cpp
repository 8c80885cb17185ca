#include <penumbra/Error.h>
#include <penumbra/Shadows.h>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace penumbra {
namespace {

// A perspective projection's w row is (0, 0, -1, 0) (OpenGL's right-handed view looking down -Z);
// this much slack absorbs the rounding of any matrix library.
constexpr float kPerspectiveTolerance = 1e-5f;
// The far distance given to an infinite (or effectively infinite) far plane: far beyond any
// coordinate Penumbra accepts, so every projection clips to the scene's bounds instead.
constexpr float kFarthestFarM = 4.0f * kMaxCoordinateM;

}  // namespace

ShadowCamera ShadowCamera::fromMatrices(const glm::mat4& viewFromWorld, const glm::mat4& clipFromView,
                                        DepthConvention depth) {
  const glm::mat4& p = clipFromView;
  const bool perspective = std::abs(p[2][3] + 1.0f) < kPerspectiveTolerance && std::abs(p[3][3]) < kPerspectiveTolerance &&
                           std::abs(p[0][3]) < kPerspectiveTolerance && std::abs(p[1][3]) < kPerspectiveTolerance &&
                           p[0][0] > 0.0f && p[1][1] > 0.0f && std::isfinite(p[2][2]) && std::isfinite(p[3][2]);
  if (!perspective)
    throw usageError("ShadowCamera::fromMatrices: clipFromView is not a perspective projection looking down -Z "
                     "(w row (0, 0, -1, 0), positive x and y scales)");
  const glm::mat4 worldFromView = glm::inverse(viewFromWorld);
  PN_CHECK(std::isfinite(worldFromView[3][0]) && std::isfinite(worldFromView[3][1]) && std::isfinite(worldFromView[3][2]),
           "ShadowCamera::fromMatrices: viewFromWorld is not invertible");
  ShadowCamera c;
  c.viewFromWorld = viewFromWorld;
  c.clipFromView = clipFromView;
  c.depth = depth;
  c.aspect = p[1][1] / p[0][0];
  c.fit.position = glm::vec3(worldFromView[3]);
  c.fit.target = c.fit.position - glm::normalize(glm::vec3(worldFromView[2]));
  c.fit.up = glm::normalize(glm::vec3(worldFromView[1]));
  c.fit.fovYRad = 2.0f * std::atan(1.0f / p[1][1]);
  // The distances at which ndc.z reaches the two ends of the convention's range: near and far.
  // ndc.z(d) = (p[3][2] − p[2][2]·d) / d, so d = p[3][2] / (ndc + p[2][2]); an end the
  // projection never reaches (an infinite far plane) gives no finite positive d.
  const float ends[2] = {depth == DepthConvention::ZeroToOne ? 0.0f : -1.0f, 1.0f};
  float nearM = kFarthestFarM, farM = 0.0f;
  for (float ndc : ends) {
    const float d = p[3][2] / (ndc + p[2][2]);
    const float distanceM = std::isfinite(d) && d > 0.0f ? std::min(d, kFarthestFarM) : kFarthestFarM;
    nearM = std::min(nearM, distanceM);
    farM = std::max(farM, distanceM);
  }
  PN_CHECK(nearM > 0.0f && nearM < farM,
           fmt::format("ShadowCamera::fromMatrices: the projection's near and far planes ({} m, {} m) are not in front of the camera",
                       nearM, farM));
  c.fit.nearM = nearM;
  c.fit.farM = farM;
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
