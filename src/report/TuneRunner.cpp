#include "report/TuneRunner.h"

#include "platform/Context.h"

#include <penumbra/Error.h>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <set>

namespace penumbra::report {
namespace {

using Clock = std::chrono::steady_clock;

// Parameters that trade something a still frame does not measure: left at their defaults.
// csm.stabilize trades shimmer under a moving camera against resolution.
const std::vector<std::string> kFixedKeys = {"csm.stabilize"};

// Before any full-size configuration is measured, one is guessed to take this many times a
// screen-stage one (fixed costs, shader compiles and the reference load do not scale with pixels).
constexpr double kFullOverScreenGuess = 4.0;
constexpr double kSecondsPerMinute = 60.0;

struct Technique {
  std::string projection, filter;
  std::vector<TuneDim> space;
  int defaultMapSize = 0;
  // Full-size evaluations: candidate and row.
  std::vector<std::pair<TuneCandidate, TuneRow>> full;
  TuneCandidate center;
  bool descending = true;
};

struct Job {
  size_t technique = 0;
  TuneCandidate candidate;
};

bool sameConfig(const BenchConfig& a, const BenchConfig& b) {
  return a.scene == b.scene && a.projection == b.projection && a.filter == b.filter && a.params == b.params;
}

nlohmann::json rowJson(const TuneRow& r) {
  nlohmann::json params = nlohmann::json::object();
  for (const auto& [k, v] : r.params) params[k] = v;
  return {{"projection", r.projection}, {"filter", r.filter}, {"params", params}, {"shadow_map", r.mapSize},
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

/// Measures jobs through runBench, remembering every row (in memory and in
/// OUT/evaluations.jsonl) so that a configuration is never measured twice, not even across runs.
class Evaluator {
public:
  Evaluator(gl::Context& context, const TuneRequest& request, const SetupFactory& makeSetup,
            const std::vector<Technique>& techniques)
      : mContext(context), mRequest(request), mMakeSetup(makeSetup), mTechniques(techniques),
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

  size_t measured() const { return mMeasured; }
  size_t resumed() const { return mResumed; }
  const std::string& clock() const { return mClock; }

  /// Seconds one job takes at this image size: measured so far, else guessed.
  double secondsPerJob(int width, int height) const {
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

  size_t unmeasured(const std::vector<Job>& jobs, int width, int height, int frames) const {
    size_t n = 0;
    for (const Job& j : jobs) n += mMemo.contains(key(j, width, height, frames)) ? 0 : 1;
    return n;
  }

  /// One row per job, nothing where the configuration failed or was refused (reported on stderr).
  std::vector<std::optional<TuneRow>> run(const std::vector<Job>& jobs, int width, int height, int frames) {
    std::vector<std::optional<TuneRow>> out(jobs.size());
    std::map<int, std::vector<size_t>> byMap;  // runBench takes one map size per run
    for (size_t i = 0; i < jobs.size(); ++i) {
      const auto it = mMemo.find(key(jobs[i], width, height, frames));
      if (it != mMemo.end()) {
        out[i] = it->second;
        out[i]->error = error(jobs[i], out[i]->metrics);  // a resumed run may ask another objective
        out[i]->isDefault = jobs[i].candidate == defaultCandidate(mTechniques[jobs[i].technique].space);
        if (mLoaded.erase(it->first) > 0) ++mResumed;  // counted once
        continue;
      }
      const Technique& t = mTechniques[jobs[i].technique];
      byMap[tuneMapSize(t.space, jobs[i].candidate, t.defaultMapSize)].push_back(i);
    }
    for (const auto& [mapSize, indices] : byMap) {
      BenchSettings set = mRequest.settings;
      set.width = width;
      set.height = height;
      set.shadowMapSize = mapSize;
      set.timedFrames = frames;
      std::vector<BenchConfig> configs;
      for (const size_t i : indices) configs.push_back(config(jobs[i]));
      const auto start = Clock::now();
      const BenchResults results = runBench(mContext, configs, mMakeSetup,
                                            {.settings = set, .outDir = mRequest.outDir, .progress = false,
                                             .verbose = mRequest.verbose, .microBenchmarks = false});
      if (!results.machine.clock.empty()) mClock = results.machine.clock;
      auto& [seconds, count] = mSeconds[{width, height}];
      seconds += std::chrono::duration<double>(Clock::now() - start).count();
      count += indices.size();
      for (const SkippedConfig& k : results.skipped)
        std::fprintf(stderr, "penumbra tune: %s · %s %s %s: %s\n", k.config.projection.c_str(), k.config.filter.c_str(),
                     k.config.paramsText().c_str(), k.failed ? "failed" : "refused", k.reason.c_str());
      for (size_t n = 0; n < indices.size(); ++n) {
        const auto row = std::find_if(results.rows.begin(), results.rows.end(),
                                      [&](const BenchRow& r) { return sameConfig(r.config, configs[n]); });
        if (row == results.rows.end()) continue;
        TuneRow t = tuneRow(results, *row);
        t.error = error(jobs[indices[n]], t.metrics);
        t.isDefault = jobs[indices[n]].candidate == defaultCandidate(mTechniques[jobs[indices[n]].technique].space);
        remember(key(jobs[indices[n]], width, height, frames), t);
        out[indices[n]] = std::move(t);
        ++mMeasured;
      }
    }
    return out;
  }

private:
  double error(const Job& j, const VisibilityMetrics& m) const {
    const double e = objectiveValue(mRequest.objective, m);
    if (mRequest.objective != TuneObjective::Acne) return e;
    return e + kBiasTieWeight * tuneBiasSize(mTechniques[j.technique].space, j.candidate);
  }

  BenchConfig config(const Job& j) const {
    const Technique& t = mTechniques[j.technique];
    return {.plan = "tune", .scene = mRequest.scene, .projection = t.projection, .filter = t.filter,
            .params = tuneParams(t.space, j.candidate), .inGrid = false};
  }

  std::string key(const Job& j, int width, int height, int frames) const {
    const Technique& t = mTechniques[j.technique];
    return fmt::format("{}|{}|{}x{}|map {}|{} frames|{} samples|{}|{}|{}", mRequest.scene, mRequest.settings.camera, width,
                       height, tuneMapSize(t.space, j.candidate, t.defaultMapSize), frames,
                       mRequest.settings.referenceSamples, t.projection, t.filter, config(j).paramsText());
  }

  TuneRow tuneRow(const BenchResults& results, const BenchRow& b) const {
    TuneRow r;
    r.projection = b.config.projection;
    r.filter = b.config.filter;
    r.params = b.config.params;
    r.mapSize = b.shadowMapSize;
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

  void remember(const std::string& k, const TuneRow& r) {
    mMemo[k] = r;
    nlohmann::json j = rowJson(r);
    j["key"] = k;
    std::ofstream out(mLogPath, std::ios::app);
    out << j.dump() << '\n';  // one line per row, flushed: an interruption loses at most the row in flight
  }

  gl::Context& mContext;
  const TuneRequest& mRequest;
  const SetupFactory& mMakeSetup;
  const std::vector<Technique>& mTechniques;
  std::filesystem::path mLogPath;
  std::string mClock;
  std::map<std::string, TuneRow> mMemo;
  std::set<std::string> mLoaded;  // keys read from an earlier run and not used yet
  size_t mMeasured = 0, mResumed = 0;
  std::map<std::pair<int, int>, std::pair<double, size_t>> mSeconds;  // by image size: seconds, jobs
};

}  // namespace

const char* objectiveKey(TuneObjective o) {
  switch (o) {
    case TuneObjective::Rmse: return "rmse";
    case TuneObjective::PenumbraRmse: return "penumbra_rmse";
    case TuneObjective::Leak: return "leak";
    case TuneObjective::Acne: return "acne";
  }
  return "rmse";
}

TuneObjective parseObjective(std::string_view text) {
  for (const TuneObjective o : {TuneObjective::Rmse, TuneObjective::PenumbraRmse, TuneObjective::Leak, TuneObjective::Acne})
    if (text == objectiveKey(o)) return o;
  throw usageError(fmt::format("--objective {}: expected rmse, penumbra_rmse, leak or acne", text));
}

double objectiveValue(TuneObjective o, const VisibilityMetrics& m) {
  switch (o) {
    case TuneObjective::Rmse: return m.rmse;
    case TuneObjective::PenumbraRmse: return m.penumbraRmse;
    case TuneObjective::Leak: return m.leakPct;
    case TuneObjective::Acne: return m.acnePct <= kMaxAcnePct ? m.umbraLeakPct : kAcneRejectedError + m.acnePct;
  }
  return m.rmse;
}

namespace {

/// What a stage prints on stderr: its name, its configurations, and the run's time left.
void announce(const char* stage, size_t jobs, size_t fresh, int width, int height, double stageSeconds, double leftSeconds) {
  std::fprintf(stderr, "penumbra tune: %s: %zu configurations at %dx%d (%zu to measure, ~%.0f s); about %.0f s left in all\n",
               stage, jobs, width, height, fresh, stageSeconds, leftSeconds);
}

std::vector<TunePoint> points(const std::vector<std::pair<TuneCandidate, TuneRow>>& rows) {
  std::vector<TunePoint> out;
  for (const auto& [c, r] : rows) out.push_back(r.point());
  return out;
}

}  // namespace

TuneResults runTune(gl::Context& context, const TuneRequest& request, const SetupFactory& makeSetup) {
  const auto start = Clock::now();
  const auto elapsed = [&] { return std::chrono::duration<double>(Clock::now() - start).count(); };
  TuneResults res;
  res.request = request;
  res.machine = describeMachine();
  res.machine.glRenderer = context.info().renderer;
  res.machine.glVersion = context.info().version;
  res.machine.glVendor = context.info().vendor;

  std::vector<Technique> techniques;
  for (const std::string& p : request.projections)
    for (const std::string& f : request.filters) {
      BenchSetup s = makeSetup({.plan = "tune", .scene = request.scene, .projection = p, .filter = f, .params = {}, .inGrid = false});
      std::vector<ParamDesc> descs;
      std::vector<float> current;
      for (const Parameterized* owner : {static_cast<const Parameterized*>(s.filter.get()),
                                         static_cast<const Parameterized*>(s.projection.get())})
        for (const ParamDesc& d : owner->paramDescs()) {
          descs.push_back(d);
          current.push_back(owner->param(d.key));
        }
      Technique t;
      t.projection = p;
      t.filter = f;
      t.defaultMapSize = request.settings.shadowMapSize.value_or(s.scene.shadow.mapSize);
      std::vector<std::string> fixed = kFixedKeys;
      if (request.objective == TuneObjective::Acne)  // the filter's bias only, on the default's map
        for (const ParamDesc& d : descs)
          if (!isBiasKey(d.key) || !s.filter->hasParam(d.key)) fixed.emplace_back(d.key);
      t.space = tuneSpace(descs, current, request.objective == TuneObjective::Acne ? 0 : t.defaultMapSize, fixed);
      if (t.space.empty())
        throw usageError(fmt::format("tune: {} · {} has no parameter to search{}", f, p,
                                     request.objective == TuneObjective::Acne ? " (no bias parameter)" : ""));
      t.center = defaultCandidate(t.space);
      techniques.push_back(std::move(t));
    }
  Evaluator eval(context, request, makeSetup, techniques);
  const int fullW = request.settings.width, fullH = request.settings.height;
  // The screen stage's image: the full one's sides divided, its aspect kept, never below the minimum.
  const double screenScale = std::min(1.0, std::max(1.0 / kScreenSizeDivisor,
                                                    static_cast<double>(kMinScreenSidePixels) / std::min(fullW, fullH)));
  const int screenW = static_cast<int>(std::lround(fullW * screenScale));
  const int screenH = static_cast<int>(std::lround(fullH * screenScale));
  const size_t keep = std::max<size_t>(2, static_cast<size_t>(request.candidates / kHalvingDivisor));
  // Rough plan of the full-size configurations from `stage` on, for the estimate of the time left:
  // the promoted, each descent round's neighbours (two per dimension) for the rounds it is
  // expected to take, the confirmed (about half the promoted).
  const auto fullJobsLeft = [&](int stage, int roundsDone) {
    double jobs = 0.0;
    for (const Technique& t : techniques) {
      const int rounds = std::max(1, kExpectedDescentRounds - roundsDone);
      jobs += (stage <= 2 ? static_cast<double>(keep + 1) : 0.0) +
              (stage <= 3 ? 2.0 * static_cast<double>(t.space.size() * static_cast<size_t>(rounds)) : 0.0) +
              static_cast<double>(keep / 2 + 1);
    }
    return jobs;
  };

  // 1. Screen.
  std::vector<Job> jobs;
  for (size_t t = 0; t < techniques.size(); ++t) {
    jobs.push_back({t, defaultCandidate(techniques[t].space)});
    for (TuneCandidate& c : latinHypercube(techniques[t].space, request.candidates, request.seed + t))
      if (c != jobs.back().candidate) jobs.push_back({t, std::move(c)});
  }
  if (request.shard) {  // this machine's share of the screen, then stop: --merge goes on from all shares
    std::vector<Job> share;
    for (size_t i = 0; i < jobs.size(); ++i)
      if (static_cast<int>(i % static_cast<size_t>(request.shard->count)) == request.shard->index - 1) share.push_back(jobs[i]);
    jobs = std::move(share);
  }
  const double screenGuess = static_cast<double>(eval.unmeasured(jobs, screenW, screenH, kScreenFrames)) *
                             eval.secondsPerJob(screenW, screenH);
  announce("1/4 screen", jobs.size(), eval.unmeasured(jobs, screenW, screenH, kScreenFrames), screenW, screenH, screenGuess,
           screenGuess + fullJobsLeft(2, 0) * eval.secondsPerJob(fullW, fullH));
  const std::vector<std::optional<TuneRow>> screened = eval.run(jobs, screenW, screenH, kScreenFrames);
  if (request.shard) {
    res.evaluations = eval.measured();
    res.resumed = eval.resumed();
    res.seconds = elapsed();
    return res;
  }

  // 2. Promote: per technique, the small-size front and the most accurate, and the default.
  std::vector<Job> promoted;
  for (size_t t = 0; t < techniques.size(); ++t) {
    std::vector<size_t> index;
    std::vector<TunePoint> pts;
    for (size_t i = 0; i < jobs.size(); ++i)
      if (jobs[i].technique == t && screened[i]) {
        index.push_back(i);
        pts.push_back(screened[i]->point());
      }
    promoted.push_back({t, defaultCandidate(techniques[t].space)});
    for (const size_t k : halvingSurvivors(pts, keep))
      if (jobs[index[k]].candidate != promoted.back().candidate) promoted.push_back(jobs[index[k]]);
  }
  announce("2/4 full size", promoted.size(), eval.unmeasured(promoted, fullW, fullH, kFullFrames), fullW, fullH,
           static_cast<double>(eval.unmeasured(promoted, fullW, fullH, kFullFrames)) * eval.secondsPerJob(fullW, fullH),
           fullJobsLeft(2, 0) * eval.secondsPerJob(fullW, fullH));
  const std::vector<std::optional<TuneRow>> full = eval.run(promoted, fullW, fullH, kFullFrames);
  for (size_t i = 0; i < promoted.size(); ++i)
    if (full[i]) techniques[promoted[i].technique].full.emplace_back(promoted[i].candidate, *full[i]);

  // The budget: the one given, else (no error target either) the dearest default's own cost.
  TuneBudget budget = request.budget;
  const auto defaultCost = [&](const std::vector<std::pair<TuneCandidate, TuneRow>>& rows, size_t t) {
    std::optional<double> cost;
    for (const auto& [c, r] : rows)
      if (c == defaultCandidate(techniques[t].space)) cost = std::max(cost.value_or(0.0), r.costMs);
    return cost;
  };
  const bool costDecides = request.objective != TuneObjective::Acne;  // a bias costs nothing
  if (!budget.costMs && !budget.maxError && costDecides) {
    for (size_t t = 0; t < techniques.size(); ++t)
      if (const std::optional<double> c = defaultCost(techniques[t].full, t))
        budget.costMs = std::max(budget.costMs.value_or(0.0), *c);
    if (!budget.costMs) throw usageError(fmt::format("tune: no default configuration could be rendered on {}", request.scene));
  }

  // 3. Descend: around each technique's best within the budget, one dimension at a time.
  for (int round = 0; round < kMaxDescentRounds; ++round) {
    std::vector<Job> step;
    for (size_t t = 0; t < techniques.size(); ++t) {
      Technique& tech = techniques[t];
      if (!tech.descending) continue;
      if (const std::optional<size_t> best = pickRecommended(points(tech.full), budget)) tech.center = tech.full[*best].first;
      for (TuneCandidate& c : neighbours(tech.space, tech.center)) {
        const bool seen = std::any_of(tech.full.begin(), tech.full.end(), [&](const auto& e) { return e.first == c; });
        if (!seen) step.push_back({t, std::move(c)});
      }
    }
    if (step.empty()) break;
    const double stepSeconds = static_cast<double>(eval.unmeasured(step, fullW, fullH, kFullFrames)) * eval.secondsPerJob(fullW, fullH);
    const double confirmSeconds = fullJobsLeft(4, 0) * eval.secondsPerJob(fullW, fullH);
    if (elapsed() + stepSeconds + confirmSeconds > request.maxMinutes * kSecondsPerMinute) {
      std::fprintf(stderr, "penumbra tune: descent stopped after %d round(s): --max-minutes %g would pass\n", round,
                   request.maxMinutes);
      break;
    }
    announce(fmt::format("3/4 descent, round {}", round + 1).c_str(), step.size(),
             eval.unmeasured(step, fullW, fullH, kFullFrames), fullW, fullH, stepSeconds,
             fullJobsLeft(3, round) * eval.secondsPerJob(fullW, fullH));
    const std::vector<std::optional<TuneRow>> rows = eval.run(step, fullW, fullH, kFullFrames);
    for (size_t i = 0; i < step.size(); ++i)
      if (rows[i]) techniques[step[i].technique].full.emplace_back(step[i].candidate, *rows[i]);
    for (Technique& tech : techniques) {
      const std::optional<size_t> best = pickRecommended(points(tech.full), budget);
      tech.descending = best && tech.full[*best].first != tech.center;
    }
  }

  // 4. Confirm: each technique's full-size front within the memory budget, its best within
  // the budget and its default, measured again with more frames.
  std::vector<Job> finalists;
  for (size_t t = 0; t < techniques.size(); ++t) {
    const Technique& tech = techniques[t];
    for (const TuneRow& r : [&] {
           std::vector<TuneRow> rows;
           for (const auto& [c, row] : tech.full) rows.push_back(row);
           return rows;
         }())
      res.explored.push_back(r);
    std::vector<TuneCandidate> picks = {defaultCandidate(tech.space)};
    for (const size_t i : tuneFront(points(tech.full), budget.memoryMiB)) picks.push_back(tech.full[i].first);
    if (const std::optional<size_t> best = pickRecommended(points(tech.full), budget)) picks.push_back(tech.full[*best].first);
    for (TuneCandidate& c : picks) {
      const bool dup = std::any_of(finalists.begin(), finalists.end(), [&](const Job& j) { return j.technique == t && j.candidate == c; });
      if (!dup) finalists.push_back({t, std::move(c)});
    }
  }
  const double confirmSeconds =
      static_cast<double>(eval.unmeasured(finalists, fullW, fullH, kConfirmFrames)) * eval.secondsPerJob(fullW, fullH);
  announce("4/4 confirm", finalists.size(), eval.unmeasured(finalists, fullW, fullH, kConfirmFrames), fullW, fullH,
           confirmSeconds, confirmSeconds);
  const std::vector<std::optional<TuneRow>> confirmed = eval.run(finalists, fullW, fullH, kConfirmFrames);
  for (size_t i = 0; i < finalists.size(); ++i) {
    if (!confirmed[i]) continue;
    if (confirmed[i]->isDefault) res.defaults.push_back(res.confirmed.size());
    res.confirmed.push_back(*confirmed[i]);
  }
  if (res.defaults.empty()) throw usageError(fmt::format("tune: no default configuration could be rendered on {}", request.scene));
  if (!request.budget.costMs && !request.budget.maxError && costDecides) {
    budget.costMs.reset();
    for (const size_t d : res.defaults) budget.costMs = std::max(budget.costMs.value_or(0.0), res.confirmed[d].costMs);
  }
  std::vector<TunePoint> pts;
  for (const TuneRow& r : res.confirmed) pts.push_back(r.point());
  res.front = tuneFront(pts, budget.memoryMiB);
  res.recommended = pickRecommended(pts, budget);
  if (res.recommended && request.objective == TuneObjective::Acne && pts[*res.recommended].error >= kAcneRejectedError)
    res.recommended.reset();  // every configuration has acne
  res.budgetMs = budget.costMs.value_or(0.0);
  res.evaluations = eval.measured();
  res.resumed = eval.resumed();
  res.machine.clock = eval.clock();
  res.seconds = elapsed();
  res.machine.loadEnd = loadAverage();
  return res;
}

}  // namespace penumbra::report
