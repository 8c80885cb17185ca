#include "bench/BenchResults.h"

#include "platform/Context.h"

#include <penumbra/Technique.h>

#include <fmt/format.h>

#include <algorithm>
#include <ctime>
#include <fstream>
#include <limits>
#include <numeric>
#include <thread>
#include <sys/utsname.h>

namespace penumbra::report {
namespace {

// The q-quantile of sorted samples, interpolating linearly between the two nearest ranks.
double quantile(const std::vector<double>& sorted, double q) {
  const double pos = q * static_cast<double>(sorted.size() - 1);
  const auto lo = static_cast<size_t>(pos);
  const size_t hi = std::min(lo + 1, sorted.size() - 1);
  const double t = pos - static_cast<double>(lo);
  return sorted[lo] * (1.0 - t) + sorted[hi] * t;
}

}  // namespace

TimeStats timeStats(std::span<const double> samplesMs) {
  if (samplesMs.empty()) return {};
  std::vector<double> s(samplesMs.begin(), samplesMs.end());
  std::sort(s.begin(), s.end());
  constexpr double kLow = 0.1, kHigh = 0.9;  // the p10–p90 band: robust to one outlier frame
  return {quantile(s, 0.5), quantile(s, kLow), quantile(s, kHigh)};
}

TimeStats shadowCostStats(const FrameSamples& frames) {
  std::vector<double> sums;
  for (const auto& [pass, samples] : frames) {
    if (std::find_if(std::begin(kShadowCostPasses), std::end(kShadowCostPasses),
                     [&](const char* p) { return pass == p; }) == std::end(kShadowCostPasses))
      continue;
    if (sums.size() < samples.size()) sums.resize(samples.size(), 0.0);
    for (size_t i = 0; i < samples.size(); ++i) sums[i] += samples[i];
  }
  return timeStats(sums);
}

std::optional<double> BenchRow::pagesDrawnMean() const {
  if (!motion || motion->pagesDrawn.empty()) return std::nullopt;
  return std::accumulate(motion->pagesDrawn.begin(), motion->pagesDrawn.end(), 0.0) / static_cast<double>(motion->pagesDrawn.size());
}

double BenchRow::oneOffSeconds() const {
  double s = 0.0;
  for (const OneOffCost& c : oneOff) s += c.seconds;
  return s;
}

TimeStats BenchRow::time(std::string_view pass) const {
  for (const PassStats& p : passes)
    if (p.name == pass) return p.ms;
  return {};
}

std::vector<std::string> BenchResults::passNames() const {
  std::vector<std::string> names;
  for (const BenchRow& r : rows)
    for (const PassStats& p : r.passes)
      if (p.name != kTotalPass && std::find(names.begin(), names.end(), p.name) == names.end()) names.push_back(p.name);
  names.emplace_back(kTotalPass);
  return names;
}

namespace {

// A word as a POSIX shell reads it: as is when it has only safe characters, else single-quoted.
std::string shellWord(const std::string& word) {
  const bool safe = !word.empty() && word.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                                            "0123456789._/:,=+-") == std::string::npos;
  if (safe) return word;
  std::string quoted = "'";
  for (const char c : word) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

}  // namespace

std::string compareCommand(const BenchResults& results, const BenchRow& row) {
  const BenchConfig& c = row.config;
  std::string cmd = fmt::format("penumbra compare --scene {} --projection {} --filter {}", shellWord(c.scene),
                                shellWord(c.projection), shellWord(filterArgument(c.filter)));
  for (const auto& [key, value] : c.params) cmd += " --set " + shellWord(key + "=" + value);
  cmd += fmt::format(" --size {}x{} --shadow-map {} --samples {}", row.width, row.height, row.shadowMapSize,
                     results.settings.referenceSamples);
  if (results.settings.shadowBudgetTexels > 0) cmd += fmt::format(" --shadow-budget {}", results.settings.shadowBudgetTexels);
  if (!results.settings.camera.empty()) cmd += " --camera " + shellWord(results.settings.camera);
  return cmd;
}

double loadAverage() {
  std::ifstream in("/proc/loadavg");
  double load = -1.0;
  if (!(in >> load)) return -1.0;
  return load;
}

MachineInfo describeMachine(const gl::GlInfo& gl) {
  MachineInfo m = describeMachine();
  m.glRenderer = gl.renderer;
  m.glVersion = gl.version;
  m.glVendor = gl.vendor;
  return m;
}

MachineInfo describeMachine() {
  MachineInfo m;
  std::ifstream cpuinfo("/proc/cpuinfo");
  for (std::string line; std::getline(cpuinfo, line);)
    if (line.starts_with("model name")) {
      const size_t colon = line.find(':');
      if (colon != std::string::npos) m.cpu = line.substr(line.find_first_not_of(' ', colon + 1));
      break;
    }
  utsname u{};
  if (uname(&u) == 0) m.os = fmt::format("{} {} {}", u.sysname, u.release, u.machine);
  m.hardwareThreads = static_cast<int>(std::thread::hardware_concurrency());
  m.loadStart = loadAverage();
  const std::time_t now = std::time(nullptr);
  std::tm utc{};
  char text[32] = {};
  if (gmtime_r(&now, &utc) && std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &utc) > 0) m.date = text;
  return m;
}

std::vector<size_t> paretoFront(std::span<const double> x, std::span<const double> y) {
  std::vector<size_t> order(x.size());
  std::iota(order.begin(), order.end(), size_t{0});
  // Ascending x, ties by ascending y, then index: a point is on the front when its y beats every
  // earlier one, or when it repeats the last front point exactly (neither dominates the other).
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return x[a] != x[b] ? x[a] < x[b] : y[a] < y[b]; });
  std::vector<size_t> front;
  double bestY = std::numeric_limits<double>::infinity();
  for (const size_t i : order)
    if (y[i] < bestY || (!front.empty() && y[i] == y[front.back()] && x[i] == x[front.back()])) {
      front.push_back(i);
      bestY = y[i];
    }
  return front;
}

std::string numberText(double v) {
  const double a = std::abs(v);
  return fmt::format("{:.{}f}", v, a >= 100 ? 0 : a >= 10 ? 1 : a >= 1 ? 2 : 3);
}

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

std::vector<size_t> sceneRows(const BenchResults& results, const std::string& scene) {
  std::optional<std::string> light;
  for (const BenchRow& r : results.rows)
    if (r.config.scene == scene && (!light || lightParams(r).empty())) {
      light = lightParams(r);
      if (light->empty()) break;
    }
  std::vector<size_t> rows;
  for (size_t i = 0; i < results.rows.size(); ++i)
    if (results.rows[i].config.scene == scene && lightParams(results.rows[i]) == light) rows.push_back(i);
  return rows;
}

std::string oneOffText(const BenchRow& r) {
  return r.oneOff.empty() ? std::string() : fmt::format(" + one-off {:.3g} s (static casters only)", r.oneOffSeconds());
}

}  // namespace penumbra::report
