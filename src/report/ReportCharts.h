#pragma once
// The report's charts, built from the results (HtmlReport.cpp lays them out):
//  1. quality vs cost: RMSE against the visibility pass's median time, one point per
//     configuration, colour = filter, marker = projection, the Pareto front marked;
//  2. cost (and error) against light size, for every technique run at several light sizes.
#include "report/BenchResults.h"
#include "report/SvgChart.h"

#include <string>
#include <vector>

namespace penumbra::report {

/// The pass whose time is the cost axis: the only pass that differs between filters (docs/design.md).
inline constexpr const char* kCostPass = "visibility";

/// A row's light.* parameters as text ("" when it uses the scene's own light).
std::string lightParams(const BenchRow& row);
/// A row's parameters other than light.* as text.
std::string techniqueParams(const BenchRow& row);
/// "pcss · csm" plus the technique parameters when there are any.
std::string rowLabel(const BenchRow& row);

struct QualityCostChart {
  std::string scene, light;     ///< the group: scene and light parameters ("" = its own)
  Chart chart;
  std::vector<size_t> frontRows;  ///< indices into results.rows, ascending cost
};

/// One chart per scene, over its rows at the scene's own light (or, if it has none, at the first
/// light it was run with).
std::vector<QualityCostChart> qualityCostCharts(const BenchResults& results);

struct LightSizeCharts {
  std::string scene, projection;
  Chart cost, error;
};

/// For each scene and projection, every technique (filter + parameters) run at two or more
/// light sizes: its visibility-pass time (median, p10–p90 bars) and its RMSE against the
/// light size. Empty when the run swept no light size.
std::vector<LightSizeCharts> lightSizeCharts(const BenchResults& results);

/// Stable colour of a filter and marker of a projection (by registry order) across charts.
std::string filterColor(const std::string& filterId);
Marker projectionMarker(const std::string& projectionId);

}  // namespace penumbra::report
