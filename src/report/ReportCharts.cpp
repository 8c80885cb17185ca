#include "report/ReportCharts.h"

#include "bench/Recommendation.h"
#include "techniques/Registry.h"

#include <fmt/format.h>

#include <algorithm>
#include <functional>
#include <limits>
#include <map>
#include <optional>
#include <set>

namespace penumbra::report {
namespace {

// A filter's marker with its colour: two filters of like colours differ in shape too.
constexpr Marker kMarkers[] = {Marker::Circle, Marker::Square, Marker::Triangle, Marker::Diamond, Marker::TriangleDown, Marker::Star};

template <class T>
size_t indexIn(const std::vector<T>& list, const T& value) {
  return static_cast<size_t>(std::find(list.begin(), list.end(), value) - list.begin());
}

std::string timeText(const TimeStats& t) {
  return fmt::format("{} ms (p10–p90 {}–{})", numberText(t.median), numberText(t.p10), numberText(t.p90));
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
    if (filters.contains(f)) legend.push_back({f, filterColor(f), filterMarker(f), false, false});
  if (projections)
    for (const std::string& p : projectionIds())
      if (projs.contains(p)) legend.push_back({.label = "projection " + p, .color = "#333", .tag = projectionTag(p)});
  return legend;
}

}  // namespace

std::string filterColor(const std::string& filterId) { return paletteColor(indexIn(filterIds(), filterId)); }

Marker filterMarker(const std::string& filterId) { return kMarkers[indexIn(filterIds(), filterId) % std::size(kMarkers)]; }

std::string projectionTag(const std::string& projectionId) {
  // The shortest prefix no other registered projection starts with.
  const std::vector<std::string> ids = projectionIds();
  for (size_t n = 1; n < projectionId.size(); ++n) {
    const std::string prefix = projectionId.substr(0, n);
    if (std::none_of(ids.begin(), ids.end(), [&](const std::string& o) { return o != projectionId && o.starts_with(prefix); }))
      return prefix;
  }
  return projectionId;
}

ErrorMetric sceneMetric(const std::string& scene) {
  for (const Situation& s : kSituations)
    if (scene == s.scene) return s.metric;
  return ErrorMetric::Rmse;
}

namespace {

// The scene's deciding error (its situation's metric, the mean over the row's frames) against `x`
// (cost or memory) over the rows, one series per filter and projection, the front ringed;
// returns the front (rows, ascending x).
std::vector<size_t> errorChart(const BenchResults& results, const std::vector<size_t>& rows, Chart& c,
                               const std::function<double(const BenchRow&)>& x, const std::string& xText) {
  const ErrorMetric metric = rows.empty() ? ErrorMetric::Rmse : sceneMetric(results.rows[rows.front()].config.scene);
  const auto y = [&](const BenchRow& r) { return motionError(metric, r); };
  const bool moving = std::any_of(rows.begin(), rows.end(), [&](size_t i) { return results.rows[i].motion.has_value(); });
  std::vector<double> xs, ys;
  for (const size_t i : rows) {
    xs.push_back(x(results.rows[i]));
    ys.push_back(y(results.rows[i]));
  }
  std::vector<size_t> front;
  for (const size_t k : paretoFront(xs, ys)) front.push_back(rows[k]);
  c.yLabel = fmt::format("{} of V against the reference{}", metricName(metric), moving ? ", mean over the frames" : "");
  c.logX = true;
  std::map<std::pair<std::string, std::string>, ChartSeries> series;  // by filter and projection
  for (const size_t i : rows) {
    const BenchRow& r = results.rows[i];
    ChartSeries& s = series[{r.config.filter, r.config.projection}];
    s.color = filterColor(r.config.filter);
    s.marker = filterMarker(r.config.filter);
    const bool onFront = std::find(front.begin(), front.end(), i) != front.end();
    s.points.push_back({x(r), y(r), std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::quiet_NaN(),
                        fmt::format("{}: {} {}, {:.2f} MiB{}, {} {:.4f}{}{}", rowLabel(r), kCostName, timeText(r.shadowCost),
                                    r.memoryMiB(), oneOffText(r), metricName(metric), y(r),
                                    r.motion ? fmt::format(", flicker {:.3f} %", flickerPct(r)) : "",
                                    onFront ? " (on the " + xText + " front)" : ""),
                        onFront, projectionTag(r.config.projection)});
  }
  for (auto& [key, s] : series) c.series.push_back(std::move(s));
  for (const size_t i : front) c.front.emplace_back(x(results.rows[i]), y(results.rows[i]));
  c.legend = legendFor(results, rows, true);
  c.legend.push_back({"Pareto front", kFrontColor, Marker::Circle, true, true});
  return front;
}

BarChart passBars(const BenchResults& results, std::vector<size_t> rows, const std::string& title) {
  BarChart b;
  b.title = title;
  b.xLabel = "median ms per pass (the black tick: the whole cost's median over frames)";
  for (const auto& [pass, color] : kPassColors) b.legend.push_back({pass, color, Marker::Square, false, false});
  b.legend.push_back({"whole cost (median of the per-frame sum)", "#000", Marker::Square, false, false});
  std::stable_sort(rows.begin(), rows.end(), [&](size_t a, size_t c) {
    return results.rows[a].shadowCost.median < results.rows[c].shadowCost.median;
  });
  for (const size_t i : rows) {
    const BenchRow& r = results.rows[i];
    Bar bar;
    bar.label = rowLabel(r);
    for (const auto& [pass, color] : kPassColors)
      bar.segments.push_back({r.time(pass).median, color, fmt::format("{}: {} {}", rowLabel(r), pass, timeText(r.time(pass)))});
    bar.mark = r.shadowCost.median;
    bar.markTooltip = fmt::format("{}: whole cost {}", rowLabel(r), timeText(r.shadowCost));
    bar.valueText = fmt::format("{} ms · {} MiB{}", numberText(r.shadowCost.median), numberText(r.memoryMiB()),
                                r.oneOff.empty() ? "" : " + bake");
    b.bars.push_back(std::move(bar));
  }
  return b;
}

}  // namespace

std::vector<SceneCharts> sceneCharts(const BenchResults& results) {
  std::vector<std::string> scenes;
  for (const BenchRow& r : results.rows)
    if (indexIn(scenes, r.config.scene) == scenes.size()) scenes.push_back(r.config.scene);
  std::vector<SceneCharts> charts;
  for (const std::string& scene : scenes) {
    SceneCharts q;
    q.scene = scene;
    q.rows = sceneRows(results, scene);
    q.light = q.rows.empty() ? "" : lightParams(results.rows[q.rows.front()]);
    const std::string where = scene + (q.light.empty() ? "" : " (" + q.light + ")");
    q.cost.title = where + ": error against whole cost";
    q.cost.xLabel = fmt::format("{}, median ms per frame (log scale)", kCostName);
    q.costFront = errorChart(results, q.rows, q.cost, [](const BenchRow& r) { return r.shadowCost.median; }, "cost");
    q.memory.title = where + ": error against memory";
    q.memory.xLabel = "GPU memory the technique keeps, MiB (log scale)";
    q.memoryFront = errorChart(results, q.rows, q.memory, [](const BenchRow& r) { return r.memoryMiB(); }, "memory");
    q.passes = passBars(results, q.rows, where + ": where the time goes");
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
      l.cost.title = fmt::format("{}: whole cost against light size", where);
      l.cost.xLabel = l.error.xLabel = xLabel;
      l.cost.yLabel = "shadow + prefilter + visibility, median ms (log; bars: p10–p90)";
      l.cost.logY = true;
      l.error.title = fmt::format("{}: error against light size", where);
      l.error.yLabel = "RMSE of V against the reference";
      out.push_back(std::move(l));
      it = std::prev(out.end());
    }
    ChartSeries cost{.color = filterColor(k.filter), .marker = filterMarker(k.filter), .connect = true, .points = {}};
    ChartSeries error = cost;
    for (const size_t i : groups[k]) {
      const BenchRow& r = results.rows[i];
      const TimeStats t = r.shadowCost;
      const std::string tip = fmt::format("{} at light size {}: whole cost {}, RMSE {:.4f}", rowLabel(r), r.lightSize, timeText(t), r.metrics.rmse);
      cost.points.push_back({r.lightSize, t.median, t.p10, t.p90, tip, false});
      error.points.push_back({r.lightSize, r.metrics.rmse, std::numeric_limits<double>::quiet_NaN(),
                              std::numeric_limits<double>::quiet_NaN(), tip, false});
    }
    it->cost.series.push_back(std::move(cost));
    it->error.series.push_back(std::move(error));
    const std::string label = k.params.empty() ? k.filter : k.filter + " " + k.params;
    it->cost.legend.push_back({label, filterColor(k.filter), filterMarker(k.filter), false, false});
    it->error.legend.push_back(it->cost.legend.back());
  }
  return out;
}

