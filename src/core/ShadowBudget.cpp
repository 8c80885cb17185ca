#include "core/ShadowBudget.h"

#include <algorithm>
#include <cmath>

namespace penumbra::core {
namespace {

int64_t texelsOf(std::span<const BudgetRequest> requests, std::span<const int> sizes) {
  int64_t sum = 0;
  for (size_t i = 0; i < requests.size(); ++i)
    sum += static_cast<int64_t>(requests[i].views) * sizes[i] * sizes[i];
  return sum;
}

// Sizes for texels-per-importance k: side = sqrt(k · importance), capped, rounded down.
std::vector<int> sizesFor(std::span<const BudgetRequest> requests, double k) {
  std::vector<int> sizes;
  for (const BudgetRequest& r : requests) {
    const double side = std::sqrt(k * r.importance);
    const int rounded = static_cast<int>(side / kMinBudgetMapSize) * kMinBudgetMapSize;
    sizes.push_back(std::clamp(rounded, std::min(kMinBudgetMapSize, r.requestedMapSize), r.requestedMapSize));
  }
  return sizes;
}

}  // namespace

std::vector<int> allocateMapSizes(std::span<const BudgetRequest> requests, int64_t budgetTexels) {
  std::vector<int> requested;
  for (const BudgetRequest& r : requests) requested.push_back(r.requestedMapSize);
  if (budgetTexels <= 0 || texelsOf(requests, requested) <= budgetTexels) return requested;
  // Bisection on k (texels² per unit of importance): the total grows with k.
  double lo = 0.0, hi = 1.0;
  while (texelsOf(requests, sizesFor(requests, hi)) <= budgetTexels) hi *= 2.0;  // not reached: requested do not fit
  constexpr int kBisections = 60;  // far below one texel of change in any side
  for (int i = 0; i < kBisections; ++i) {
    const double mid = 0.5 * (lo + hi);
    (texelsOf(requests, sizesFor(requests, mid)) <= budgetTexels ? lo : hi) = mid;
  }
  return sizesFor(requests, lo);
}

double lightImportance(const Light& light, const Camera& camera, float aspect, const Aabb& sceneBounds) {
  if (!isPositional(light)) return 1.0;
  float radiusM = light.rangeM;
  if (!(radiusM > 0.0f)) {
    radiusM = 0.0f;  // no range: as far as the scene reaches
    for (const glm::vec3& c : sceneBounds.corners()) radiusM = std::max(radiusM, glm::length(c - light.position));
  }
  const glm::vec3 toLight = light.position - camera.position;
  const float distanceM = glm::length(toLight);
  if (camera.orthographic()) {
    // The sphere's radius against the view's half extents, unless it lies wholly behind the eye.
    if (glm::dot(toLight, camera.forward()) < -radiusM) return kMinImportance;
    const double halfY = camera.orthoHalfHeightM, halfX = halfY * aspect;
    const double r = radiusM;
    return std::clamp((std::min(r, halfX) / halfX) * (std::min(r, halfY) / halfY), kMinImportance, 1.0);
  }
  if (distanceM <= radiusM) return 1.0;  // the camera stands in its light
  // The sphere's angular radius against the image's half extents (tan of half the fields of view).
  const double sinR = radiusM / distanceM;
  const double tanR = sinR / std::sqrt(std::max(1e-12, 1.0 - sinR * sinR));
  const double tanY = std::tan(0.5 * camera.fovYRad), tanX = tanY * aspect;
  if (glm::dot(toLight / distanceM, camera.forward()) < -sinR) return kMinImportance;  // wholly behind
  const double share = (std::min(tanR, tanX) / tanX) * (std::min(tanR, tanY) / tanY);
  return std::clamp(share, kMinImportance, 1.0);
}

}  // namespace penumbra::core
