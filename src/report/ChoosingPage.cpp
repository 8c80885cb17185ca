#include "report/ChoosingPage.h"

#include "report/ReportCharts.h"
#include "comparison/SequenceComparison.h"
#include "report/SvgChart.h"

#include <penumbra/Files.h>
#include "techniques/Registry.h"

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

// The whole page's warning when the run was `--quick` (plain text; `code` in backquotes).
std::string quickText(const BenchResults& r) {
  return fmt::format("A quick look, not for decisions: this page comes from `penumbra bench --quick` ({}), sizes chosen "
                     "so that tests run in seconds. Small images and maps and a noisy reference change the errors, and "
                     "so the picks; decide on the full run's page (`penumbra bench`, docs/choosing.md in the repository).",
                     settingsText(r));
}

std::string motionRuleText(const BenchResults& r) {
  return fmt::format("In motion: every candidate is also rendered over {} frames at {:g} fps, its still frame first — the "
                     "scene's own animation where it has one, else a camera walk around its target ({:g}° a second) — and "
                     "each frame is compared with its own reference. The error that decides is the mean over those frames; "
                     "flicker is the share of surface points, followed from one frame to the next, whose V changes by more "
                     "than 0.1 while the reference's changes by less than 0.02 (docs/aliasing.md).",
                     r.settings.motionFrames, kMotionFps, kWalkDegreesPerSecond);
}

// What decides and what is left out, as sentences (plain text; `code` in backquotes).
std::vector<std::string> ruleText(const BenchResults& r) {
  std::vector<std::string> out = {
      "Candidates: every configuration the run measured on the situation's scene at its own light. Where casters may "
      "move, techniques with one-off work are left out: a baked distance field (sdf) is only valid while nothing "
      "moves, and rebaking takes seconds, not a frame."};
  if (r.settings.motionFrames > 1) out.push_back(motionRuleText(r));
  out.push_back(fmt::format("Acceptable: flicker at most {:g} % of the followed points (one in a thousand), and an error at "
                            "most {:g}× the lowest error among the candidates within that flicker limit.",
                            kMaxFlickerPct, kAcceptableErrorFactor));
  if (r.settings.retimeRounds > 0)
    out.push_back(fmt::format(
        "Costs: the acceptable candidates that no other acceptable one beats clearly (cheaper beyond both spreads and "
        "more accurate) are timed again in {} interleaved rounds, one frame of each per round, so that every round's "
        "times share the machine's load; the picks' costs are those rounds' median and p10–p90.",
        r.settings.retimeRounds));
  out.push_back("Cheapest acceptable: the lowest whole cost (shadow + prefilter + visibility per frame). Another whose "
                "cost ratio to it goes either way over the rounds (p10 ≤ 1 ≤ p90) is a tie; the simplest of a tie, the "
                "one that keeps the least GPU memory, is picked.");
  out.push_back("Balanced: the lowest whole cost × error, the knee of the front on log-log axes.");
  out.push_back("Best: the lowest error, whatever it costs. Another whose error ratio to it goes either way over the "
                "frames (p10 ≤ 1 ≤ p90) is a tie; the cheapest of a tie is picked.");
  out.push_back("Memory (what the technique keeps on the GPU) is shown, not ranked. A tie and a configuration that more "
                "than one budget picks are named once.");
  return out;
}

std::string htmlCode(std::string_view text) {
  // `a` → <code>a</code>, **b** → <b>b</b>, the rest escaped.
  std::string out;
  bool inCode = false, inBold = false;
  size_t start = 0;
  for (size_t i = 0; i <= text.size(); ++i) {
    const bool bold = !inCode && text.substr(i, 2) == "**";
    if (i < text.size() && text[i] != '`' && !bold) continue;
    out += escapeXml(text.substr(start, i - start));
    if (i == text.size()) break;
    if (bold) {
      out += inBold ? "</b>" : "<b>";
      inBold = !inBold;
      start = i + 2;
      ++i;
      continue;
    }
    out += inCode ? "</code>" : "<code>";
    inCode = !inCode;
    start = i + 1;
  }
  return out;
}

// A table of text cells (`code` and **bold** marked as in Markdown), written as Markdown or HTML.
struct Table {
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;
  std::vector<bool> left;  ///< per column: left-aligned

