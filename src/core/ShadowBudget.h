#pragma once
// One texel budget for every light's maps (Shadows' mapBudgetTexels): each light's map size
// follows its importance on screen, never above what it asks for. Pure C++: unit-tested.
#include <penumbra/Scene.h>

#include <cstdint>
#include <span>
#include <vector>

namespace penumbra::core {

/// What one light asks of the budget.
struct BudgetRequest {
  int requestedMapSize = 0;  ///< texels per side it would have without a budget
  int views = 1;             ///< maps of that size it renders (cascades, cube faces)
  double importance = 1.0;   ///< its weight, > 0
};

/// Smallest map side a light is given, and the step sizes are rounded down to.
inline constexpr int kMinBudgetMapSize = 16;

/// Map sizes, one per request: requested sizes when budgetTexels is 0 or they all fit; otherwise
/// side² ∝ importance (the same texels per unit of importance for every light not capped at its
/// request), rounded down to multiples of kMinBudgetMapSize, so that Σ views·side² <= budget.
/// When even kMinBudgetMapSize for every light exceeds the budget, every light gets that.
std::vector<int> allocateMapSizes(std::span<const BudgetRequest> requests, int64_t budgetTexels);

/// A light's importance for the budget: the share of the camera's image its influence covers.
/// A sun covers the whole image (1); a spot or point light, the sphere of its range around it
/// (without a range: the scene's bounds it can reach), projected with the camera's field of view,
/// in [kMinImportance, 1].
double lightImportance(const Light& light, const Camera& camera, float aspect, const Aabb& sceneBounds);

/// The least importance a light keeps (one behind the camera still needs a map).
inline constexpr double kMinImportance = 0.01;

}  // namespace penumbra::core
