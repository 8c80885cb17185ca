#include "report/ReportCharts.h"

#include <penumbra/Registry.h>

#include <fmt/format.h>

#include <algorithm>
#include <map>
#include <set>

namespace penumbra::report {
namespace {

constexpr Marker kMarkers[] = {Marker::Circle, Marker::Square, Marker::Triangle, Marker::Diamond};
// Projection legend entries show the marker only: in a grey no filter colour uses (paletteColor).
constexpr const char* kProjectionLegendColor = "#777";

template <class T>
size_t indexIn(const std::vector<T>& list, const T& value) {
  return static_cast<size_t>(std::find(list.begin(), list.end(), value) - list.begin());
}

std::string timeText(const TimeStats& t) {
  return fmt::format("{:.3g} ms (p10–p90 {:.3g}–{:.3g})", t.median, t.p10, t.p90);
}

// Legend entries for the filters and projections that occur in `rows`, in registry order.
std::vector<LegendEntry> legendFor(const BenchResults& results, const std::vector<size_t>& rows, bool projections) {
  std::set<std::string> filters, projs;
  for (const size_t i : rows) {
    filters.insert(results.rows[i].config.filter);
    projs.insert(results.rows[i].config.projection);
  }
  std::vector<LegendEntry> legend;
  for (const std::string& f : filterIds())
    if (filters.contains(f)) legend.push_back({f, filterColor(f), Marker::Circle, false, false});
  if (projections)
    for (const std::string& p : projectionIds())
      if (projs.contains(p)) legend.push_back({"▸ " + p, kProjectionLegendColor, projectionMarker(p), false, false});
  return legend;
}

}  // namespace

std::string lightParams(const BenchRow& row) {
  std::string out;
  for (const auto& [k, v] : row.config.params)
    if (k.starts_with("light.")) out += (out.empty() ? "" : ";") + k + "=" + v;
  return out;
}

std::string techniqueParams(const BenchRow& row) {
  std::string out;
  for (const auto& [k, v] : row.config.params)
    if (!k.starts_with("light.")) out += (out.empty() ? "" : ";") + k + "=" + v;
  return out;
}

std::string rowLabel(const BenchRow& row) {
  const std::string params = techniqueParams(row);
  return fmt::format("{} · {}{}", row.config.filter, row.config.projection, params.empty() ? "" : " · " + params);
}

std::string filterColor(const std::string& filterId) { return paletteColor(indexIn(filterIds(), filterId)); }

Marker projectionMarker(const std::string& projectionId) {
  return kMarkers[indexIn(projectionIds(), projectionId) % std::size(kMarkers)];
}

std::vector<QualityCostChart> qualityCostCharts(const BenchResults& results) {
  // Scenes in run order; per scene the rows at its own light, else at its first light.
  std::vector<std::string> scenes;
  std::map<std::string, std::string> lightOf;
  for (const BenchRow& r : results.rows) {
    if (indexIn(scenes, r.config.scene) == scenes.size()) {
      scenes.push_back(r.config.scene);
      lightOf[r.config.scene] = lightParams(r);
    }
    if (lightParams(r).empty()) lightOf[r.config.scene] = "";
  }
  std::vector<QualityCostChart> charts;
  for (const std::string& scene : scenes) {
    QualityCostChart q;
    q.scene = scene;
    q.light = lightOf[scene];
    std::vector<size_t> rows;
    for (size_t i = 0; i < results.rows.size(); ++i)
      if (results.rows[i].config.scene == scene && lightParams(results.rows[i]) == q.light) rows.push_back(i);
    std::vector<double> x, y;
    for (const size_t i : rows) {
      x.push_back(results.rows[i].time(kCostPass).median);
      y.push_back(results.rows[i].metrics.rmse);
    }
    for (const size_t k : paretoFront(x, y)) q.frontRows.push_back(rows[k]);
    Chart& c = q.chart;
    c.title = fmt::format("{}{}: error against cost", scene, q.light.empty() ? "" : " (" + q.light + ")");
    c.xLabel = fmt::format("{} pass, median ms (log scale)", kCostPass);
    c.yLabel = "RMSE of V against the reference";
    c.logX = true;
    std::map<std::pair<std::string, std::string>, ChartSeries> series;  // by filter and projection
    for (const size_t i : rows) {
      const BenchRow& r = results.rows[i];
      ChartSeries& s = series[{r.config.filter, r.config.projection}];
      s.color = filterColor(r.config.filter);
      s.marker = projectionMarker(r.config.projection);
      const bool front = std::find(q.frontRows.begin(), q.frontRows.end(), i) != q.frontRows.end();
      s.points.push_back({r.time(kCostPass).median, r.metrics.rmse, std::numeric_limits<double>::quiet_NaN(),
                          std::numeric_limits<double>::quiet_NaN(),
                          fmt::format("{}: {} {}, RMSE {:.4f}{}", rowLabel(r), kCostPass, timeText(r.time(kCostPass)),
                                      r.metrics.rmse, front ? " (Pareto front)" : ""),
                          front});
    }
    for (auto& [key, s] : series) c.series.push_back(std::move(s));
    for (const size_t i : q.frontRows)
      c.front.emplace_back(results.rows[i].time(kCostPass).median, results.rows[i].metrics.rmse);
    c.legend = legendFor(results, rows, true);
    c.legend.push_back({"Pareto front", kFrontColor, Marker::Circle, true, true});
    charts.push_back(std::move(q));
  }
  return charts;
}

std::vector<LightSizeCharts> lightSizeCharts(const BenchResults& results) {
  // Technique = scene, projection, filter and its non-light parameters; light size varies. One
  // curve per plan: its points ran one after the other (BenchPlan.h), so they share the
  // machine's load; a point from another plan (the matrix's own light) may not.
  struct Key {
    std::string plan, scene, projection, filter, params;
    auto operator<=>(const Key&) const = default;
  };
  std::map<Key, std::vector<size_t>> groups;
  std::vector<Key> order;
  for (size_t i = 0; i < results.rows.size(); ++i) {
    const BenchRow& r = results.rows[i];
    const Key k{r.config.plan, r.config.scene, r.config.projection, r.config.filter, techniqueParams(r)};
    if (!groups.contains(k)) order.push_back(k);
    groups[k].push_back(i);
  }
  std::vector<LightSizeCharts> out;
  for (const Key& k : order) {
    std::set<float> sizes;
    for (const size_t i : groups[k]) sizes.insert(results.rows[i].lightSize);
    if (sizes.size() < 2) continue;
    auto it = std::find_if(out.begin(), out.end(), [&](const LightSizeCharts& l) { return l.scene == k.scene && l.projection == k.projection; });
    if (it == out.end()) {
      LightSizeCharts l;
      l.scene = k.scene;
      l.projection = k.projection;
      const std::string where = fmt::format("{}, --projection {}", k.scene, k.projection);
      const std::string xLabel = "light size (spot: sphere radius in m; sun: angular radius in rad)";
      l.cost.title = fmt::format("{}: {} pass time against light size", where, kCostPass);
      l.cost.xLabel = l.error.xLabel = xLabel;
      l.cost.yLabel = "median ms (log scale; bars: p10–p90)";
      l.cost.logY = true;
      l.error.title = fmt::format("{}: error against light size", where);
      l.error.yLabel = "RMSE of V against the reference";
      out.push_back(std::move(l));
      it = std::prev(out.end());
    }
    ChartSeries cost{.color = filterColor(k.filter), .marker = projectionMarker(k.projection), .connect = true, .points = {}};
    ChartSeries error = cost;
    for (const size_t i : groups[k]) {
      const BenchRow& r = results.rows[i];
      const TimeStats t = r.time(kCostPass);
      const std::string tip = fmt::format("{} at light size {}: {} {}, RMSE {:.4f}", rowLabel(r), r.lightSize, kCostPass, timeText(t), r.metrics.rmse);
      cost.points.push_back({r.lightSize, t.median, t.p10, t.p90, tip, false});
      error.points.push_back({r.lightSize, r.metrics.rmse, std::numeric_limits<double>::quiet_NaN(),
                              std::numeric_limits<double>::quiet_NaN(), tip, false});
    }
    it->cost.series.push_back(std::move(cost));
    it->error.series.push_back(std::move(error));
    const std::string label = k.params.empty() ? k.filter : k.filter + " " + k.params;
    it->cost.legend.push_back({label, filterColor(k.filter), projectionMarker(k.projection), false, false});
    it->error.legend.push_back(it->cost.legend.back());
  }
  return out;
}

}  // namespace penumbra::report