  std::string markdown() const {
    std::string m = "|";
    std::string rule = "|";
    for (const std::string& h : header) {
      m += " " + h + " |";
      rule += "---|";
    }
    m += "\n" + rule + "\n";
    for (const auto& row : rows) {
      m += "|";
      for (const std::string& c : row) m += " " + c + " |";
      m += "\n";
    }
    return m;
  }
  std::string html(const std::string& cls) const {
    std::string h = "<div class=\"wide\"><table class=\"" + cls + "\"><tr>";
    for (size_t k = 0; k < header.size(); ++k)
      h += fmt::format("<th{}>{}</th>", k < left.size() && left[k] ? " class=\"l\"" : "", htmlCode(header[k]));
    h += "</tr>\n";
    for (const auto& row : rows) {
      h += "<tr>";
      for (size_t k = 0; k < row.size(); ++k)
        h += fmt::format("<td{}>{}</td>", k < left.size() && left[k] ? " class=\"l wrap\"" : "", htmlCode(row[k]));
      h += "</tr>\n";
    }
    return h + "</table></div>\n";
  }
};

std::string errorText(double v) { return fmt::format("{:.4f}", v); }
// The metric shown beside the one that decides.
ErrorMetric otherMetric(ErrorMetric m) { return m == ErrorMetric::Rmse ? ErrorMetric::PenumbraRmse : ErrorMetric::Rmse; }
std::string costText(const TimeStats& t) {
  return fmt::format("{} ({}–{})", numberText(t.median), numberText(t.p10), numberText(t.p90));
}
std::string oneOffCell(const BenchRow& r) {
  return r.oneOff.empty() ? "—" : fmt::format("{} s bake (static casters only)", numberText(r.oneOffSeconds()));
}
std::string flickerText(const BenchRow& r) { return r.motion ? fmt::format("{:.3f}", flickerPct(r)) : "—"; }

// The deciding error over the frames: its mean, and the frames' range when there are several.
std::string motionErrorText(ErrorMetric metric, const BenchRow& r) {
  const std::vector<double> e = frameErrors(metric, r);
  if (e.size() < 2) return errorText(e.front());
  return fmt::format("{} ({}–{})", errorText(motionError(metric, r)), errorText(*std::min_element(e.begin(), e.end())),
                     errorText(*std::max_element(e.begin(), e.end())));
}

std::string budgetsText(const SituationPicks& p, size_t row) {
  std::string out;
  for (const Budget b : p.budgetsOf(row)) out += (out.empty() ? "" : " = ") + std::string(budgetName(b));
  return out;
}

std::vector<size_t> pickedRows(const SituationPicks& p) {
  std::vector<size_t> rows;
  for (const Budget b : kBudgets)
    if (const std::optional<size_t> i = p.pick(b)) addOnce(rows, *i);
  return rows;
}

// The `penumbra compare` command that reproduces a row: its still error and, for a row scored in
// motion, its motion too (the frames, and the walk where the scene does not move).
std::string reproduceCommand(const BenchResults& r, const BenchRow& row) {
  std::string cmd = compareCommand(r, row);
  if (row.motion && !row.motion->frames.empty())
    cmd += fmt::format(" --frames {} --fps {:g}{}", row.motion->frames.size(), row.motion->fps,
                       row.motion->what == std::string_view(kWalkMotion) ? " --walk" : "");
  return cmd;
}

std::string acceptableText(const BenchResults& r, const SituationPicks& p) {
  const Situation& s = *p.situation;
  std::string scored = "scored on its still frame";
  if (p.motion && !p.candidates.empty()) {
    const MotionScore& m = *r.rows[p.candidates.front()].motion;
    scored = fmt::format("scored on its still frame and over {} ({} frames at {:g} fps)", m.what, m.frames.size(), m.fps);
  }
  if (p.acceptable.empty())
    return fmt::format("Scene `{}`, {}. **No candidate is acceptable**: each of the {} flickers beyond {:g} %.", s.scene,
                       scored, p.candidates.size(), kMaxFlickerPct);
  return fmt::format("Scene `{}`, {}. Acceptable: {} ≤ {:g} × {:.4f} = {:.4f} and flicker ≤ {:g} % ({} of {} candidates).",
                     s.scene, scored, metricName(s.metric), kAcceptableErrorFactor, p.bestError, p.acceptableError,
                     kMaxFlickerPct, p.acceptable.size(), p.candidates.size());
}

