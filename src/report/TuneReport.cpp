#include "report/TuneReport.h"

#include "report/SvgChart.h"

#include <penumbra/Technique.h>
#include <penumbra/Files.h>

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>

namespace penumbra::report {
namespace {

// Integral values below this are written without a fraction (tap counts, texels).
constexpr double kExactIntegerLimit = 1e9;

// A value as the scene file takes it: a number when it reads as one, else a choice name.
nlohmann::json sceneValue(const std::string& text) {
  double v = 0.0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (ec != std::errc() || end != text.data() + text.size()) return text;
  if (v == std::round(v) && std::fabs(v) < kExactIntegerLimit) return static_cast<long long>(v);
  return v;
}

std::string technique(const TuneRow& r) { return r.filter + " · " + r.projection; }

std::string viewText(const TuneRow& r) { return r.camera.empty() ? r.scene : r.scene + " from " + r.camera; }

std::string paramsText(const TuneRow& r) {
  std::string out;
  for (const auto& [k, v] : r.params) out += (out.empty() ? "" : " ") + k + "=" + v;
  return out.empty() ? "(defaults)" : out;
}

// The cost the search ranked by, as the chart's x.
double rankedCost(const TuneRow& r, TuneCost c) { return r.point(c).costMs; }

std::string mapText(const TuneRow& r) {
  return r.budgetTexels > 0 ? fmt::format("{} (budget {} texels)", r.grantedMapSize, r.budgetTexels) : std::to_string(r.mapSize);
}

std::string tooltip(const TuneRow& r, TuneObjective o) {
  return fmt::format("{} map {}: {} {:.4g}, {:.3g} ms, {:.4g} Mops, {:.1f} MiB\n{}", technique(r), mapText(r), objectiveKey(o),
                     r.error, r.costMs, r.workM, r.memoryMiB, paramsText(r));
}

const char* const kStyle = R"(
body { font: 14px/1.45 system-ui, sans-serif; margin: 24px auto; max-width: 1280px; padding: 0 16px; color: #222; }
table { border-collapse: collapse; margin: 8px 0 16px; }
th, td { border: 1px solid #ddd; padding: 3px 7px; text-align: right; vertical-align: top; }
th { background: #f3f3f3; } td.l, th.l { text-align: left; } code { background: #f4f4f4; padding: 1px 4px; }
tr.rec { font-weight: bold; } .note { color: #555; }
)";

std::string rowHtml(const TuneRow& r, const std::string& what, bool recommended) {
  const std::string ratio =
      r.rounds > 0 ? fmt::format("{:.2f} <small>{:.2f}–{:.2f}</small>", r.costRatio.median, r.costRatio.p10, r.costRatio.p90) : "—";
  return fmt::format(
      "<tr{}><td class=\"l\">{}</td><td class=\"l\">{}</td><td>{}</td><td class=\"l\"><code>{}</code></td><td>{:.4f}</td>"
      "<td>{:.4f}</td><td>{:.2f}</td><td>{:.3f}</td><td>{:.3f}</td><td>{}</td><td>{:.3f} <small>{:.3f}–{:.3f}</small></td>"
      "<td>{}</td><td>{:.4g}</td><td>{:.1f}</td></tr>\n",
      recommended ? " class=\"rec\"" : "", escapeXml(what), escapeXml(technique(r)), escapeXml(mapText(r)), escapeXml(paramsText(r)),
      r.metrics.rmse, r.metrics.penumbraRmse, r.metrics.leakPct, r.metrics.umbraLeakPct, r.metrics.acnePct,
      r.withinBars ? "✓" : "<b>beyond</b>", r.costMs, r.costP10Ms, r.costP90Ms, ratio, r.workM, r.memoryMiB);
}

std::string tuneHtml(const TuneResults& res) {
  const TuneObjective o = res.request.objective;
  const TuneCost c = res.request.cost;
  Chart chart{.title = fmt::format("{} against {} on {}", objectiveKey(o),
                                   c == TuneCost::Model ? "modelled work" : "whole shadow cost", tuneViewsText(res.request)),
              .xLabel = c == TuneCost::Model ? std::string("memory written + taps read, millions per frame (--cost model)")
                                             : fmt::format("shadow + prefilter + visibility, ms per frame ({})", res.machine.clock),
              .yLabel = objectiveKey(o), .logX = true, .logY = o != TuneObjective::Leak, .width = 900, .height = 520, .series = {}, .front = {},
              .legend = {}};
  std::vector<std::string> names;
  for (const TuneRow& r : res.explored)
    if (std::find(names.begin(), names.end(), technique(r)) == names.end()) names.push_back(technique(r));
  // Each configuration once: at its confirmed cost where it was confirmed, else as explored. The
  // front is drawn over every point shown (within the bars and the memory budget), so that no
  // point shown is both cheaper and more accurate than the front.
  const auto sameConfig = [](const TuneRow& a, const TuneRow& b) {
    return a.filter == b.filter && a.projection == b.projection && a.params == b.params && a.mapSize == b.mapSize &&
           a.budgetTexels == b.budgetTexels;
  };
  std::vector<const TuneRow*> shown;
  for (const TuneRow& r : res.confirmed) shown.push_back(&r);
  for (const TuneRow& r : res.explored)
    if (std::none_of(res.confirmed.begin(), res.confirmed.end(), [&](const TuneRow& c) { return sameConfig(c, r); }))
      shown.push_back(&r);
  const auto isConfirmed = [&](const TuneRow* r) { return r >= res.confirmed.data() && r < res.confirmed.data() + res.confirmed.size(); };
  for (size_t n = 0; n < names.size(); ++n) {
    ChartSeries explored{.color = paletteColor(n), .marker = Marker::Circle, .connect = false, .points = {}};
    ChartSeries confirmed{.color = paletteColor(n), .marker = Marker::Diamond, .connect = false, .points = {}};
    ChartSeries defaults{.color = paletteColor(n), .marker = Marker::Square, .connect = false, .points = {}};
    ChartSeries beyond{.color = paletteColor(n), .marker = Marker::Cross, .connect = false, .points = {}};
    for (const TuneRow* r : shown) {
      if (technique(*r) != names[n]) continue;
      const bool conf = isConfirmed(r);
      const std::string tip = (r->isDefault ? "default: " : conf ? "confirmed: " : "") + tooltip(*r, o);
      ChartPoint pt{.x = rankedCost(*r, c), .y = r->error, .tooltip = tip,
                    .emphasised = conf && res.recommended == static_cast<size_t>(r - res.confirmed.data())};
      if (conf && r->rounds > 0)  // the confirmed cost's spread
        pt.tooltip += fmt::format("\ncost p10–p90 {:.3g}–{:.3g} ms over {} interleaved rounds", r->costP10Ms, r->costP90Ms, r->rounds);
      (!r->withinBars ? beyond : r->isDefault ? defaults : conf ? confirmed : explored).points.push_back(pt);
    }
    for (ChartSeries* series : {&explored, &confirmed, &defaults, &beyond}) chart.series.push_back(std::move(*series));
    chart.legend.push_back({.label = names[n], .color = paletteColor(n), .marker = Marker::Circle});
  }
  std::vector<TunePoint> pts;
  for (const TuneRow* r : shown) {
    TunePoint p = r->point(c);
    p.costMs = rankedCost(*r, c);
    pts.push_back(p);
  }
  for (const size_t i : tuneFront(pts, res.request.budget.memoryMiB)) chart.front.emplace_back(pts[i].costMs, pts[i].error);
  chart.legend.push_back({.label = "explored", .color = "#777", .marker = Marker::Circle});
  chart.legend.push_back({.label = "confirmed (ring: the pick)", .color = "#777", .marker = Marker::Diamond});
  chart.legend.push_back({.label = "default", .color = "#777", .marker = Marker::Square});
  chart.legend.push_back({.label = "beyond the acne/leak bars", .color = "#777", .marker = Marker::Cross});
  chart.legend.push_back({.label = "Pareto front of all shown", .color = kFrontColor, .line = true, .dashed = true});

  std::string h = "<!doctype html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>penumbra tune</title><style>";
  h += kStyle;
  h += "</style></head><body>\n";
  h += fmt::format("<h1>penumbra tune: {} on {}</h1>\n", escapeXml(objectiveKey(o)), escapeXml(tuneViewsText(res.request)));
  h += fmt::format("<p class=\"note\">{} on {}{}, {}; {}×{} pixels, reference {} samples per pixel; budget {:.4g} {}{}; "
                   "{} configurations measured ({} read back from an earlier run) in {:.0f} s. Raw data: "
                   "<a href=\"tune.json\">tune.json</a>.</p>\n",
                   escapeXml(res.machine.glRenderer), escapeXml(res.machine.cpu),
                   // A run read back whole from an earlier one timed nothing: no clock to name.
                   res.machine.clock.empty() ? std::string() : " (" + escapeXml(res.machine.clock) + ")",
                   escapeXml(res.machine.date), res.request.settings.width, res.request.settings.height,
                   res.request.settings.referenceSamples, res.budget, c == TuneCost::Model ? "Mops (--cost model)" : "ms",
                   res.request.budget.memoryMiB ? fmt::format(", {:.1f} MiB", *res.request.budget.memoryMiB) : "",
                   res.evaluations + res.resumed, res.resumed, res.seconds);
  if (res.recommended) {
    const TuneRow& r = res.confirmed[*res.recommended];
    h += fmt::format("<h2>Recommended</h2>\n<p><code>{}</code></p>\n<pre>{}</pre>\n", escapeXml(r.command),
                     escapeXml(tuneSceneSnippet(r)));
  } else {
    h += "<h2>Recommended</h2>\n<p>No configuration fits the budget.</p>\n";
  }
  h += svgChart(chart);
  if (res.request.views.size() > 1) {
    h += fmt::format("\n<h2>Views</h2>\n<p class=\"note\">Each row's error and cost are the {} of its views'.</p>\n"
                     "<table><tr><th class=\"l\"></th><th class=\"l\">view</th><th>{}</th><th>RMSE</th><th>cost ms</th>"
                     "<th class=\"l\">compare</th></tr>\n",
                     aggregateKey(res.request.aggregate), objectiveKey(o));
    for (const auto& [what, row] : {std::pair<const char*, const TuneRow*>{"recommended", res.recommended ? &res.confirmed[*res.recommended] : nullptr},
                                    std::pair<const char*, const TuneRow*>{"default", tuneDefaultFor(res)}})
      if (row)
        for (const TuneRow& v : row->views)
          h += fmt::format("<tr><td class=\"l\">{}</td><td class=\"l\">{}</td><td>{:.4g}</td><td>{:.4f}</td><td>{:.3f}</td>"
                           "<td class=\"l\"><code>{}</code></td></tr>\n",
                           what, escapeXml(viewText(v)), v.error, v.metrics.rmse, v.costMs, escapeXml(v.command));
    h += "</table>\n";
  }
  h += fmt::format(
      "\n<h2>Confirmed configurations</h2>\n<p class=\"note\">Errors are the full-size measurements (the frames are "
      "deterministic). {} Bars: acne at most {:g} % (or the default's own) and umbra leak at most the default's + {:g} "
      "points{}.</p>\n",
      c == TuneCost::Model
          ? std::string("Costs are modelled work (--cost model); the milliseconds are shown, not ranked.")
          : fmt::format("Costs: each confirmed configuration and every technique's default timed again in {} interleaved "
                        "rounds (one frame of each per round, so a round's times share the machine's load): median and "
                        "p10–p90, and the per-round ratio to the budget's default. A configuration fits the budget when "
                        "the upper end of its spread does ({}): never over the budget within the noise.",
                        kConfirmRounds, res.request.budget.costMs ? "its p90 cost ≤ --budget-ms" : "its ratio's p90 ≤ 1"),
      kMaxAcnePct, kUmbraLeakSlackPct, res.request.allowArtifacts ? " — lifted by --allow-artifacts" : "");
  h += "<table><tr><th class=\"l\"></th><th class=\"l\">technique</th><th>map</th>"
       "<th class=\"l\">--set</th><th>RMSE</th><th>penumbra RMSE</th><th>leak %</th><th>umbra leak %</th><th>acne %</th>"
       "<th>bars</th><th>cost ms <small>p10–p90</small></th><th>× budget's default <small>p10–p90</small></th>"
       "<th>work Mops</th><th>MiB</th></tr>\n";
  for (size_t i = 0; i < res.confirmed.size(); ++i) {
    const bool onFront = std::find(res.front.begin(), res.front.end(), i) != res.front.end();
    const std::string what = res.recommended == i ? "recommended" : res.confirmed[i].isDefault ? "default"
                                                                  : onFront                       ? "front"
                                                                                                  : "";
    h += rowHtml(res.confirmed[i], what, res.recommended == i);
  }
  h += "</table>\n</body></html>\n";
  return h;
}

}  // namespace

std::string tuneViewsText(const TuneRequest& request) {
  std::string out;
  for (const TuneView& v : request.views) {
    TuneRow r;
    r.scene = v.scene;
    r.camera = v.camera;
    out += (out.empty() ? "" : ", ") + viewText(r);
  }
  return out;
}

std::string tuneSetLine(const TuneRow& r) {
  std::string line = fmt::format("--projection {} --filter {} --shadow-map {}", r.projection, filterArgument(r.filter), r.mapSize);
  if (r.budgetTexels > 0) line += fmt::format(" --shadow-budget {}", r.budgetTexels);
  for (const auto& [k, v] : r.params) line += fmt::format(" --set {}={}", k, v);
  return line;
}

std::string tuneSceneSnippet(const TuneRow& r) {
  nlohmann::ordered_json params = nlohmann::ordered_json::object();
  for (const auto& [k, v] : r.params) params[k] = sceneValue(v);
  // Under a budget, the side the maps got: one light's maps at that side hold what the budget gave.
  nlohmann::ordered_json shadow = {{"projection", r.projection}, {"filter", r.filter},
                                   {"mapSize", r.budgetTexels > 0 ? r.grantedMapSize : r.mapSize}};
  if (!r.params.empty()) shadow["params"] = params;
  return "\"shadow\": " + shadow.dump(2);
}

nlohmann::json tuneRowJson(const TuneRow& r, TuneObjective objective) {
  nlohmann::json params = nlohmann::json::object();
  for (const auto& [k, v] : r.params) params[k] = v;
  nlohmann::json views = nlohmann::json::array();
  for (const TuneRow& v : r.views)
    views.push_back({{"scene", v.scene}, {"camera", v.camera}, {"error", v.error}, {"rmse", v.metrics.rmse},
                     {"penumbra_rmse", v.metrics.penumbraRmse}, {"leak_pct", v.metrics.leakPct}, {"acne_pct", v.metrics.acnePct},
                     {"shadow_cost_ms", v.costMs}, {"work_mops", v.workM}, {"shadow_memory_mb", v.memoryMiB}, {"command", v.command}});
  return {{"filter", r.filter}, {"projection", r.projection}, {"params", params}, {"shadow_map", r.mapSize},
          {"shadow_budget", r.budgetTexels > 0 ? nlohmann::json(r.budgetTexels) : nlohmann::json()},
          {"granted_map", r.grantedMapSize}, {"work_mops", r.workM}, {"views", views},
          {"width", r.width}, {"height", r.height}, {"frames", r.frames}, {"objective", objectiveKey(objective)},
          {"error", r.error}, {"rmse", r.metrics.rmse}, {"penumbra_rmse", r.metrics.penumbraRmse},
          {"leak_pct", r.metrics.leakPct}, {"overdark_pct", r.metrics.overDarkPct},
          {"umbra_leak_pct", r.metrics.umbraLeakPct}, {"acne_pct", r.metrics.acnePct}, {"shadow_cost_ms", r.costMs},
          {"shadow_cost_p10_ms", r.costP10Ms}, {"shadow_cost_p90_ms", r.costP90Ms}, {"shadow_memory_mb", r.memoryMiB},
          {"command", r.command}, {"set", tuneSetLine(r)}, {"scene_snippet", tuneSceneSnippet(r)},
          {"within_bars", r.withinBars}, {"cost_rounds", r.rounds},
          {"cost_ratio", r.rounds > 0 ? nlohmann::json{{"median", r.costRatio.median}, {"p10", r.costRatio.p10}, {"p90", r.costRatio.p90}}
                                      : nlohmann::json()},
          {"budget_cost_ms", r.rounds > 0 ? nlohmann::json(r.budgetCostMs) : nlohmann::json()}};
}

const TuneRow* tuneDefaultFor(const TuneResults& res) {
  if (res.defaults.empty()) return nullptr;
  if (res.recommended) {
    const TuneRow& rec = res.confirmed[*res.recommended];
    for (const size_t d : res.defaults)
      if (res.confirmed[d].filter == rec.filter && res.confirmed[d].projection == rec.projection) return &res.confirmed[d];
  }
  return &res.confirmed[res.defaults.front()];
}

nlohmann::json tuneJson(const TuneResults& res) {
  const TuneObjective o = res.request.objective;
  nlohmann::json j;
  j["scene"] = res.request.views.front().scene;
  j["views"] = nlohmann::json::array();
  for (const TuneView& v : res.request.views) j["views"].push_back({{"scene", v.scene}, {"camera", v.camera}});
  j["aggregate"] = aggregateKey(res.request.aggregate);
  j["cost"] = costKey(res.request.cost);
  j["objective"] = objectiveKey(o);
  j["recommended"] = res.recommended ? tuneRowJson(res.confirmed[*res.recommended], o) : nlohmann::json();
  j["default"] = tuneDefaultFor(res) ? tuneRowJson(*tuneDefaultFor(res), o) : nlohmann::json();
  j["defaults"] = nlohmann::json::array();
  for (const size_t d : res.defaults) j["defaults"].push_back(tuneRowJson(res.confirmed[d], o));
  j["front"] = nlohmann::json::array();
  for (const size_t i : res.front) j["front"].push_back(tuneRowJson(res.confirmed[i], o));
  j["explored"] = nlohmann::json::array();
  for (const TuneRow& r : res.explored) j["explored"].push_back(tuneRowJson(r, o));
  // The cost budget in the unit the search ranked by.
  j[res.request.cost == TuneCost::Model ? "budget_mops" : "budget_ms"] = res.budget;
  j["budget_mb"] = res.request.budget.memoryMiB ? nlohmann::json(*res.request.budget.memoryMiB) : nlohmann::json();
  j["max_error"] = res.request.budget.maxError ? nlohmann::json(*res.request.budget.maxError) : nlohmann::json();
  j["allow_artifacts"] = res.request.allowArtifacts;
  j["bars"] = {{"max_acne_pct", kMaxAcnePct}, {"umbra_leak_slack_pct", kUmbraLeakSlackPct}};
  j["confirm_rounds"] = res.request.cost == TuneCost::Measured ? kConfirmRounds : 0;
  j["width"] = res.request.settings.width;
  j["height"] = res.request.settings.height;
  j["samples"] = res.request.settings.referenceSamples;
  j["evaluations"] = res.evaluations;
  j["resumed"] = res.resumed;
  j["seconds"] = res.seconds;
  j["gl_renderer"] = res.machine.glRenderer;
  j["gl_version"] = res.machine.glVersion;
  j["cpu"] = res.machine.cpu;
  j["clock"] = res.machine.clock;
  j["hardware_threads"] = res.machine.hardwareThreads;
  j["load_start"] = res.machine.loadStart;
  j["load_end"] = res.machine.loadEnd;
  j["date"] = res.machine.date;
  j["command"] = res.machine.command;
  return j;
}

void writeTuneOutputs(const std::filesystem::path& dir, const TuneResults& results) {
  writeTextFile(dir / "tune.json", tuneJson(results).dump(2) + "\n");
  writeTextFile(dir / "tune.html", tuneHtml(results));
}

}  // namespace penumbra::report
