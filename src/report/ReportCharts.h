#pragma once
// The report's charts, built from the results (HtmlReport.cpp lays them out):
//  1. per scene: its deciding error (its situation's metric, Recommendation.h, mean over the
//     frames it was scored on; RMSE for other scenes) against the whole cost (BenchRow::shadowCost:
//     shadow + prefilter + visibility per frame) and against the memory the technique keeps, one
//     point per configuration, colour and shape = filter, a letter = projection, each Pareto
//     front marked (the recommendation's own front on the cost chart); and a
//     stacked bar per configuration showing where its time goes, pass by pass;
//  2. whole cost (and error) against light size, for every technique run at several light sizes;
//  3. per-light cost and memory, and error, against the number of lights (the light-count plan).
#include "bench/BenchResults.h"
#include "bench/Recommendation.h"
#include "report/SvgChart.h"

#include <string>
#include <vector>

namespace penumbra::report {

/// What the cost axis is, in words (BenchRow::shadowCost).
inline constexpr const char* kCostName = "shadow + prefilter + visibility";
/// Colours of the passes in the stacked bars (Okabe–Ito, apart from the filter palette's order).
inline constexpr std::pair<const char*, const char*> kPassColors[] = {
    {"projection", "#F0E442"}, {"shadow", "#56B4E9"}, {"prefilter", "#E69F00"}, {"visibility", "#009E73"}, {"contact", "#CC79A7"}};

/// A scene's charts at one light (its own, else the first it was run with).
struct SceneCharts {
  std::string scene, light;        ///< the group: scene and light parameters ("" = its own)
  std::vector<size_t> rows;        ///< indices into results.rows
  Chart cost, memory;              ///< RMSE against whole cost; RMSE against memory
  std::vector<size_t> costFront;   ///< the whole-cost Pareto front, ascending cost
  std::vector<size_t> memoryFront; ///< the memory Pareto front, ascending memory
  BarChart passes;                 ///< per configuration, its passes' medians stacked, cheapest first
};

/// One entry per scene, in run order.
std::vector<SceneCharts> sceneCharts(const BenchResults& results);

struct LightSizeCharts {
  std::string scene, projection;
  Chart cost, error;
};

/// For each scene and projection, every technique (filter + parameters) run at two or more
/// light sizes: its whole cost (median, p10–p90 bars) and its RMSE against the light size.
/// Empty when the run swept no light size.
std::vector<LightSizeCharts> lightSizeCharts(const BenchResults& results);

/// The light-count plan's charts: per light, the whole cost and the memory, and the combined
/// RMSE, against the number of shadowed lights; one curve per filter.
struct LightCountCharts {
  std::string scene;
  Chart costPerLight, memoryPerLight, error;
};

/// Empty when the run has no rows of the light-count plan (kLightCountPlan) at two counts or more.
std::vector<LightCountCharts> lightCountCharts(const BenchResults& results);

/// Stable colour and marker of a filter (by registry order) across charts: filters are told apart
/// by shape as well as colour.
std::string filterColor(const std::string& filterId);
Marker filterMarker(const std::string& filterId);
/// The error a scene's charts plot: its situation's metric (Recommendation.h), else RMSE.
ErrorMetric sceneMetric(const std::string& scene);
/// A projection's tag beside each point: the shortest prefix of its id that no other registered
/// projection starts with ("u", "c", "p", "t").
std::string projectionTag(const std::string& projectionId);

}  // namespace penumbra::report