// The picks as a table: one row per configuration, its budgets joined when several picked it.
Table picksTable(const BenchResults& r, const SituationPicks& p) {
  const ErrorMetric metric = p.situation->metric;
  Table t;
  t.header = {"budget", "configuration", fmt::format("{} (decides){}", metricName(metric), p.motion ? ", mean (frames' range)" : ""),
              fmt::format("{}, still", metricName(otherMetric(metric))), "flicker %",
              fmt::format("whole cost ms (p10–p90{})", p.retimed ? ", interleaved rounds" : ""), "memory MiB", "one-off",
              "reproduce"};
  t.left = {true, true, false, false, false, false, false, true, true};
  for (const size_t i : pickedRows(p)) {
    const BenchRow& row = r.rows[i];
    t.rows.push_back({budgetsText(p, i), fmt::format("**{}**", rowLabel(row)), motionErrorText(metric, row),
                      errorText(situationError(otherMetric(metric), row)), flickerText(row), costText(pickCost(row)),
                      numberText(row.memoryMiB()), oneOffCell(row), fmt::format("`{}`", reproduceCommand(r, row))});
  }
  return t;
}

std::string ratioText(const TimeStats& t) { return fmt::format("{:.2f}–{:.2f}", t.p10, t.p90); }

// The notes under a situation's picks: one budget for all, ties, what was left out and why.
std::vector<std::string> pickNotes(const BenchResults& r, const SituationPicks& p) {
  std::vector<std::string> notes;
  const std::vector<size_t> picked = pickedRows(p);
  if (picked.size() == 1)
    notes.push_back(fmt::format("One configuration is the cheapest acceptable, the balanced and the best choice here: **{}**.",
                                rowLabel(r.rows[picked.front()])));
  if (p.cheapestTie) {
    std::string with;
    for (const size_t i : p.cheapestTie->with) {
      const std::optional<TimeStats> ratio = costRatio(r.rows[i], r.rows[*p.cheapestAcceptable]);
      with += fmt::format("{}{} (cost ratio {} over the rounds)", with.empty() ? "" : ", ", rowLabel(r.rows[i]),
                          ratio ? ratioText(*ratio) : "ranges overlap");
    }
    notes.push_back(fmt::format("Tie for the cheapest acceptable: **{}** and {}; the costs cannot be told apart, so the one "
                                "that keeps the least GPU memory is picked.",
                                rowLabel(r.rows[*p.cheapestAcceptable]), with));
  }
  if (p.bestTie) {
    std::string with;
    for (const size_t i : p.bestTie->with) {
      const std::optional<TimeStats> ratio = errorRatio(p.situation->metric, r.rows[i], r.rows[*p.best]);
      with += fmt::format("{}{} ({} {}, error ratio {} over the frames)", with.empty() ? "" : ", ", rowLabel(r.rows[i]),
                          metricName(p.situation->metric), errorText(motionError(p.situation->metric, r.rows[i])),
                          ratio ? ratioText(*ratio) : "equal");
    }
    notes.push_back(fmt::format("Tie for the best: **{}** ({} {}) and {}; the errors cannot be told apart over the frames, "
                                "so the cheaper is picked.",
                                rowLabel(r.rows[*p.best]), metricName(p.situation->metric),
                                errorText(motionError(p.situation->metric, r.rows[*p.best])), with));
  }
  // One bench command per parameter set among the picks: a run's sweeps form a cross product,
  // which would add combinations no pick has (msm.translucent beside translucent.shadows is refused).
  std::vector<std::vector<size_t>> byParams;
  for (const size_t i : picked) {
    const auto same = std::find_if(byParams.begin(), byParams.end(),
                                   [&](const std::vector<size_t>& g) { return r.rows[g.front()].config.params == r.rows[i].config.params; });
    if (same == byParams.end()) byParams.push_back({i});
    else same->push_back(i);
  }
  std::string retime;
  for (const std::vector<size_t>& g : byParams) retime += (retime.empty() ? "`" : "; `") + benchCommand(r, g) + "`";
  if (!picked.empty()) notes.push_back("Re-time these: " + retime + (byParams.size() > 1 ? " (one run per parameter set)." : "."));
  if (!p.excluded.empty()) {
    // "label: why" entries, the labels that share a reason named together.
    std::vector<std::pair<std::string, std::string>> byReason;
    for (const std::string& e : p.excluded) {
      const size_t colon = e.find(": ");
      const std::string label = e.substr(0, colon), why = colon == std::string::npos ? "" : e.substr(colon + 2);
      const auto it = std::find_if(byReason.begin(), byReason.end(), [&](const auto& b) { return b.second == why; });
      if (it == byReason.end()) byReason.emplace_back(label, why);
      else it->first += ", " + label;
    }
    std::string text = "Left out: ";
    for (size_t k = 0; k < byReason.size(); ++k) text += fmt::format("{}{}: {}", k ? "; " : "", byReason[k].first, byReason[k].second);
    notes.push_back(text + ".");
  }
  if (!p.flickering.empty()) {
    std::string text = fmt::format("Not acceptable, flicker above {:g} % of the followed points: ", kMaxFlickerPct);
    for (size_t k = 0; k < p.flickering.size(); ++k)
      text += fmt::format("{}{} ({:.3f} %)", k ? ", " : "", rowLabel(r.rows[p.flickering[k]]), flickerPct(r.rows[p.flickering[k]]));
    notes.push_back(text + ".");
  }
  return notes;
}

