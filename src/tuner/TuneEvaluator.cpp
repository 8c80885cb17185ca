#include "tuner/TuneEvaluator.h"

#include <penumbra/Error.h>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <unistd.h>

namespace penumbra::report {
namespace {

using Clock = std::chrono::steady_clock;

bool sameConfig(const BenchConfig& a, const BenchConfig& b) {
  return a.scene == b.scene && a.projection == b.projection && a.filter == b.filter && a.params == b.params;
}

nlohmann::json rowJson(const TuneRow& r) {
  nlohmann::json params = nlohmann::json::object();
  for (const auto& [k, v] : r.params) params[k] = v;
  return {{"projection", r.projection}, {"filter", r.filter}, {"params", params}, {"shadow_map", r.mapSize},
          {"shadow_budget", r.budgetTexels}, {"granted_map", r.grantedMapSize}, {"scene", r.scene}, {"camera", r.camera},
          {"width", r.width}, {"height", r.height}, {"frames", r.frames}, {"rmse", r.metrics.rmse},
          {"mae", r.metrics.mae}, {"leak_pct", r.metrics.leakPct}, {"overdark_pct", r.metrics.overDarkPct},
          {"umbra_leak_pct", r.metrics.umbraLeakPct}, {"penumbra_rmse", r.metrics.penumbraRmse},
          {"acne_pct", r.metrics.acnePct}, {"pixels", r.metrics.pixels}, {"shadow_cost_ms", r.costMs}, {"shadow_cost_p10_ms", r.costP10Ms},
          {"shadow_cost_p90_ms", r.costP90Ms}, {"shadow_memory_mb", r.memoryMiB}, {"command", r.command}};
}

TuneRow rowFromJson(const nlohmann::json& j) {
  TuneRow r;
  r.projection = j.at("projection").get<std::string>();
  r.filter = j.at("filter").get<std::string>();
  for (const auto& [k, v] : j.at("params").items()) r.params.emplace_back(k, v.get<std::string>());
  r.mapSize = j.at("shadow_map").get<int>();
  r.budgetTexels = j.value("shadow_budget", int64_t{0});
  r.grantedMapSize = j.value("granted_map", r.mapSize);
  r.scene = j.value("scene", std::string());
  r.camera = j.value("camera", std::string());
  r.width = j.at("width").get<int>();
  r.height = j.at("height").get<int>();
  r.frames = j.at("frames").get<int>();
  r.metrics.rmse = j.at("rmse").get<double>();
  r.metrics.mae = j.at("mae").get<double>();
  r.metrics.leakPct = j.at("leak_pct").get<double>();
  r.metrics.overDarkPct = j.at("overdark_pct").get<double>();
  r.metrics.umbraLeakPct = j.at("umbra_leak_pct").get<double>();
  r.metrics.penumbraRmse = j.at("penumbra_rmse").get<double>();
  r.metrics.acnePct = j.value("acne_pct", 0.0);
  r.metrics.pixels = j.at("pixels").get<size_t>();
  r.costMs = j.at("shadow_cost_ms").get<double>();
  r.costP10Ms = j.at("shadow_cost_p10_ms").get<double>();
  r.costP90Ms = j.at("shadow_cost_p90_ms").get<double>();
  r.memoryMiB = j.at("shadow_memory_mb").get<double>();
  r.command = j.at("command").get<std::string>();
  return r;
}

double aggregate(TuneAggregate a, const std::vector<double>& values) {
  if (a == TuneAggregate::Worst) return *std::max_element(values.begin(), values.end());
  double sum = 0.0;
  for (const double v : values) sum += v;
  return sum / static_cast<double>(values.size());
}

}  // namespace

TuneProgress::TuneProgress(bool wanted) : mWanted(wanted), mTerminal(isatty(fileno(stderr)) != 0), mLast(Clock::now()) {}

TuneProgress::~TuneProgress() { finish(); }

void TuneProgress::stage(std::string name, size_t total, double laterSeconds) {
  mName = std::move(name);
  mTotal = total;
  mDone = 0;
  mLaterSeconds = laterSeconds;
}

void TuneProgress::advance(double secondsEach) {
  ++mDone;
  if (!mWanted) return;
  const double left = static_cast<double>(mTotal - std::min(mDone, mTotal)) * secondsEach + mLaterSeconds;
  const auto now = Clock::now();
  const double since = std::chrono::duration<double>(now - mLast).count();
  // A terminal also shows each stage's last count; a log only every kLineSeconds.
  if (mPrinted && since < (mTerminal ? kRedrawSeconds : kLineSeconds) && (!mTerminal || mDone < mTotal)) return;
  const std::string line = fmt::format("penumbra tune: {}: {}/{} configurations, about {:.0f} s left", mName, mDone, mTotal, left);
  if (mTerminal) std::fprintf(stderr, "\r%s\033[K", line.c_str());
  else std::fprintf(stderr, "%s\n", line.c_str());
  std::fflush(stderr);
  mLast = now;
  mPrinted = true;
  mOpen = mTerminal;
}

void TuneProgress::finish() {
  if (mOpen) std::fprintf(stderr, "\n");
  mOpen = false;
}

TuneRow aggregateTuneRows(TuneAggregate a, std::vector<TuneRow> views) {
  TuneRow r = views.front();
  const auto over = [&](auto field) {
    std::vector<double> v;
    for (const TuneRow& x : views) v.push_back(field(x));
    return aggregate(a, v);
  };
  r.metrics.rmse = over([](const TuneRow& x) { return x.metrics.rmse; });
  r.metrics.mae = over([](const TuneRow& x) { return x.metrics.mae; });
  r.metrics.leakPct = over([](const TuneRow& x) { return x.metrics.leakPct; });
  r.metrics.overDarkPct = over([](const TuneRow& x) { return x.metrics.overDarkPct; });
  r.metrics.umbraLeakPct = over([](const TuneRow& x) { return x.metrics.umbraLeakPct; });
  r.metrics.penumbraRmse = over([](const TuneRow& x) { return x.metrics.penumbraRmse; });
  r.metrics.acnePct = over([](const TuneRow& x) { return x.metrics.acnePct; });
  r.metrics.pixels = 0;
  for (const TuneRow& x : views) r.metrics.pixels += x.metrics.pixels;
  r.error = over([](const TuneRow& x) { return x.error; });
  r.costMs = over([](const TuneRow& x) { return x.costMs; });
  r.costP10Ms = over([](const TuneRow& x) { return x.costP10Ms; });
  r.costP90Ms = over([](const TuneRow& x) { return x.costP90Ms; });
  r.workM = over([](const TuneRow& x) { return x.workM; });
  r.memoryMiB = 0.0;
  for (const TuneRow& x : views) r.memoryMiB = std::max(r.memoryMiB, x.memoryMiB);
  r.views = std::move(views);
  return r;
}

TuneEvaluator::TuneEvaluator(gl::Context& context, const TuneRequest& request, const TuneSetupFactory& makeSetup,
                             const std::vector<TuneTechnique>& techniques, TuneProgress& progress)
    : mContext(context), mRequest(request), mMakeSetup(makeSetup), mTechniques(techniques), mProgress(progress),
      mLogPath(request.outDir / "evaluations.jsonl") {
  std::ifstream in(mLogPath);
  for (std::string line; std::getline(in, line);) {
    const nlohmann::json j = nlohmann::json::parse(line, nullptr, false);
    if (j.is_discarded() || !j.contains("key")) continue;  // a line cut short by an interruption
    try {
      mMemo[j["key"].get<std::string>()] = rowFromJson(j);
      mLoaded.insert(j["key"].get<std::string>());
    } catch (const nlohmann::json::exception&) {
      continue;
    }
  }
}

double TuneEvaluator::secondsPerJob(int width, int height) const {
  const auto it = mSeconds.find({width, height});
  if (it != mSeconds.end() && it->second.second > 0) return it->second.first / it->second.second;
  double screen = 0.0;
  size_t n = 0;
  for (const auto& [size, s] : mSeconds) {
    screen += s.first;
    n += s.second;
  }
  return n > 0 ? kFullOverScreenGuess * screen / static_cast<double>(n) : 1.0;
}

size_t TuneEvaluator::unmeasured(const std::vector<TuneJob>& jobs, int width, int height, int frames) const {
  size_t n = 0;
  for (const TuneJob& j : jobs)
    for (const TuneView& v : mRequest.views) n += mMemo.contains(key(j, v, width, height, frames)) ? 0 : 1;
  return n;
}

std::vector<std::optional<TuneRow>> TuneEvaluator::run(const std::vector<TuneJob>& jobs, int width, int height, int frames) {
  // runBench takes one view and one map setting per run.
  std::map<std::tuple<size_t, int, int64_t>, std::vector<size_t>> groups;
  for (size_t i = 0; i < jobs.size(); ++i)
    for (size_t v = 0; v < mRequest.views.size(); ++v)
      if (!mMemo.contains(key(jobs[i], mRequest.views[v], width, height, frames))) {
        const TuneMaps maps = mapsOf(jobs[i]);
        groups[{v, maps.size, maps.budgetTexels}].push_back(i);
      }
  for (const auto& [group, indices] : groups) measure(jobs, indices, std::get<0>(group), width, height, frames);

  std::vector<std::optional<TuneRow>> out(jobs.size());
  for (size_t i = 0; i < jobs.size(); ++i) {
    std::vector<TuneRow> views;
    for (const TuneView& v : mRequest.views) {
      const auto it = mMemo.find(key(jobs[i], v, width, height, frames));
      if (it == mMemo.end()) break;  // failed or refused there
      if (mLoaded.erase(it->first) > 0) ++mResumed;  // read back from an earlier run: counted once
      TuneRow r = it->second;
      // The error and the work again: a resumed run may ask another objective.
      r.error = objectiveValue(mRequest.objective, r.metrics);
      r.workM = work(jobs[i], r);
      views.push_back(std::move(r));
    }
    if (views.size() != mRequest.views.size()) continue;
    TuneRow row = aggregateTuneRows(mRequest.aggregate, std::move(views));
    if (mRequest.objective == TuneObjective::Acne)
      row.error += kBiasTieWeight * tuneBiasSize(mTechniques[jobs[i].technique].space, jobs[i].candidate);
    row.isDefault = jobs[i].candidate == defaultCandidate(mTechniques[jobs[i].technique].space);
    out[i] = std::move(row);
  }
  return out;
}

void TuneEvaluator::measure(const std::vector<TuneJob>& jobs, const std::vector<size_t>& indices, size_t viewIndex, int width, int height,
             int frames) {
  const TuneView& view = mRequest.views[viewIndex];
  const TuneMaps maps = mapsOf(jobs[indices.front()]);
  BenchSettings set = mRequest.settings;
  set.width = width;
  set.height = height;
  set.shadowMapSize = maps.size;
  set.shadowBudgetTexels = maps.budgetTexels;
  set.timedFrames = frames;
  set.camera = view.camera;
  std::vector<BenchConfig> configs;
  for (const size_t i : indices) configs.push_back(config(jobs[i], view));
  auto& [seconds, count] = mSeconds[{width, height}];
  auto last = Clock::now();
  const SetupFactory factory = [&](const BenchConfig& c) { return mMakeSetup(c, view.camera); };
  const BenchResults results =
      runBench(mContext, configs, factory,
               {.settings = set, .outDir = mRequest.outDir, .progress = false, .verbose = mRequest.verbose,
                .microBenchmarks = false, .configDone = [&] {
                  const auto now = Clock::now();
                  seconds += std::chrono::duration<double>(now - last).count();
                  ++count;
                  last = now;
                  mProgress.advance(seconds / static_cast<double>(count));
                }});
  if (!results.machine.clock.empty()) mClock = results.machine.clock;
  for (const SkippedConfig& k : results.skipped) {
    mProgress.finish();
    std::fprintf(stderr, "penumbra tune: %s · %s %s %s: %s\n", k.config.projection.c_str(), k.config.filter.c_str(),
                 k.config.paramsText().c_str(), k.failed ? "failed" : "refused", k.reason.c_str());
  }
  for (size_t n = 0; n < indices.size(); ++n) {
    const auto row = std::find_if(results.rows.begin(), results.rows.end(),
                                  [&](const BenchRow& r) { return sameConfig(r.config, configs[n]); });
    if (row == results.rows.end()) continue;
    remember(key(jobs[indices[n]], view, width, height, frames), tuneRow(results, *row));
    ++mMeasured;
  }
}

std::vector<std::vector<std::vector<double>>> TuneEvaluator::timeRounds(const std::vector<TuneJob>& jobs, int width, int height,
                                                                       int rounds) {
  std::vector<std::vector<std::vector<double>>> out;
  for (const TuneView& view : mRequest.views) {
    std::vector<BenchConfig> configs;
    std::vector<RenderOptions> renders;
    std::vector<int> mapSizes;
    for (const TuneJob& j : jobs) {
      const TuneMaps maps = mapsOf(j);
      configs.push_back(config(j, view));
      renders.push_back({.width = width, .height = height, .shadowBudgetTexels = maps.budgetTexels, .debugView = 0});
      mapSizes.push_back(maps.size);
    }
    const SetupFactory factory = [&](const BenchConfig& c) { return mMakeSetup(c, view.camera); };
    const auto start = Clock::now();
    out.push_back(timeInterleaved(configs, renders, mapSizes, factory, mRequest.settings.warmupFrames, rounds));
    const double each = std::chrono::duration<double>(Clock::now() - start).count() / static_cast<double>(std::max<size_t>(jobs.size(), 1));
    for (size_t k = 0; k < jobs.size(); ++k) mProgress.advance(each);
  }
  return out;
}

TuneMaps TuneEvaluator::mapsOf(const TuneJob& j) const {
  const TuneTechnique& t = mTechniques[j.technique];
  return tuneMaps(t.space, j.candidate, t.maps);
}

// TuneCost::Model's work of one view's row: the memory kept, written once; a read per tap per pixel.
double TuneEvaluator::work(const TuneJob& j, const TuneRow& r) const {
  const TuneTechnique& t = mTechniques[j.technique];
  double taps = 0.0;
  for (const auto& [key, def] : t.taps) {
    float v = def;
    for (size_t d = 0; d < t.space.size(); ++d)
      if (t.space[d].desc.key == key) v = j.candidate[d];
    taps += v;
  }
  constexpr double kBytesPerMiB = 1024.0 * 1024.0, kMillion = 1e6;
  const double texels = r.memoryMiB * kBytesPerMiB / kModelBytesPerTexel;
  return (texels + static_cast<double>(r.width) * r.height * std::max(1.0, taps)) / kMillion;
}

BenchConfig TuneEvaluator::config(const TuneJob& j, const TuneView& v) const {
  const TuneTechnique& t = mTechniques[j.technique];
  return {.plan = "tune", .scene = v.scene, .projection = t.projection, .filter = t.filter,
          .params = tuneParams(t.space, j.candidate), .inGrid = false};
}

std::string TuneEvaluator::key(const TuneJob& j, const TuneView& v, int width, int height, int frames) const {
  const TuneTechnique& t = mTechniques[j.technique];
  const TuneMaps maps = mapsOf(j);
  return fmt::format("{}|{}|{}x{}|map {}{}|{} frames|{} samples|{}|{}|{}", v.scene, v.camera, width, height, maps.size,
                     maps.budgetTexels > 0 ? fmt::format(" budget {}", maps.budgetTexels) : "", frames,
                     mRequest.settings.referenceSamples, t.projection, t.filter, config(j, v).paramsText());
}

TuneRow TuneEvaluator::tuneRow(const BenchResults& results, const BenchRow& b) const {
  TuneRow r;
  r.projection = b.config.projection;
  r.filter = b.config.filter;
  r.params = b.config.params;
  r.mapSize = b.shadowMapSize;
  r.budgetTexels = results.settings.shadowBudgetTexels;
  r.grantedMapSize = b.grantedMapSize;
  r.scene = b.config.scene;
  r.camera = results.settings.camera;
  r.width = b.width;
  r.height = b.height;
  r.frames = b.frames;
  r.metrics = b.metrics;
  r.error = objectiveValue(mRequest.objective, b.metrics);
  r.costMs = b.shadowCost.median;
  r.costP10Ms = b.shadowCost.p10;
  r.costP90Ms = b.shadowCost.p90;
  r.memoryMiB = b.memoryMiB();
  r.command = compareCommand(results, b);
  return r;
}

void TuneEvaluator::remember(const std::string& k, const TuneRow& r) {
  mMemo[k] = r;
  nlohmann::json j = rowJson(r);
  j["key"] = k;
  std::ofstream out(mLogPath, std::ios::app);
  out << j.dump() << '\n';  // one line per row, flushed: an interruption loses at most the row in flight
}

}  // namespace penumbra::report
