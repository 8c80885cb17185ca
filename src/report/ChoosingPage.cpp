#include "report/ChoosingPage.h"

#include "report/ReportCharts.h"
#include "report/SvgChart.h"

#include <penumbra/Files.h>
#include <penumbra/Registry.h>

#include <fmt/format.h>

#include <algorithm>
#include <set>

namespace penumbra::report {
namespace {

std::string joinSet(const std::vector<std::string>& items) {
  std::string out;
  for (const std::string& i : items) out += (out.empty() ? "" : ",") + i;
  return out;
}

template <class T>
void addOnce(std::vector<T>& list, const T& value) {
  if (std::find(list.begin(), list.end(), value) == list.end()) list.push_back(value);
}

std::string machineText(const BenchResults& r) {
  const MachineInfo& m = r.machine;
  return fmt::format("{} ({}), times by {}; CPU {} ({} hardware threads, load {:.2f} → {:.2f}); {}; {}", m.glRenderer,
                     m.glVersion, m.clock, m.cpu, m.hardwareThreads, m.loadStart, m.loadEnd, m.os, m.date);
}

std::string settingsText(const BenchResults& r) {
  const BenchSettings& s = r.settings;
  return fmt::format("{}×{} pixels, shadow maps {}, {} reference samples per pixel, {} timed frames after {} warm-up",
                     s.width, s.height, s.shadowMapSize ? fmt::format("{}²", *s.shadowMapSize) : "at each scene's own size",
                     s.referenceSamples, s.timedFrames, s.warmupFrames);
}

// What decides and what is left out, as sentences (plain text; `code` in backquotes).
std::vector<std::string> ruleText() {
  return {
      fmt::format("Candidates: every configuration the run measured on the situation's scene at its own light. Where "
                  "casters may move, techniques with one-off work are left out: a baked distance field (sdf) is only "
                  "valid while nothing moves, and rebaking takes seconds, not a frame."),
      fmt::format("Acceptable: an error at most {:g}× the lowest error any candidate reached in that situation.",
                  kAcceptableErrorFactor),
      "Cheapest acceptable: the acceptable candidate with the lowest whole cost (shadow + prefilter + visibility per "
      "frame, median over the timed frames).",
      "Balanced: the acceptable candidate with the lowest whole cost × error, the knee of the front on log-log axes.",
      "Best: the candidate with the lowest error, whatever it costs.",
      "Every pick lies on the situation's whole-cost Pareto front: a configuration both cheaper and more accurate would "
      "be acceptable too and win all three orders. Memory (what the technique keeps on the GPU) is shown, not ranked."};
}

std::string htmlCode(std::string_view text) {
  // `a` → <code>a</code>, the rest escaped.
  std::string out;
  bool inCode = false;
  size_t start = 0;
  for (size_t i = 0; i <= text.size(); ++i) {
    if (i < text.size() && text[i] != '`') continue;
    out += escapeXml(text.substr(start, i - start));
    if (i < text.size()) out += inCode ? "</code>" : "<code>";
    inCode = !inCode;
    start = i + 1;
  }
  return out;
}

std::string errorText(double v) { return fmt::format("{:.4f}", v); }
// The metric shown beside the one that decides.
ErrorMetric otherMetric(ErrorMetric m) { return m == ErrorMetric::Rmse ? ErrorMetric::PenumbraRmse : ErrorMetric::Rmse; }
std::string costText(const TimeStats& t) {
  return fmt::format("{} ({}–{})", numberText(t.median), numberText(t.p10), numberText(t.p90));
}
std::string oneOffCell(const BenchRow& r) {
  return r.oneOff.empty() ? "—" : fmt::format("{} s bake (static casters only)", numberText(r.oneOffSeconds()));
}

std::vector<size_t> pickedRows(const SituationPicks& p) {
  std::vector<size_t> rows;
  for (const Budget b : kBudgets)
    if (const std::optional<size_t> i = p.pick(b)) addOnce(rows, *i);
  return rows;
}

std::string acceptableText(const BenchResults& r, const SituationPicks& p) {
  size_t acceptable = 0;
  for (const size_t i : p.candidates) acceptable += situationError(p.situation->metric, r.rows[i]) <= p.acceptableError;
  return fmt::format("Acceptable: {} ≤ {:g} × {:.4f} = {:.4f} ({} of {} candidates)", metricName(p.situation->metric),
                     kAcceptableErrorFactor, p.bestError, p.acceptableError, acceptable, p.candidates.size());
}

// Per filter, its candidate with the lowest error in the situation (default parameters only).
std::optional<size_t> bestOfFilter(const BenchResults& r, const SituationPicks& p, const std::string& filter) {
  std::optional<size_t> best;
  for (const size_t i : p.candidates) {
    const BenchRow& row = r.rows[i];
    if (row.config.filter != filter || !techniqueParams(row).empty()) continue;
    if (!best || situationError(p.situation->metric, row) < situationError(p.situation->metric, r.rows[*best])) best = i;
  }
  return best;
}

}  // namespace

std::string benchCommand(const BenchResults& results, const std::vector<size_t>& rows) {
  std::vector<std::string> scenes, projections, filters;
  std::vector<std::pair<std::string, std::string>> params;
  for (const size_t i : rows) {
    const BenchConfig& c = results.rows[i].config;
    addOnce(scenes, c.scene);
    addOnce(projections, c.projection);
    addOnce(filters, c.filter);
    for (const auto& kv : c.params) addOnce(params, kv);
  }
  const BenchSettings& s = results.settings;
  std::string cmd = fmt::format("penumbra bench --scenes {} --projections {} --filters {}", joinSet(scenes),
                                joinSet(projections), joinSet(filters));
  for (const auto& [key, value] : params) cmd += fmt::format(" --sweep {}={}:{}:1", key, value, value);
  cmd += fmt::format(" --size {}x{} --samples {} --frames {} --warmup {}", s.width, s.height, s.referenceSamples,
                     s.timedFrames, s.warmupFrames);
  if (s.shadowMapSize) cmd += fmt::format(" --shadow-map {}", *s.shadowMapSize);
  if (!s.camera.empty()) cmd += " --camera " + s.camera;
  return cmd;
}

std::string recommendationHtml(const BenchResults& r, const std::vector<SituationPicks>& picks) {
  std::string h = "<h2 id=\"choose\">Which technique? Recommendations from this run</h2>\n<p>For each situation, the "
                  "configuration this run measured as the cheapest acceptable, the balanced and the best choice. "
                  "Measured on " + escapeXml(machineText(r)) + ", at " + escapeXml(settingsText(r)) +
                  ". The same table is written as a Markdown page (docs/choosing.md in the repository).</p>\n<ul>";
  for (const std::string& line : ruleText()) h += "<li>" + htmlCode(line) + "</li>";
  h += "</ul>\n";
  for (const SituationPicks& p : picks) {
    const Situation& s = *p.situation;
    h += fmt::format("<h3 id=\"choose-{}\">{}</h3>\n<p>Scene <code>{}</code>: {}", s.id, escapeXml(s.title), s.scene,
                     escapeXml(s.why));
    if (p.candidates.empty()) {
      h += fmt::format(" <b>Not measured in this run</b>: add <code>--scenes {}</code>.</p>\n", s.scene);
      continue;
    }
    h += fmt::format(" {}.</p>\n", escapeXml(acceptableText(r, p)));
    h += fmt::format("<div class=\"wide\"><table class=\"picks\"><tr><th class=\"l\">budget</th><th class=\"l\">configuration</th>"
                     "<th>{} (decides)</th><th>{}</th><th>whole cost ms <small>p10–p90</small></th><th>memory MiB</th>"
                     "<th class=\"l\">one-off</th><th class=\"l cmd\">reproduce the error (and one frame's times)</th></tr>\n",
                     metricName(s.metric), metricName(otherMetric(s.metric)));
    for (const Budget b : kBudgets) {
      const BenchRow& row = r.rows[*p.pick(b)];
      h += fmt::format("<tr><th class=\"l\">{}</th><td class=\"l wrap\"><b>{}</b></td><td>{}</td><td>{}</td><td>{}</td>"
                       "<td>{}</td><td class=\"l wrap\">{}</td><td class=\"l cmd\"><code>{}</code></td></tr>\n",
                       budgetName(b), escapeXml(rowLabel(row)), errorText(situationError(s.metric, row)),
                       errorText(situationError(otherMetric(s.metric), row)), costText(row.shadowCost), numberText(row.memoryMiB()),
                       escapeXml(oneOffCell(row)),
                       escapeXml(compareCommand(r, row)));
    }
    h += "</table></div>\n";
    h += "<p class=\"note\">Re-time these three: <code>" + escapeXml(benchCommand(r, pickedRows(p))) + "</code>";
    if (!p.excluded.empty()) {
      h += ". Left out: ";
      for (size_t k = 0; k < p.excluded.size(); ++k) h += (k ? "; " : "") + escapeXml(p.excluded[k]);
    }
    h += ".</p>\n";
  }
  return h;
}

std::string choosingMarkdown(const BenchResults& r, const std::vector<SituationPicks>& picks, const std::string& reportLink) {
  std::string m = "# Which shadow technique?\n\n";
  m += "<!-- Written by `penumbra bench` from its own results: do not edit by hand (docs/bench.md says how to "
       "regenerate it). -->\n\n";
  m += fmt::format(
      "For four situations users bring, the configuration that [the bench]({}) measured as the **cheapest acceptable**, "
      "the **balanced** and the **best** choice: its error against the ray-traced reference, its whole cost per frame, "
      "the GPU memory it keeps, and the `penumbra compare` command that reproduces its error (and prints one frame's "
      "pass times). This page is written by `penumbra bench`; every number comes from that run.\n\n",
      reportLink);
  m += fmt::format("- Run: `{}`, {}.\n- Machine: {}.\n- Times are this machine's (llvmpipe runs on the CPU): compare them "
                   "with each other, not with a GPU's. Whole cost = shadow + prefilter + visibility passes per frame, the "
                   "median over the timed frames (docs/bench.md, \"What is measured\", says what is counted).\n\n",
                   r.machine.command.empty() ? "penumbra bench" : r.machine.command, settingsText(r), machineText(r));
  m += "## How the picks are made\n\n| situation | scene | error that decides | what the scene stands for |\n|---|---|---|---|\n";
  for (const Situation& s : kSituations)
    m += fmt::format("| [{}](#{}) | `{}` | {} | {} |\n", s.title, s.id, s.scene, metricName(s.metric), s.why);
  m += "\n";
  for (const std::string& line : ruleText()) m += "- " + line + "\n";
  m += "\n";
  for (const SituationPicks& p : picks) {
    const Situation& s = *p.situation;
    m += fmt::format("## {} <a id=\"{}\"></a>\n\nScene `{}`. ", s.title, s.id, s.scene);
    if (p.candidates.empty()) {
      m += fmt::format("**Not measured in this run**: add `--scenes {}`.\n\n", s.scene);
      continue;
    }
    m += acceptableText(r, p) + ".\n\n";
    m += fmt::format("| budget | configuration | {} (decides) | {} | whole cost ms (p10–p90) | memory MiB | one-off | "
                     "reproduce |\n|---|---|---|---|---|---|---|---|\n",
                     metricName(s.metric), metricName(otherMetric(s.metric)));
    for (const Budget b : kBudgets) {
      const BenchRow& row = r.rows[*p.pick(b)];
      m += fmt::format("| {} | **{}** | {} | {} | {} | {} | {} | `{}` |\n", budgetName(b), rowLabel(row),
                       errorText(situationError(s.metric, row)), errorText(situationError(otherMetric(s.metric), row)),
                       costText(row.shadowCost), numberText(row.memoryMiB()), oneOffCell(row), compareCommand(r, row));
    }
    m += "\nRe-time these three: `" + benchCommand(r, pickedRows(p)) + "`.";
    if (!p.excluded.empty()) {
      m += " Left out: ";
      for (size_t k = 0; k < p.excluded.size(); ++k) m += (k ? "; " : "") + p.excluded[k];
      m += ".";
    }
    m += "\n\n";
  }
  // Every filter's own best showing per situation: what the technique pages link to.
  m += "## Every filter at a glance <a id=\"every-filter\"></a>\n\nPer filter and situation, its most accurate "
       "projection in this run (default parameters): the error that decides there · whole cost ms · memory MiB. "
       "✓ = acceptable by the rule above.\n\n| filter |";
  std::string rule = "|---|";
  for (const SituationPicks& p : picks) {
    m += fmt::format(" [{}](#{}) (`{}`) |", p.situation->title, p.situation->id, p.situation->scene);
    rule += "---|";
  }
  m += "\n" + rule + "\n";
  std::set<std::string> measured;
  for (const BenchRow& row : r.rows) measured.insert(row.config.filter);
  for (const std::string& filter : filterIds()) {
    if (!measured.contains(filter)) continue;
    m += fmt::format("| <a id=\"{0}\"></a>{0} |", filter);
    for (const SituationPicks& p : picks) {
      const std::optional<size_t> i = bestOfFilter(r, p, filter);
      if (!i) {
        const bool leftOut = std::any_of(p.excluded.begin(), p.excluded.end(),
                                         [&](const std::string& e) { return e.starts_with(filter + " · "); });
        m += leftOut ? " left out: baked, casters may move |" : " — |";
        continue;
      }
      const BenchRow& row = r.rows[*i];
      const double e = situationError(p.situation->metric, row);
      m += fmt::format(" {:.4f} · {} ms · {} MiB ({}){} |", e, numberText(row.shadowCost.median), numberText(row.memoryMiB()),
                       row.config.projection, e <= p.acceptableError ? " ✓" : "");
    }
    m += "\n";
  }
  return m;
}

void writeChoosingPage(const std::filesystem::path& path, const std::filesystem::path& reportDir, const BenchResults& results) {
  const std::filesystem::path folder = std::filesystem::absolute(path).parent_path();
  const std::string link =
      std::filesystem::absolute(reportDir / "report.html").lexically_normal().lexically_relative(folder).generic_string();
  writeTextFile(path, choosingMarkdown(results, recommend(results), link));
}

}  // namespace penumbra::report