// Per filter, its candidate with the lowest error in the situation (default parameters only).
std::optional<size_t> bestOfFilter(const BenchResults& r, const SituationPicks& p, const std::string& filter) {
  std::optional<size_t> best;
  for (const size_t i : p.candidates) {
    const BenchRow& row = r.rows[i];
    if (row.config.filter != filter || !techniqueParams(row).empty()) continue;
    if (!best || motionError(p.situation->metric, row) < motionError(p.situation->metric, r.rows[*best])) best = i;
  }
  return best;
}

std::string pageTitle(const BenchResults& r) {
  return r.settings.quick ? "Which shadow technique? A quick look, not for decisions" : "Which shadow technique?";
}

}  // namespace

std::string benchCommand(const BenchResults& results, const std::vector<size_t>& rows) {
  std::vector<std::string> scenes, projections, filters;
  std::vector<std::pair<std::string, std::vector<std::string>>> params;  // per key, its values in order
  for (const size_t i : rows) {
    const BenchConfig& c = results.rows[i].config;
    addOnce(scenes, c.scene);
    addOnce(projections, c.projection);
    addOnce(filters, c.filter);
    for (const auto& [key, value] : c.params) {
      auto it = std::find_if(params.begin(), params.end(), [&](const auto& p) { return p.first == key; });
      if (it == params.end()) it = params.insert(params.end(), {key, {}});
      addOnce(it->second, value);
    }
  }
  const BenchSettings& s = results.settings;
  std::string cmd = fmt::format("penumbra bench --scenes {} --projections {} --filters {}", joinSet(scenes),
                                joinSet(projections), joinSet(filters));
  for (const auto& [key, values] : params) cmd += fmt::format(" --sweep {}={}", key, joinSet(values));
  cmd += fmt::format(" --size {}x{} --samples {} --frames {} --warmup {}", s.width, s.height, s.referenceSamples,
                     s.timedFrames, s.warmupFrames);
  if (s.motionFrames != BenchSettings{}.motionFrames) cmd += fmt::format(" --motion-frames {}", s.motionFrames);
  if (s.shadowMapSize) cmd += fmt::format(" --shadow-map {}", *s.shadowMapSize);
  if (!s.camera.empty()) cmd += " --camera " + s.camera;
  return cmd;
}

std::string picksSummary(const BenchResults& r, const std::vector<SituationPicks>& picks) {
  std::string out = r.settings.quick ? "picks (a quick look, not for decisions: --quick's small images, maps and frames):\n" : "picks:\n";
  for (const SituationPicks& p : picks) {
    const Situation& s = *p.situation;
    out += fmt::format("  {} ({}, {}): ", s.id, s.scene, metricName(s.metric));
    if (p.candidates.empty()) {
      out += "not measured in this run\n";
      continue;
    }
    if (p.acceptable.empty()) {
      out += fmt::format("nothing acceptable (every candidate flickers beyond {:g} %)\n", kMaxFlickerPct);
      continue;
    }
    std::string line;
    for (const size_t i : pickedRows(p)) {
      const BenchRow& row = r.rows[i];
      line += fmt::format("{}{}: {} ({:.4f}, {} ms{})", line.empty() ? "" : "; ", budgetsText(p, i), rowLabel(row),
                          motionError(s.metric, row), numberText(pickCost(row).median),
                          row.motion ? fmt::format(", flicker {:.3f} %", flickerPct(row)) : "");
    }
    const bool tie = p.cheapestTie || p.bestTie;
    out += line + (tie ? " (a tie: the page names it)" : "") + "\n";
  }
  return out;
}

