#include "bench/ResultsIO.h"

#include "bench/Recommendation.h"

#include <penumbra/Files.h>

#include <fmt/format.h>

#include <string>

namespace penumbra::report {
namespace {

// 2: umbra_leak_pct; 3: micro[].ratio; 4: shadow cost, memory, one-off costs, frame_ms, compare_command,
// recommendations; 5: motion, flicker and interleaved-round columns, "samples", the recommendations'
// flicker, contenders and ties; 6: frame_ms and samples moved to frames.json ("per_frame")
constexpr int kFormatVersion = 6;
constexpr int kFramesFormatVersion = 1;
constexpr const char* kFramesFile = "frames.json";
const char* const kStatSuffixes[] = {"_ms_median", "_ms_p10", "_ms_p90"};

std::string csvField(const Cell& c) {
  if (std::holds_alternative<std::monostate>(c)) return {};
  if (const double* d = std::get_if<double>(&c)) return fmt::format("{}", *d);
  const std::string& s = std::get<std::string>(c);
  if (s.find_first_of(",\"\r\n") == std::string::npos) return s;
  std::string quoted = "\"";
  for (const char ch : s) quoted += ch == '"' ? std::string("\"\"") : std::string(1, ch);
  return quoted + "\"";
}

nlohmann::json jsonCell(const Cell& c) {
  if (std::holds_alternative<std::monostate>(c)) return nullptr;
  if (const double* d = std::get_if<double>(&c)) return *d;
  return std::get<std::string>(c);
}

nlohmann::json statsJson(const TimeStats& t) { return {{"median", t.median}, {"p10", t.p10}, {"p90", t.p90}}; }

}  // namespace

std::vector<std::string> tableColumns(const BenchResults& results) {
  std::vector<std::string> cols = {"plan", "scene", "projection", "filter", "params", "light_size", "lights", "width", "height",
                                   "shadow_map", "frames", "rmse", "mae", "bias", "leak_pct", "umbra_leak_pct",
                                   "overdark_pct", "penumbra_rmse", "pixels", "rmse_rgb", "rmse_r", "rmse_g", "rmse_b"};
  for (const char* suffix : kStatSuffixes) cols.push_back(std::string(kShadowCostColumn) + suffix);
  for (const char* c : {"shadow_memory_mb", "one_off_s", "one_off_what", "motion", "motion_frames", "flicker_pct",
                        "rmse_motion_mean", "penumbra_rmse_motion_mean", "rmse_rgb_motion_mean", "pages_drawn"})
    cols.emplace_back(c);
  for (const char* suffix : kStatSuffixes) cols.push_back(std::string(kRoundsCostColumn) + suffix);
  for (const std::string& pass : results.passNames())
    for (const char* suffix : kStatSuffixes) cols.push_back(pass + suffix);
  for (const char* c : {"compare_command", "image", "heatmap", "reference", "clock", "gl_renderer"}) cols.emplace_back(c);
  return cols;
}

std::vector<Cell> tableRow(const BenchResults& results, const BenchRow& r) {
  const VisibilityMetrics& m = r.metrics;
  auto num = [](auto v) { return Cell(static_cast<double>(v)); };
  // A float as the double its shortest text names (0.12f → 0.12, not 0.11999999731779099).
  auto numFloat = [](float v) { return Cell(std::stod(fmt::format("{}", v))); };
  std::vector<Cell> cells = {r.config.plan, r.config.scene, r.config.projection, r.config.filter,
                             r.config.paramsText(), numFloat(r.lightSize), num(r.lights), num(r.width), num(r.height),
                             num(r.shadowMapSize), num(r.frames), num(m.rmse), num(m.mae), num(m.bias),
                             num(m.leakPct), num(m.umbraLeakPct), num(m.overDarkPct), num(m.penumbraRmse), num(m.pixels)};
  // The colour metrics where the row has them (a scene with translucent casters), else empty cells.
  if (r.colour)
    cells.insert(cells.end(), {num(r.colour->rmse), num(r.colour->channelRmse[0]), num(r.colour->channelRmse[1]),
                               num(r.colour->channelRmse[2])});
  else
    cells.insert(cells.end(), 4, Cell());
  cells.insert(cells.end(), {num(r.shadowCost.median), num(r.shadowCost.p10), num(r.shadowCost.p90), num(r.memoryMiB())});
  if (r.oneOff.empty()) {
    cells.insert(cells.end(), 2, Cell());
  } else {
    std::string what;
    for (const OneOffCost& o : r.oneOff) what += (what.empty() ? "" : "; ") + o.what + (o.cached ? " (read from the cache)" : "");
    cells.emplace_back(num(r.oneOffSeconds()));
    cells.emplace_back(what + kOneOffValidity);
  }
  if (r.motion) {
    cells.insert(cells.end(), {Cell(r.motion->what), num(r.motion->frames.size()), num(flickerPct(r)),
                               num(motionError(ErrorMetric::Rmse, r)), num(motionError(ErrorMetric::PenumbraRmse, r))});
    if (r.colour) cells.emplace_back(motionError(ErrorMetric::ColourRmse, r));
    else cells.emplace_back();
  } else {
    cells.insert(cells.end(), 6, Cell());
  }
  if (const std::optional<double> pages = r.pagesDrawnMean()) cells.emplace_back(*pages);
  else cells.emplace_back();
  if (r.rounds)
    cells.insert(cells.end(), {num(r.rounds->stats.median), num(r.rounds->stats.p10), num(r.rounds->stats.p90)});
  else
    cells.insert(cells.end(), 3, Cell());
  for (const std::string& pass : results.passNames()) {
    const auto it = std::find_if(r.passes.begin(), r.passes.end(), [&](const PassStats& p) { return p.name == pass; });
    if (it == r.passes.end()) {
      cells.insert(cells.end(), 3, Cell());
    } else {
      cells.insert(cells.end(), {num(it->ms.median), num(it->ms.p10), num(it->ms.p90)});
    }
  }
  cells.emplace_back(compareCommand(results, r));
  for (const std::string* s : {&r.imagePath, &r.heatmapPath, &r.referencePath, &results.machine.clock,
                               &results.machine.glRenderer})
    cells.emplace_back(*s);
  return cells;
}

namespace {
void csvLine(std::string& out, const std::vector<std::string>& fields) {
  for (size_t i = 0; i < fields.size(); ++i) out += (i ? "," : "") + fields[i];
  out += "\r\n";
}
}  // namespace

std::string resultsCsv(const BenchResults& results) {
  std::string out;
  auto line = [&](const std::vector<std::string>& fields) { csvLine(out, fields); };
  std::vector<std::string> header;
  for (const std::string& c : tableColumns(results)) header.push_back(csvField(c));
  line(header);
  for (const BenchRow& r : results.rows) {
    std::vector<std::string> fields;
    for (const Cell& c : tableRow(results, r)) fields.push_back(csvField(c));
    line(fields);
  }
  return out;
}

std::string microCsv(const BenchResults& results) {
  std::string out;
  csvLine(out, {"name", "baseline", "ms_median", "ms_p10", "ms_p90", "ratio_median", "ratio_p10", "ratio_p90", "repetitions",
                "error", "description", "clock", "gl_renderer"});
  auto number = [](bool present, double v) { return present ? csvField(Cell(v)) : std::string(); };
  for (const MicroResult& m : results.micro) {
    const bool timed = m.error.empty();
    const TimeStats ratio = m.ratio.value_or(TimeStats{});
    csvLine(out, {csvField(Cell(m.name)), csvField(Cell(m.baseline)), number(timed, m.ms.median), number(timed, m.ms.p10),
                  number(timed, m.ms.p90), number(m.ratio.has_value(), ratio.median), number(m.ratio.has_value(), ratio.p10),
                  number(m.ratio.has_value(), ratio.p90), number(true, m.repetitions), csvField(Cell(m.error)),
                  csvField(Cell(m.description)), csvField(Cell(results.machine.clock)), csvField(Cell(results.machine.glRenderer))});
  }
  return out;
}

nlohmann::json resultsJson(const BenchResults& results) {
  const MachineInfo& m = results.machine;
  const BenchSettings& s = results.settings;
  nlohmann::json j;
  j["format"] = "penumbra-bench";
  j["version"] = kFormatVersion;
  j["machine"] = {{"gl_renderer", m.glRenderer}, {"gl_version", m.glVersion}, {"gl_vendor", m.glVendor},
                  {"clock", m.clock},           {"cpu", m.cpu},              {"os", m.os},
                  {"hardware_threads", m.hardwareThreads}, {"load_start", m.loadStart}, {"load_end", m.loadEnd},
                  {"date", m.date}, {"command", m.command}};
  j["settings"] = {{"width", s.width},
                   {"height", s.height},
                   {"shadow_map", s.shadowMapSize ? nlohmann::json(*s.shadowMapSize) : nlohmann::json(nullptr)},
                   {"warmup_frames", s.warmupFrames},
                   {"timed_frames", s.timedFrames},
                   {"max_seconds_per_config", s.maxSecondsPerConfig},
                   {"reference_samples", s.referenceSamples},
                   {"micro_repetitions", s.microRepetitions}};
  if (!s.camera.empty()) j["settings"]["camera"] = s.camera;
  j["seconds"] = results.seconds;
  const std::vector<std::string> columns = tableColumns(results);
  j["columns"] = columns;
  j["rows"] = nlohmann::json::array();
  for (const BenchRow& r : results.rows) {
    const std::vector<Cell> cells = tableRow(results, r);
    nlohmann::json row = nlohmann::json::object();
    for (size_t i = 0; i < columns.size(); ++i) row[columns[i]] = jsonCell(cells[i]);
    j["rows"].push_back(std::move(row));
  }
  j["skipped"] = nlohmann::json::array();
  for (const SkippedConfig& k : results.skipped)
    j["skipped"].push_back({{"plan", k.config.plan}, {"scene", k.config.scene}, {"projection", k.config.projection},
                            {"filter", k.config.filter}, {"params", k.config.paramsText()},
                            {"reason", k.reason}, {"failed", k.failed}});
  j["per_frame"] = kFramesFile;  // frame_ms and samples, per row (framesJson)
  // The recommendation (Recommendation.h), rows as indices into "rows".
  j["recommendations"] = nlohmann::json::array();
  for (const SituationPicks& p : recommend(results)) {
    nlohmann::json s = {{"situation", p.situation->id},
                        {"title", p.situation->title},
                        {"scene", p.situation->scene},
                        {"metric", metricKey(p.situation->metric)},
                        {"static_casters", p.situation->staticCasters},
                        {"candidates", p.candidates},
                        {"front", p.front},
                        {"best_error", p.bestError},
                        {"acceptable_error", p.acceptableError},
                        {"acceptable_factor", kAcceptableErrorFactor},
                        {"max_flicker_pct", kMaxFlickerPct},
                        {"flickering", p.flickering},
                        {"acceptable", p.acceptable},
                        {"contenders", p.contenders},
                        {"retimed", p.retimed},
                        {"cheapest_tie", p.cheapestTie ? nlohmann::json(p.cheapestTie->with) : nlohmann::json(nullptr)},
                        {"best_tie", p.bestTie ? nlohmann::json(p.bestTie->with) : nlohmann::json(nullptr)}};
    for (const Budget b : kBudgets) s[budgetKey(b)] = p.pick(b) ? nlohmann::json(*p.pick(b)) : nlohmann::json(nullptr);
    j["recommendations"].push_back(std::move(s));
  }
  j["scale"] = nlohmann::json::array();  // the triangle-count plan (bench/ScaleBench.h)
  for (const ScaleRow& r : results.scale)
    j["scale"].push_back({{"triangles", r.triangles}, {"vertices", r.vertices}, {"file_bytes", r.fileBytes},
                          {"load_s", r.loadSeconds}, {"frames", r.frames}, {"gbuffer_ms", statsJson(r.gbufferMs)},
                          {"shadow_ms", statsJson(r.shadowMs)}, {"bvh_build_s", r.bvhSeconds}, {"bvh_bytes", r.bvhBytes},
                          {"bvh_peak_bytes", r.bvhPeakBytes}, {"error", r.error}});
  j["micro"] = nlohmann::json::array();
  for (const MicroResult& mr : results.micro)
    j["micro"].push_back({{"name", mr.name}, {"description", mr.description}, {"baseline", mr.baseline}, {"ms", statsJson(mr.ms)},
                          {"ratio", mr.ratio ? statsJson(*mr.ratio) : nlohmann::json(nullptr)},
                          {"repetitions", mr.repetitions}, {"error", mr.error}});
  return j;
}

nlohmann::json framesJson(const BenchResults& results) {
  nlohmann::json j;
  j["format"] = "penumbra-bench-frames";
  j["version"] = kFramesFormatVersion;
  // The samples behind every row's time statistics: per row, per pass, each timed frame (ms).
  j["frame_ms"] = nlohmann::json::array();
  for (const BenchRow& r : results.rows) {
    nlohmann::json frames = nlohmann::json::object();
    for (const auto& [pass, samples] : r.frameMs) frames[pass] = samples;
    j["frame_ms"].push_back(std::move(frames));
  }
  // Per row, what its motion and its interleaved rounds measured (null where it had none): each
  // frame's RMSE and penumbra RMSE (the still frame first; the colour RMSE too where the row has it), the flicker counts, each round's cost.
  j["samples"] = nlohmann::json::array();
  for (const BenchRow& r : results.rows) {
    nlohmann::json m = nullptr;
    if (r.motion) {
      m = {{"what", r.motion->what}, {"fps", r.motion->fps}, {"rmse", frameErrors(ErrorMetric::Rmse, r)},
           {"penumbra_rmse", frameErrors(ErrorMetric::PenumbraRmse, r)}, {"flicker_followed", r.motion->flicker.followed},
           {"flicker_points", r.motion->flicker.flickering}};
      if (r.colour) m["rmse_rgb"] = frameErrors(ErrorMetric::ColourRmse, r);
    }
    nlohmann::json rounds = nullptr;
    if (r.rounds) rounds = {{"group", r.rounds->group}, {"ms", r.rounds->ms}};
    j["samples"].push_back({{"motion", m}, {"rounds", rounds}});
  }
  return j;
}

void writeResults(const std::filesystem::path& dir, const BenchResults& results) {
  writeTextFile(dir / "results.csv", resultsCsv(results));
  // Compact, and the per-frame samples apart: a full run's made the indented file 2.3 MB and the
  // compact one 2.1 MB, 0.8 MB of it per-frame; a reader parses it, nobody diffs it by line.
  writeTextFile(dir / "results.json", resultsJson(results).dump() + "\n");
  writeTextFile(dir / kFramesFile, framesJson(results).dump() + "\n");
  writeTextFile(dir / "micro.csv", microCsv(results));
}

}  // namespace penumbra::report