std::vector<LightCountCharts> lightCountCharts(const BenchResults& results) {
  std::map<std::string, std::map<std::string, std::vector<size_t>>> byScene;  // scene → technique → rows
  std::vector<std::string> scenes;
  for (size_t i = 0; i < results.rows.size(); ++i) {
    const BenchRow& r = results.rows[i];
    if (r.config.plan != kLightCountPlan) continue;
    if (!byScene.contains(r.config.scene)) scenes.push_back(r.config.scene);
    byScene[r.config.scene][rowLabel(r)].push_back(i);
  }
  std::vector<LightCountCharts> out;
  for (const std::string& scene : scenes) {
    LightCountCharts l;
    l.scene = scene;
    const std::string xLabel = "shadowed lights (the scene's first N)";
    l.costPerLight.title = fmt::format("{}: whole cost per light", scene);
    l.costPerLight.yLabel = "(" + std::string(kCostName) + ") / lights, median ms (bars: p10–p90)";
    l.memoryPerLight.title = fmt::format("{}: memory per light", scene);
    l.memoryPerLight.yLabel = "GPU memory the technique keeps / lights, MiB";
    l.error.title = fmt::format("{}: error of all lights together", scene);
    l.error.yLabel = "RMSE of the combined V (lights weighted by their light)";
    for (Chart* c : {&l.costPerLight, &l.memoryPerLight, &l.error}) c->xLabel = xLabel;
    for (const auto& [label, rows] : byScene[scene]) {
      std::set<int> counts;
      for (const size_t i : rows) counts.insert(results.rows[i].lights);
      if (counts.size() < 2) continue;
      const BenchRow& first = results.rows[rows.front()];
      ChartSeries cost{.color = filterColor(first.config.filter), .marker = filterMarker(first.config.filter),
                       .connect = true, .points = {}};
      ChartSeries memory = cost, error = cost;
      constexpr double kNone = std::numeric_limits<double>::quiet_NaN();
      for (const size_t i : rows) {
        const BenchRow& r = results.rows[i];
        const double n = r.lights;
        const TimeStats& t = r.shadowCost;
        const std::string tip = fmt::format("{}, {} lights: whole cost {} ({} ms per light), {} MiB, RMSE {:.4f}", label,
                                            r.lights, timeText(t), numberText(t.median / n), numberText(r.memoryMiB()),
                                            r.metrics.rmse);
        cost.points.push_back({n, t.median / n, t.p10 / n, t.p90 / n, tip, false});
        memory.points.push_back({n, r.memoryMiB() / n, kNone, kNone, tip, false});
        error.points.push_back({n, r.metrics.rmse, kNone, kNone, tip, false});
      }
      for (auto [chart, series] : {std::pair{&l.costPerLight, &cost}, {&l.memoryPerLight, &memory}, {&l.error, &error}}) {
        chart->series.push_back(std::move(*series));
        chart->legend.push_back({label, filterColor(first.config.filter), filterMarker(first.config.filter), false, false});
      }
    }
    if (!l.error.series.empty()) out.push_back(std::move(l));
  }
  return out;
}

}  // namespace penumbra::report