std::string recommendationHtml(const BenchResults& r, const std::vector<SituationPicks>& picks) {
  std::string h = "<h2 id=\"choose\">Which technique? Recommendations from this run</h2>\n";
  if (r.settings.quick) h += "<p class=\"quick\">" + htmlCode(quickText(r)) + "</p>\n";
  h += "<p>For each situation, the configuration this run measured as the cheapest acceptable, the balanced and the best "
       "choice. Measured on " + escapeXml(machineText(r)) + ", at " + escapeXml(settingsText(r)) +
       ". The same table is written as a Markdown page (docs/choosing.md in the repository).</p>\n<ul>";
  for (const std::string& line : ruleText(r)) h += "<li>" + htmlCode(line) + "</li>";
  h += "</ul>\n";
  for (const SituationPicks& p : picks) {
    const Situation& s = *p.situation;
    h += fmt::format("<h3 id=\"choose-{}\">{}</h3>\n<p>{}</p>\n", s.id, escapeXml(s.title), escapeXml(s.why));
    if (p.candidates.empty()) {
      h += fmt::format("<p><b>Not measured in this run</b>: add <code>--scenes {}</code>.</p>\n", s.scene);
      continue;
    }
    h += "<p>" + htmlCode(acceptableText(r, p)) + "</p>\n";
    if (!p.acceptable.empty()) h += picksTable(r, p).html("picks");
    for (const std::string& note : pickNotes(r, p)) h += "<p class=\"note\">" + htmlCode(note) + "</p>\n";
  }
  return h;
}

std::string choosingMarkdown(const BenchResults& r, const std::vector<SituationPicks>& picks, const std::string& reportLink) {
  std::string m = "# " + pageTitle(r) + "\n\n";
  m += "<!-- Written by `penumbra bench` from its own results: do not edit by hand (docs/bench.md says how to "
       "regenerate it). -->\n\n";
  if (r.settings.quick) m += "> **" + quickText(r) + "**\n\n";
  m += fmt::format(
      "For each of the {} situations users bring, the configuration that [the bench]({}) measured as the **cheapest acceptable**, "
      "the **balanced** and the **best** choice: its error against the ray-traced reference, still and in motion, its "
      "flicker, its whole cost per frame, the GPU memory it keeps, and the `penumbra compare` command that reproduces its "
      "error, motion and flicker (and prints its warm pass times). This page is written by `penumbra bench`; every "
      "number comes from that run.\n\n",
      std::size(kSituations), reportLink);
  m += fmt::format("- Run: `{}`, {}.\n- Machine: {}.\n- Times are this machine's (llvmpipe runs on the CPU): compare them "
                   "with each other, not with a GPU's. Whole cost = shadow + prefilter + visibility passes per frame "
                   "(docs/bench.md, \"What is measured\", says what is counted).\n\n",
                   r.machine.command.empty() ? "penumbra bench" : r.machine.command, settingsText(r), machineText(r));
  m += "## How the picks are made\n\n| situation | scene | error that decides | motion | what the scene stands for |\n"
       "|---|---|---|---|---|\n";
  for (const SituationPicks& p : picks) {
    const Situation& s = *p.situation;
    std::string motion = "still frame only";
    if (p.motion) motion = r.rows[p.candidates.front()].motion->what;
    m += fmt::format("| [{}](#{}) | `{}` | {} | {} | {} |\n", s.title, s.id, s.scene, metricName(s.metric), motion, s.why);
  }
  m += "\n";
  for (const std::string& line : ruleText(r)) m += "- " + line + "\n";
  m += "\n";
  for (const SituationPicks& p : picks) {
    const Situation& s = *p.situation;
    m += fmt::format("## {} <a id=\"{}\"></a>\n\n", s.title, s.id);
    if (p.candidates.empty()) {
      m += fmt::format("Scene `{}`. **Not measured in this run**: add `--scenes {}`.\n\n", s.scene, s.scene);
      continue;
    }
    m += acceptableText(r, p) + "\n\n";
    if (!p.acceptable.empty()) m += picksTable(r, p).markdown() + "\n";
    for (const std::string& note : pickNotes(r, p)) m += note + "\n\n";
  }
  // Every filter's own best showing per situation: what the technique pages link to.
  m += "## Every filter at a glance <a id=\"every-filter\"></a>\n\nPer filter and situation, its most accurate "
       "projection in this run (default parameters): the error that decides there (mean over the frames) · flicker % · "
       "whole cost ms (its own timed frames) · memory MiB. ✓ = acceptable by the rule above.\n\n| filter |";
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
      const bool acceptable = std::find(p.acceptable.begin(), p.acceptable.end(), *i) != p.acceptable.end();
      m += fmt::format(" {:.4f} · {} · {} ms · {} MiB ({}){} |", motionError(p.situation->metric, row),
                       row.motion ? fmt::format("{:.3f} %", flickerPct(row)) : "still", numberText(row.shadowCost.median),
                       numberText(row.memoryMiB()), row.config.projection, acceptable ? " ✓" : "");
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
