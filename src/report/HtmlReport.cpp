#include "report/HtmlReport.h"

#include "bench/ScaleBench.h"

#include "report/ChoosingPage.h"
#include "bench/Recommendation.h"
#include "report/ReportCharts.h"
#include "report/SvgChart.h"

#include <penumbra/Files.h>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace penumbra::report {
namespace {

const char* const kStyle = R"(
body { font: 14px/1.45 system-ui, sans-serif; margin: 24px auto; max-width: 1280px; padding: 0 16px; color: #222; }
h1 { font-size: 24px; } h2 { margin-top: 36px; border-bottom: 1px solid #ccc; } h3 { margin-top: 24px; }
table { border-collapse: collapse; margin: 8px 0 16px; }
th, td { border: 1px solid #ddd; padding: 3px 7px; text-align: right; vertical-align: top; white-space: nowrap; }
th { background: #f3f3f3; } td.l, th.l { text-align: left; }
td small { color: #777; }
.charts { display: flex; flex-wrap: wrap; gap: 12px; } figure { margin: 0; width: 600px; } figcaption { font-size: 13px; }
.grid td, .grid th { text-align: center; } .grid img { display: block; image-rendering: pixelated; }
.note { color: #555; } .front { font-weight: bold; } .swatch { display: inline-block; width: 12px; height: 12px; vertical-align: middle; }
code { background: #f4f4f4; padding: 1px 4px; } .wide { overflow-x: auto; } td.why { white-space: pre-wrap; max-width: 640px; } td.wrap { white-space: normal; }
td.cmd, th.cmd { white-space: normal; min-width: 300px; max-width: 480px; }
/* the recommendation: headings and names wrap so that the command column fits a 1280-pixel window */
table.picks th { white-space: normal; } table.picks td.wrap { min-width: 120px; }
.quick { background: #fff3cd; border: 1px solid #e0c060; padding: 8px 12px; font-weight: bold; }
)";

// Image-grid thumbnails are shown at most this wide (pixels); a click opens the full picture. A
// smaller picture (--quick's 96×64) is shown at least this wide, its pixels enlarged.
constexpr int kThumbWidthPx = 320;
constexpr int kMinThumbWidthPx = 240;

std::string esc(std::string_view s) { return escapeXml(s); }


std::string ms(const TimeStats& t) {
  return fmt::format("{} <small>{}–{}</small>", numberText(t.median), numberText(t.p10), numberText(t.p90));
}

// Passes run the same way whatever the technique (docs/design.md): left out of the ratio table.
bool techniqueIndependent(const std::string& pass) { return pass == "gbuffer" || pass == "lit"; }

std::vector<std::string> scenesInOrder(const BenchResults& r) {
  std::vector<std::string> scenes;
  for (const BenchRow& row : r.rows)
    if (std::find(scenes.begin(), scenes.end(), row.config.scene) == scenes.end()) scenes.push_back(row.config.scene);
  return scenes;
}

std::string header(const BenchResults& r) {
  const MachineInfo& m = r.machine;
  const BenchSettings& s = r.settings;
  size_t refused = 0, failed = 0;
  for (const SkippedConfig& k : r.skipped) (k.failed ? failed : refused)++;
  std::string h = fmt::format("<h1>Penumbra bench: shadow techniques, quality against whole cost and memory{}</h1>\n",
                              s.quick ? " — a quick look, not for decisions" : "");
  h += fmt::format(
      "<p>{} configurations measured, {} refused as unsupported pairs, {} failed; {:.0f} s in all. Raw data: "
      "<a href=\"results.csv\">results.csv</a>, <a href=\"results.json\">results.json</a>.</p>\n",
      r.rows.size(), refused, failed, r.seconds);
  h += fmt::format(
      "<p>Each configuration: {} warm-up frame(s) (the first compiles the shaders), then up to {} timed frames "
      "(at most {:g} s); times are per-pass medians with the p10–p90 spread. Images {}×{}, shadow maps {}, "
      "reference {} light samples per pixel (Embree). Clock: <b>{}</b> on <b>{}</b>; compare times only as ratios "
      "within one run. Load average {:.2f} at the start, {:.2f} at the end, on {} hardware threads: other work on "
      "the machine inflates times and makes them drift.</p>\n",
      s.warmupFrames, s.timedFrames, s.maxSecondsPerConfig, s.width, s.height,
      s.shadowMapSize ? fmt::format("{}²", *s.shadowMapSize) : std::string("at each scene's own size"), s.referenceSamples,
      esc(m.clock), esc(m.glRenderer), m.loadStart, m.loadEnd, m.hardwareThreads);
  if (!s.camera.empty())
    h += fmt::format("<p>Camera: <code>--camera {}</code> (position : target : vertical field of view in degrees), "
                     "not the scene's own.</p>\n",
                     esc(s.camera));
  h += "<p class=\"note\">Contents: <a href=\"#choose\">which technique?</a> · <a href=\"#quality\">1. quality vs whole cost and memory</a> · <a href=\"#light\">2. cost vs light "
       "size</a> · <a href=\"#lights\">2b. cost vs number of lights</a> · <a href=\"#grid\">3. image grid</a> · <a href=\"#tables\">4. tables</a> · "
       "the building blocks' micro-benchmarks: <a href=\"micro.html\">micro.html</a></p>\n";
  return h;
}

std::string frontText(const BenchResults& r, const std::vector<size_t>& front, bool memory, ErrorMetric metric) {
  std::string h;
  for (size_t k = 0; k < front.size(); ++k) {
    const BenchRow& row = r.rows[front[k]];
    h += fmt::format("{}<span class=\"front\">{}</span> ({}, {} {:.4f})", k ? " → " : "", esc(rowLabel(row)),
                     memory ? numberText(row.memoryMiB()) + " MiB" : numberText(row.shadowCost.median) + " ms",
                     metricName(metric), motionError(metric, row));
  }
  return h;
}

// "its picks: cheapest acceptable = balanced: pcss · uniform; best: …" for a situation's scene.
std::string picksText(const BenchResults& r, const std::vector<SituationPicks>& picks, const std::string& scene) {
  for (const SituationPicks& p : picks) {
    if (scene != p.situation->scene || !p.cheapestAcceptable) continue;
    std::string h = fmt::format(" The <a href=\"#choose-{}\">recommendation</a>'s picks, by the costs of their interleaved rounds: ",
                                p.situation->id);
    std::vector<size_t> done;
    for (const Budget b : kBudgets) {
      const size_t i = *p.pick(b);
      if (std::find(done.begin(), done.end(), i) != done.end()) continue;
      done.push_back(i);
      std::string budgets;
      for (const Budget o : p.budgetsOf(i)) budgets += (budgets.empty() ? "" : " = ") + std::string(budgetName(o));
      h += fmt::format("{}{}: <b>{}</b>", done.size() > 1 ? "; " : "", budgets, esc(rowLabel(r.rows[i])));
    }
    return h + ".";
  }
  return "";
}

std::string qualitySection(const BenchResults& r) {
  std::string h = fmt::format(
      "<h2 id=\"quality\">1. Quality against whole cost and memory</h2>\n<p>One point per configuration: the error that "
      "decides in the scene's situation (penumbra RMSE on <code>pen</code>, colour RMSE on <code>glass</code>, RMSE elsewhere: pixels that face the light), "
      "the mean over the frames it was scored on (its still frame and, for a situation's scene, the scene's animation or "
      "a camera walk), against its <b>whole cost</b>: per frame the {} passes added up, then the median over the timed "
      "frames (the G-buffer and lit passes are the same for every technique and left out). Beside it, the same errors "
      "against the <b>GPU memory</b> the technique keeps (every map, moment, mip, summed-area and pyramid texture and "
      "buffer: docs/bench.md). Colour and shape: filter; the letter beside a point: its projection; ringed and joined by "
      "the dashed staircase: the Pareto front (no other configuration is both cheaper and more accurate). sdf's bake is "
      "in no frame: its points carry it as a one-off cost, valid only while the casters do not move. Below each pair, a "
      "bar per configuration shows where its time goes. Hover for numbers (and flicker).</p>\n",
      kCostName);
  const std::vector<SituationPicks> picks = recommend(r);
  for (const SceneCharts& q : sceneCharts(r)) {
    const ErrorMetric metric = q.rows.empty() ? ErrorMetric::Rmse : sceneMetric(q.scene);
    h += fmt::format("<h3>{}</h3>\n<div class=\"charts\">\n", esc(q.scene));
    h += "<figure>" + svgChart(q.cost) + "<figcaption>Whole-cost Pareto front: " + frontText(r, q.costFront, false, metric) +
         "." + picksText(r, picks, q.scene) + "</figcaption></figure>\n";
    h += "<figure>" + svgChart(q.memory) + "<figcaption>Memory Pareto front: " + frontText(r, q.memoryFront, true, metric) +
         "</figcaption></figure>\n</div>\n";
    h += "<div class=\"wide\">" + svgBarChart(q.passes) + "</div>\n";
  }
  return h;
}

std::string lightSection(const BenchResults& r) {
  std::string h = "<h2 id=\"light\">2. Cost against light size</h2>\n";
  const std::vector<LightSizeCharts> charts = lightSizeCharts(r);
  if (charts.empty())
    return h + "<p class=\"note\">This run swept no light size; add <code>--sweep light.size=0.02:0.2:5</code>.</p>\n";
  h += "<p>A claim from the course these techniques are taught from (GAMES202, Lingqi Yan, UC Santa Barbara, lecture 4 "
       "&ldquo;Real-Time Shadows 2&rdquo;): PCSS's blocker search and filter look at every texel inside a region, so "
       "&ldquo;softer &rarr; larger filtering region &rarr; slower&rdquo;; the pre-filtered methods (vssm, msm-soft: one "
       "summed-area-table lookup per region) and the distance field (sdf) pay the same whatever the size. Here it is "
       "tested on the whole cost. With fixed tap counts (pcss.blockerSamples, pcss.filterSamples) PCSS does the same "
       "arithmetic at every size: only the spread of its taps over the map grows, and whether that costs time depends on "
       "the machine's texture caches. Every technique run at two or more light sizes in one plan is drawn; bars are the "
       "p10–p90 spread over the timed frames.</p>\n";
  for (const LightSizeCharts& l : charts) h += "<div class=\"charts\">" + svgChart(l.cost) + svgChart(l.error) + "</div>\n";
  return h;
}

std::string lightCountSection(const BenchResults& r) {
  std::string h = "<h2 id=\"lights\">2b. Cost against the number of lights</h2>\n";
  const std::vector<LightCountCharts> charts = lightCountCharts(r);
  if (charts.empty())
    return h + fmt::format("<p class=\"note\">This run swept no light count; add <code>--scenes {} --sweep "
                           "light.count=1,2,4,8</code>.</p>\n", kLightCountScene);
  h += "<p>Every shadowed light renders its own maps, prefilters them and runs its own visibility pass, so the whole "
       "cost grows with the number of lights; a flat curve here means each light costs the same whatever the "
       "number. A point light renders six cube faces, a spot one map, so where the first light is a point and the "
       "others mix both (night), the step from one light to two is the spot's single map, not shared work. Memory is every light's maps and tables. The error is of all lights together, each light weighted by its "
       "unshadowed light at the pixel (<a href=\"../lights.md\">lights.md</a>).</p>\n";
  for (const LightCountCharts& l : charts)
    h += "<div class=\"charts\">" + svgChart(l.costPerLight) + svgChart(l.memoryPerLight) + svgChart(l.error) + "</div>\n";
  return h;
}

std::string gridSection(const BenchResults& r) {
  std::string h = fmt::format(
      "<h2 id=\"grid\">3. Images</h2>\n<p>Per scene, each filter with the scene's own projection: the technique, the "
      "same frame lit with the reference V<sub>ref</sub>, and the error heatmap over the technique's image: "
      "<span class=\"swatch\" style=\"background:rgb({},{},{})\"></span> leak (too bright), "
      "<span class=\"swatch\" style=\"background:rgb({},{},{})\"></span> over-dark; colour strength ∝ |ΔV|.</p>\n",
      kLeakColor[0], kLeakColor[1], kLeakColor[2], kOverDarkColor[0], kOverDarkColor[1], kOverDarkColor[2]);
  for (const std::string& scene : scenesInOrder(r)) {
    std::string rows;
    for (const BenchRow& row : r.rows) {
      if (row.config.scene != scene || row.imagePath.empty()) continue;
      // Thumbnails kMinThumbWidthPx to kThumbWidthPx wide; each opens the full-size picture.
      const int thumbW = std::clamp(row.width, kMinThumbWidthPx, kThumbWidthPx);
      const int thumbH = static_cast<int>(std::lround(static_cast<double>(row.height) * thumbW / std::max(row.width, 1)));
      auto img = [&](const std::string& path, const std::string& alt) {
        return fmt::format("<td><a href=\"{0}\"><img src=\"{0}\" width=\"{1}\" height=\"{2}\" alt=\"{3}\" title=\"{3}: "
                           "click for {4}×{5}\"></a></td>",
                           esc(path), thumbW, thumbH, esc(alt), row.width, row.height);
      };
      rows += fmt::format("<tr><td class=\"l\"><b>{}</b><br>{}{}<br>RMSE {:.4f}{}<br>leak {:.2f} % (umbra {:.2f} %)<br>over-dark {:.2f} %"
                          "<br>whole cost {} ms<br>memory {} MiB{}{}</td>",
                          esc(row.config.filter), esc(row.config.projection),
                          techniqueParams(row).empty() ? "" : "<br><small>" + esc(techniqueParams(row)) + "</small>", row.metrics.rmse,
                          row.colour ? fmt::format("<br>colour RMSE {:.4f}", row.colour->rmse) : "", row.metrics.leakPct,
                          row.metrics.umbraLeakPct, row.metrics.overDarkPct, numberText(row.shadowCost.median), numberText(row.memoryMiB()),
                          row.oneOff.empty() ? "" : fmt::format("<br>+ {:.3g} s bake<br><small>(static casters only)</small>",
                                                                row.oneOffSeconds()),
                          row.pagesDrawnMean() ? fmt::format("<br>pages drawn {} a frame<br><small>(mean over the motion)</small>",
                                                             numberText(*row.pagesDrawnMean()))
                                               : "");
      rows += img(row.imagePath, row.config.filter + " " + row.config.projection) +
              img(row.referencePath, "reference") + img(row.heatmapPath, "error heatmap") + "</tr>\n";
    }
    if (rows.empty()) continue;
    h += fmt::format("<h3>{}</h3>\n<table class=\"grid\"><tr><th class=\"l\">configuration</th><th>technique</th>"
                     "<th>reference</th><th>heatmap</th></tr>\n{}</table>\n", esc(scene), rows);
  }
  return h;
}

std::string microTable(const BenchResults& r) {
  std::string h = "<h3>Building blocks against their baselines</h3>\n";
  if (r.micro.empty()) return h + "<p class=\"note\">No micro-benchmarks in this run.</p>\n";
  h += "<p class=\"note\">Each row next to its baseline, interleaved round by round; the ratio is taken within a round "
       "(median, p10–p90 over the rounds). Prefilters against a plain copy of the same texture; each filter's visibility "
       "pass against its minimal lookup kernel: the pass's overhead over its own arithmetic (docs/bench.md).</p>\n";
  h += "<table><tr><th class=\"l\">what</th><th class=\"l\">its baseline</th><th class=\"l\">timed</th>"
       "<th>median ms <small>p10–p90</small></th><th>× its baseline <small>p10–p90</small></th></tr>\n";
  for (const MicroResult& m : r.micro) {
    const std::string baseline = m.baseline.empty() ? "—" : esc(m.baseline);
    if (!m.error.empty()) {
      h += fmt::format("<tr><td class=\"l\">{}</td><td class=\"l wrap\">{}</td><td class=\"l wrap\">{}</td>"
                       "<td colspan=\"2\" class=\"l wrap\">failed: {}</td></tr>\n",
                       esc(m.name), baseline, esc(m.description), esc(m.error));
      continue;
    }
    const std::string ratio =
        m.ratio ? fmt::format("{:.2f} × <small>{:.2f}–{:.2f}</small>", m.ratio->median, m.ratio->p10, m.ratio->p90) : "—";
    h += fmt::format("<tr><td class=\"l\">{}</td><td class=\"l wrap\">{}</td><td class=\"l wrap\">{}</td><td>{}</td><td>{}</td></tr>\n",
                     esc(m.name), baseline, esc(m.description), ms(m.ms), ratio);
  }
  return h + "</table>\n";
}

std::string ratioTable(const BenchResults& r) {
  std::string h = "<h3>Cost ratios</h3>\n";
  std::string rows;
  std::vector<std::string> passes = r.passNames();
  std::erase_if(passes, techniqueIndependent);
  for (const auto& [num, den] : kCostRatioPairs) {
    std::string pairRows;
    std::vector<std::vector<double>> ratios(passes.size());  // per pass, over the pair's rows
    for (const BenchRow& a : r.rows) {
      if (a.config.filter != num || !techniqueParams(a).empty()) continue;
      for (const BenchRow& b : r.rows) {
        if (b.config.filter != den || b.config.scene != a.config.scene || b.config.projection != a.config.projection ||
            lightParams(b) != lightParams(a) || !techniqueParams(b).empty())
          continue;
        const std::string light = lightParams(a).empty() ? "scene's own" : lightParams(a);
        pairRows += fmt::format("<tr><td class=\"l\">{} / {}</td><td class=\"l\">{}</td><td class=\"l\">{}</td><td class=\"l\">{}</td>",
                                num, den, esc(a.config.scene), esc(a.config.projection), esc(light));
        for (size_t i = 0; i < passes.size(); ++i) {
          const double x = a.time(passes[i]).median, y = b.time(passes[i]).median;
          if (y > 0) ratios[i].push_back(x / y);
          pairRows += y > 0 ? fmt::format("<td>{:.2f}</td>", x / y) : "<td>—</td>";
        }
        pairRows += "</tr>\n";
      }
    }
    if (pairRows.empty()) continue;
    // The pair's summary first: the median ratio over every scene, projection and light.
    rows += fmt::format("<tr class=\"front\"><td class=\"l\">{} / {}</td><td class=\"l\" colspan=\"3\">median of all "
                        "rows below</td>", num, den);
    for (const std::vector<double>& v : ratios)
      rows += v.empty() ? "<td>—</td>" : fmt::format("<td>{:.2f}</td>", timeStats(v).median);
    rows += "</tr>\n" + pairRows;
  }
  if (rows.empty()) {
    std::string names;
    for (const auto& [num, den] : kCostRatioPairs) names += fmt::format("{}{}/{}", names.empty() ? "" : ", ", num, den);
    return h + "<p class=\"note\">No pair (" + names + ") ran on the same scene and projection in this run.</p>\n";
  }
  h += "<p>Median time of the first filter divided by the second's, per pass that depends on the technique, same "
       "scene, projection and light (default parameters).</p>\n"
       "<table><tr><th class=\"l\">ratio</th><th class=\"l\">scene</th><th class=\"l\">projection</th><th class=\"l\">light</th>";
  for (const std::string& p : passes) h += "<th>" + esc(p) + "</th>";
  return h + "</tr>\n" + rows + "</table>\n";
}

std::string resultsTables(const BenchResults& r) {
  const std::vector<std::string> passes = r.passNames();
  std::string h = "<h3>All configurations</h3>\n<p>Times: median ms, p10–p90 in small print. Whole cost: shadow + "
                  "prefilter + visibility per frame, its median and p10–p90 over the frames. Memory: what the technique "
                  "keeps on the GPU. One-off: work done once and kept while the casters do not move. Sorted by whole "
                  "cost per scene.</p>\n";
  for (const std::string& scene : scenesInOrder(r)) {
    std::vector<const BenchRow*> rows;
    for (const BenchRow& row : r.rows)
      if (row.config.scene == scene) rows.push_back(&row);
    std::stable_sort(rows.begin(), rows.end(), [](const BenchRow* a, const BenchRow* b) {
      return a->shadowCost.median < b->shadowCost.median;
    });
    h += "<h4>" + esc(scene) + "</h4>\n<div class=\"wide\"><table><tr><th class=\"l\">filter</th><th class=\"l\">projection</th>"
         "<th class=\"l\">params</th><th>light size</th><th>frames</th><th>whole cost</th><th>memory MiB</th>"
         "<th title=\"valid for static casters only\">one-off s</th>";
    for (const std::string& p : passes) h += "<th>" + esc(p) + "</th>";
    const bool colour = std::any_of(rows.begin(), rows.end(), [](const BenchRow* row) { return row->colour.has_value(); });
    h += std::string(colour ? "<th title=\"V against the RGB reference, over red, green and blue (a one-channel V counts as "
                              "grey)\">colour RMSE</th>" : "") +
         "<th>RMSE</th><th>penumbra RMSE</th><th>leak %</th><th title=\"leaking pixels inside the reference's umbra: light "
         "bleeding rather than an edge's shape\">umbra leak %</th><th>over-dark %</th></tr>\n";
    for (const BenchRow* row : rows) {
      h += fmt::format("<tr><td class=\"l\">{}</td><td class=\"l\">{}</td><td class=\"l\">{}</td><td>{:g}</td><td>{}</td>",
                       esc(row->config.filter), esc(row->config.projection), esc(row->config.paramsText()),
                       row->lightSize, row->frames);
      h += fmt::format("<td><b>{}</b></td><td>{:.3g}</td><td>{}</td>", ms(row->shadowCost), row->memoryMiB(),
                       row->oneOff.empty() ? "—" : fmt::format("{:.3g}", row->oneOffSeconds()));
      for (const std::string& p : passes) h += "<td>" + ms(row->time(p)) + "</td>";
      if (colour) h += row->colour ? fmt::format("<td>{:.4f}</td>", row->colour->rmse) : "<td>—</td>";
      h += fmt::format("<td>{:.4f}</td><td>{:.4f}</td><td>{:.2f}</td><td>{:.2f}</td><td>{:.2f}</td></tr>\n",
                       row->metrics.rmse, row->metrics.penumbraRmse, row->metrics.leakPct, row->metrics.umbraLeakPct,
                       row->metrics.overDarkPct);
    }
    h += "</table></div>\n";
  }
  return h;
}

std::string skippedTable(const BenchResults& r) {
  std::string h = "<h3>Skipped configurations</h3>\n";
  if (r.skipped.empty()) return h + "<p class=\"note\">None: every configuration ran.</p>\n";
  h += "<table><tr><th class=\"l\">scene</th><th class=\"l\">projection</th><th class=\"l\">filter</th>"
       "<th class=\"l\">params</th><th class=\"l\">why</th></tr>\n";
  for (const SkippedConfig& k : r.skipped)
    h += fmt::format("<tr><td class=\"l\">{}</td><td class=\"l\">{}</td><td class=\"l\">{}</td><td class=\"l\">{}</td>"
                     "<td class=\"l why\">{}: {}</td></tr>\n",
                     esc(k.config.scene), esc(k.config.projection), esc(k.config.filter), esc(k.config.paramsText()),
                     k.failed ? "<b>failed</b>" : "refused", esc(k.reason));
  return h + "</table>\n";
}

std::string machineTable(const BenchResults& r) {
  const MachineInfo& m = r.machine;
  std::string h = "<h3>Machine</h3>\n<table>";
  for (const auto& [k, v] : std::vector<std::pair<const char*, std::string>>{
           {"GL_RENDERER", m.glRenderer}, {"GL_VERSION", m.glVersion}, {"GL_VENDOR", m.glVendor},
           {"clock", m.clock}, {"CPU", m.cpu}, {"hardware threads", std::to_string(m.hardwareThreads)},
           {"load average (1 min), start → end", fmt::format("{:.2f} → {:.2f}", m.loadStart, m.loadEnd)},
           {"OS", m.os}, {"date (UTC)", m.date}, {"command", m.command}})
    h += fmt::format("<tr><th class=\"l\">{}</th><td class=\"l\">{}</td></tr>", k, esc(v));
  return h + "</table>\n";
}

// A page's head with the report's style, up to the opened <body>.
std::string pageHead(const std::string& title) {
  return "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">"
         "<meta name=\"viewport\" content=\"width=device-width\"><title>" + esc(title) +
         "</title><link rel=\"icon\" href=\"data:,\"><style>" + kStyle + "</style></head><body>\n";
}

}  // namespace

std::string htmlReport(const BenchResults& r) {
  std::string h = pageHead("Penumbra bench");
  h += header(r) + recommendationHtml(r, recommend(r)) + qualitySection(r) + lightSection(r) + lightCountSection(r) + gridSection(r);
  h += "<h2 id=\"tables\">4. Tables</h2>\n" + scaleSectionHtml(r.scale, r.machine) + ratioTable(r) + resultsTables(r) + skippedTable(r) +
       machineTable(r);
  return h + "</body></html>\n";
}

std::string microHtml(const BenchResults& r) {
  std::string h = pageHead("Penumbra bench: building blocks");
  h += "<h1>Penumbra bench: the building blocks against their baselines</h1>\n";
  h += fmt::format("<p>What the tool's own parts cost, each against the simplest work of its kind: for the people who work "
                   "on Penumbra, not for choosing a technique (that is <a href=\"report.html\">the report</a>). Clock "
                   "<b>{}</b> on <b>{}</b>, {} rounds; docs/bench.md, \"Micro-benchmarks\", says what each row times.</p>\n",
                   esc(r.machine.clock), esc(r.machine.glRenderer), r.settings.microRepetitions);
  return h + microTable(r) + machineTable(r) + "</body></html>\n";
}

void writeHtmlReport(const std::filesystem::path& dir, const BenchResults& results) {
  writeTextFile(dir / "report.html", htmlReport(results));
  writeTextFile(dir / "micro.html", microHtml(results));
}

}  // namespace penumbra::report
