#include "tuner/TuneRunner.h"

#include "platform/Context.h"
#include "tuner/TuneEvaluator.h"
#include "techniques/Registry.h"

#include <penumbra/Error.h>

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

namespace penumbra::report {
namespace {

using Clock = std::chrono::steady_clock;

// Parameters that trade something a still frame does not measure: left at their defaults.
// csm.stabilize trades shimmer under a moving camera against resolution.
const std::vector<std::string> kFixedKeys = {"csm.stabilize"};

constexpr double kSecondsPerMinute = 60.0;

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

const char* aggregateKey(TuneAggregate a) { return a == TuneAggregate::Worst ? "worst" : "mean"; }

TuneAggregate parseAggregate(std::string_view text) {
  for (const TuneAggregate a : {TuneAggregate::Worst, TuneAggregate::Mean})
    if (text == aggregateKey(a)) return a;
  throw usageError(fmt::format("--aggregate {}: expected worst or mean", text));
}

const char* costKey(TuneCost c) { return c == TuneCost::Measured ? "measured" : "model"; }

TuneCost parseCost(std::string_view text) {
  for (const TuneCost c : {TuneCost::Measured, TuneCost::Model})
    if (text == costKey(c)) return c;
  throw usageError(fmt::format("--cost {}: expected measured or model", text));
}

bool withinBars(const VisibilityMetrics& m, const VisibilityMetrics& def) {
  return m.acnePct <= std::max(kMaxAcnePct, def.acnePct) && m.umbraLeakPct <= def.umbraLeakPct + kUmbraLeakSlackPct;
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

// One technique's rows as the search sees them, each marked within or beyond the bars against
// the technique's default among them.
std::vector<TunePoint> points(const std::vector<std::pair<TuneCandidate, TuneRow>>& rows, TuneCost cost, bool allowArtifacts) {
  const auto def = std::find_if(rows.begin(), rows.end(), [](const auto& e) { return e.second.isDefault; });
  std::vector<TunePoint> out;
  for (const auto& [c, r] : rows) {
    TunePoint p = r.point(cost);
    p.withinBars = allowArtifacts || def == rows.end() || withinBars(r.metrics, def->second.metrics);
    out.push_back(p);
  }
  return out;
}

// The confirmed rows' costs from interleaved rounds: ms[view][row][round]. Per view, a row's cost
// stats over the rounds and its per-round ratio to the budget's default (the dearest default on
// that view); then aggregated over the views. The budget is checked at the upper end: against a
// budget in ms the cost's p90; against the default's cost the ratio's p90 times that default's
// median (a row fits when its ratio's p90 ≤ 1: never over the budget within the noise).
// Returns the budget's default's median cost (aggregated over the views).
double confirmCosts(TuneResults& res, const std::vector<std::vector<std::vector<double>>>& ms, TuneAggregate aggregate,
                    std::optional<double> budgetMs) {
  const auto over = [&](const std::vector<double>& values) {
    if (aggregate == TuneAggregate::Worst) return *std::max_element(values.begin(), values.end());
    double sum = 0.0;
    for (const double v : values) sum += v;
    return sum / static_cast<double>(values.size());
  };
  std::vector<std::vector<TimeStats>> cost(res.confirmed.size()), ratio(res.confirmed.size());
  std::vector<double> referenceMedian;
  for (size_t v = 0; v < ms.size(); ++v) {
    size_t ref = res.defaults.front();
    for (const size_t d : res.defaults)
      if (timeStats(ms[v][d]).median > timeStats(ms[v][ref]).median) ref = d;
    referenceMedian.push_back(timeStats(ms[v][ref]).median);
    for (size_t i = 0; i < res.confirmed.size(); ++i) {
      std::vector<double> r;
      for (size_t k = 0; k < ms[v][i].size() && k < ms[v][ref].size(); ++k)
        if (ms[v][ref][k] > 0.0) r.push_back(ms[v][i][k] / ms[v][ref][k]);
      cost[i].push_back(timeStats(ms[v][i]));
      ratio[i].push_back(timeStats(r));
      if (v < res.confirmed[i].views.size()) {
        TuneRow& view = res.confirmed[i].views[v];
        view.costMs = cost[i].back().median;
        view.costP10Ms = cost[i].back().p10;
        view.costP90Ms = cost[i].back().p90;
      }
    }
  }
  const double reference = over(referenceMedian);
  for (size_t i = 0; i < res.confirmed.size(); ++i) {
    TuneRow& r = res.confirmed[i];
    const auto field = [&](const std::vector<TimeStats>& s, double TimeStats::*m) {
      std::vector<double> values;
      for (const TimeStats& t : s) values.push_back(t.*m);
      return over(values);
    };
    r.costMs = field(cost[i], &TimeStats::median);
    r.costP10Ms = field(cost[i], &TimeStats::p10);
    r.costP90Ms = field(cost[i], &TimeStats::p90);
    r.costRatio = {field(ratio[i], &TimeStats::median), field(ratio[i], &TimeStats::p10), field(ratio[i], &TimeStats::p90)};
    r.rounds = ms.empty() ? 0 : static_cast<int>(ms.front()[i].size());
    r.budgetCostMs = budgetMs ? r.costP90Ms : r.costRatio.p90 * reference;
  }
  return reference;
}

// The kinds of light that cast shadows in any view's scene (ParamDesc::lights bits).
unsigned sceneLightBits(const TuneRequest& request, const TuneSetupFactory& makeSetup) {
  unsigned bits = 0;
  for (const TuneView& v : request.views) {
    const BenchSetup s = makeSetup({.plan = "tune", .scene = v.scene, .projection = request.projections.front(),
                                    .filter = request.filters.front(), .params = {}, .inGrid = false},
                                   v.camera);
    for (const Light& l : s.scene.lights)
      if (l.castsShadow) bits |= lightKindBit(l.type);
  }
  return bits;
}

// The default configuration's maps on the first view: its side, and the texels of every shadowed
// light's maps at that side (its views counted as the renderer will make them), which is what a
// map budget must hold to leave the default unchanged.
TuneMapDefault defaultMaps(const BenchSetup& s, int mapSize, int width, int height) {
  TuneMapDefault maps{.size = mapSize, .texels = 0};
  const SceneExtent extent = s.scene.extent();
  const float aspect = static_cast<float>(width) / static_cast<float>(height);
  Technique base = s.technique;
  base.setMapSize(mapSize);
  for (const Light& l : s.scene.lights) {
    const Technique t = base.forLight(l.shadow, "");  // the light's own technique, as the core runs it
    if (!l.castsShadow || !t.problemWith(l).empty()) continue;
    const int side = t.mapSize();
    const auto views = static_cast<int64_t>(makeProjection(t)->computeFrusta(s.scene.camera, aspect, l, extent, side).views.size());
    maps.texels += views * side * side;
  }
  return maps;
}

}  // namespace

TuneResults runTune(gl::Context& context, const TuneRequest& request, const TuneSetupFactory& makeSetup) {
  PN_CHECK(!request.views.empty(), "runTune: at least one view");
  const auto start = Clock::now();
  const auto elapsed = [&] { return std::chrono::duration<double>(Clock::now() - start).count(); };
  TuneResults res;
  res.request = request;
  res.machine = describeMachine(context.info());
  const TuneCost cost = request.cost;

  std::vector<TuneTechnique> techniques;
  const TuneView& first = request.views.front();
  // A parameter of a light kind no view has cannot change a frame: it is not searched.
  const unsigned lightBits = sceneLightBits(request, makeSetup);
  for (const std::string& p : request.projections)
    for (const std::string& f : request.filters) {
      BenchSetup s = makeSetup({.plan = "tune", .scene = first.scene, .projection = p, .filter = f, .params = {}, .inGrid = false},
                               first.camera);
      std::vector<ParamDesc> descs;
      std::vector<float> current;
      TuneTechnique t;
      for (const Parameterized* owner : {&s.technique.filterValues(), &s.technique.projectionValues()})
        for (const ParamDesc& d : owner->paramDescs()) {
          descs.push_back(d);
          current.push_back(owner->param(d.key));
          if (d.unit == kTapsUnit) t.taps.emplace_back(std::string(d.key), current.back());
        }
      t.projection = p;
      t.filter = f;
      const int mapSize = request.settings.shadowMapSize.value_or(s.scene.shadow.mapSize);
      t.maps = defaultMaps(s, mapSize, request.settings.width, request.settings.height);
      std::vector<std::string> fixed = kFixedKeys;
      for (const ParamDesc& d : descs)
        if ((d.lights & lightBits) == 0) fixed.emplace_back(d.key);
      if (request.objective == TuneObjective::Acne)  // the filter's bias only, on the default's maps
        for (const ParamDesc& d : descs)
          if (!isBiasKey(d.key) || s.technique.owner(d.key) != ParamOwner::Filter) fixed.emplace_back(d.key);
      if (!request.searchKeys.empty()) {  // --params: the rest stays at the default
        for (const ParamDesc& d : descs)
          if (std::find(request.searchKeys.begin(), request.searchKeys.end(), d.key) == request.searchKeys.end())
            fixed.emplace_back(d.key);
        for (const std::string_view key : {kMapSizeKey, kMapBudgetKey})
          if (std::find(request.searchKeys.begin(), request.searchKeys.end(), key) == request.searchKeys.end())
            fixed.emplace_back(key);
      }
      const TuneMapDefault searchedMaps = request.objective == TuneObjective::Acne ? TuneMapDefault{} : t.maps;
      t.space = tuneSpace(descs, current, searchedMaps, fixed);
      if (t.space.empty())
        throw usageError(fmt::format("tune: {} · {} has no parameter to search{}", f, p,
                                     request.objective == TuneObjective::Acne ? " (no bias parameter)"
                                     : request.searchKeys.empty()            ? ""
                                                                             : " among --params " + joinNames(request.searchKeys, ",")));
      t.center = defaultCandidate(t.space);
      techniques.push_back(std::move(t));
    }
  TuneProgress progress(request.progress);
  TuneEvaluator eval(context, request, makeSetup, techniques, progress);
  const int fullW = request.settings.width, fullH = request.settings.height;
  // The screen stage's image: the full one's sides divided, its aspect kept, never below the minimum.
  const double screenScale = std::min(1.0, std::max(1.0 / kScreenSizeDivisor,
                                                    static_cast<double>(kMinScreenSidePixels) / std::min(fullW, fullH)));
  const int screenW = static_cast<int>(std::lround(fullW * screenScale));
  const int screenH = static_cast<int>(std::lround(fullH * screenScale));
  const size_t keep = std::max<size_t>(2, static_cast<size_t>(request.candidates / kHalvingDivisor));
  const auto views = static_cast<double>(request.views.size());
  // Rough plan of the full-size measurements from `stage` on, for the estimate of the time left:
  // the promoted, each descent round's neighbours (two per dimension) for the rounds it is
  // expected to take, the confirmed (about half the promoted); each on every view.
  const auto fullSecondsLeft = [&](int stage, int roundsDone) {
    double jobs = 0.0;
    for (const TuneTechnique& t : techniques) {
      const int rounds = std::max(1, kExpectedDescentRounds - roundsDone);
      jobs += (stage <= 2 ? static_cast<double>(keep + 1) : 0.0) +
              (stage <= 3 ? 2.0 * static_cast<double>(t.space.size() * static_cast<size_t>(rounds)) : 0.0) +
              static_cast<double>(keep / 2 + 1);
    }
    return jobs * views * eval.secondsPerJob(fullW, fullH);
  };

  // 1. Screen.
  std::vector<TuneJob> jobs;
  for (size_t t = 0; t < techniques.size(); ++t) {
    jobs.push_back({t, defaultCandidate(techniques[t].space)});
    for (TuneCandidate& c : latinHypercube(techniques[t].space, request.candidates, request.seed + t))
      if (c != jobs.back().candidate) jobs.push_back({t, std::move(c)});
  }
  if (request.shard) {  // this machine's share of the screen, then stop: --merge goes on from all shares
    std::vector<TuneJob> share;
    for (size_t i = 0; i < jobs.size(); ++i)
      if (static_cast<int>(i % static_cast<size_t>(request.shard->count)) == request.shard->index - 1) share.push_back(jobs[i]);
    jobs = std::move(share);
  }
  progress.stage("1/4 screen", eval.unmeasured(jobs, screenW, screenH, kScreenFrames), request.shard ? 0.0 : fullSecondsLeft(2, 0));
  const std::vector<std::optional<TuneRow>> screened = eval.run(jobs, screenW, screenH, kScreenFrames);
  if (request.shard) {
    progress.finish();
    res.evaluations = eval.measured();
    res.resumed = eval.resumed();
    res.seconds = elapsed();
    return res;
  }

  // 2. Promote: per technique, the small-size front and the most accurate, and the default.
  std::vector<TuneJob> promoted;
  for (size_t t = 0; t < techniques.size(); ++t) {
    std::vector<size_t> index;
    std::vector<std::pair<TuneCandidate, TuneRow>> rows;
    for (size_t i = 0; i < jobs.size(); ++i)
      if (jobs[i].technique == t && screened[i]) {
        index.push_back(i);
        rows.emplace_back(jobs[i].candidate, *screened[i]);
      }
    const std::vector<TunePoint> pts = points(rows, cost, request.allowArtifacts);
    promoted.push_back({t, defaultCandidate(techniques[t].space)});
    for (const size_t k : halvingSurvivors(pts, keep))
      if (jobs[index[k]].candidate != promoted.back().candidate) promoted.push_back(jobs[index[k]]);
  }
  progress.stage("2/4 full size", eval.unmeasured(promoted, fullW, fullH, kFullFrames), fullSecondsLeft(3, 0));
  const std::vector<std::optional<TuneRow>> full = eval.run(promoted, fullW, fullH, kFullFrames);
  for (size_t i = 0; i < promoted.size(); ++i)
    if (full[i]) techniques[promoted[i].technique].full.emplace_back(promoted[i].candidate, *full[i]);

  // The budget: the one given, else (no error target either) the dearest default's own cost.
  TuneBudget budget = request.budget;
  const auto defaultCost = [&](const std::vector<std::pair<TuneCandidate, TuneRow>>& rows, size_t t) {
    std::optional<double> c;
    for (const auto& [cand, r] : rows)
      if (cand == defaultCandidate(techniques[t].space)) c = std::max(c.value_or(0.0), r.point(cost).costMs);
    return c;
  };
  const bool costDecides = request.objective != TuneObjective::Acne;  // a bias costs nothing
  const std::string firstScene = first.scene;
  if (!budget.costMs && !budget.maxError && costDecides) {
    for (size_t t = 0; t < techniques.size(); ++t)
      if (const std::optional<double> c = defaultCost(techniques[t].full, t))
        budget.costMs = std::max(budget.costMs.value_or(0.0), *c);
    if (!budget.costMs) throw usageError(fmt::format("tune: no default configuration could be rendered on {}", firstScene));
  }

  // 3. Descend: around each technique's best within the budget, one dimension at a time.
  for (int round = 0; round < kMaxDescentRounds; ++round) {
    std::vector<TuneJob> step;
    for (size_t t = 0; t < techniques.size(); ++t) {
      TuneTechnique& tech = techniques[t];
      if (!tech.descending) continue;
      if (const std::optional<size_t> best = pickRecommended(points(tech.full, cost, request.allowArtifacts), budget)) tech.center = tech.full[*best].first;
      for (TuneCandidate& c : neighbours(tech.space, tech.center)) {
        const bool seen = std::any_of(tech.full.begin(), tech.full.end(), [&](const auto& e) { return e.first == c; });
        if (!seen) step.push_back({t, std::move(c)});
      }
    }
    if (step.empty()) break;
    const size_t fresh = eval.unmeasured(step, fullW, fullH, kFullFrames);
    const double stepSeconds = static_cast<double>(fresh) * eval.secondsPerJob(fullW, fullH);
    // A deterministic run (--cost model) must not stop on the clock: its rounds are its own.
    if (cost == TuneCost::Measured && elapsed() + stepSeconds + fullSecondsLeft(4, 0) > request.maxMinutes * kSecondsPerMinute) {
      progress.finish();
      std::fprintf(stderr, "penumbra tune: descent stopped after %d round(s): --max-minutes %g would pass\n", round,
                   request.maxMinutes);
      break;
    }
    progress.stage(fmt::format("3/4 descent, round {}", round + 1), fresh, fullSecondsLeft(4, 0) +
                   std::max(0, kExpectedDescentRounds - round - 1) * stepSeconds);
    const std::vector<std::optional<TuneRow>> rows = eval.run(step, fullW, fullH, kFullFrames);
    for (size_t i = 0; i < step.size(); ++i)
      if (rows[i]) techniques[step[i].technique].full.emplace_back(step[i].candidate, *rows[i]);
    // The combined move: every dimension whose step improved on the centre (within the budget), at once.
    std::vector<TuneJob> combined;
    for (size_t t = 0; t < techniques.size(); ++t) {
      const TuneTechnique& tech = techniques[t];
      const auto centre = std::find_if(tech.full.begin(), tech.full.end(), [&](const auto& e) { return e.first == tech.center; });
      if (centre == tech.full.end()) continue;
      const auto def = std::find_if(tech.full.begin(), tech.full.end(), [](const auto& e) { return e.second.isDefault; });
      std::vector<std::pair<double, TuneCandidate>> better;
      for (size_t i = 0; i < step.size(); ++i) {
        if (step[i].technique != t || !rows[i]) continue;
        TunePoint p = rows[i]->point(cost);
        p.withinBars = request.allowArtifacts || def == tech.full.end() || withinBars(rows[i]->metrics, def->second.metrics);
        if (pickRecommended(std::vector<TunePoint>{p}, budget) && p.error < centre->second.point(cost).error)
          better.emplace_back(p.error, step[i].candidate);
      }
      std::stable_sort(better.begin(), better.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
      std::vector<TuneCandidate> moves;
      for (auto& [e, c] : better) moves.push_back(std::move(c));
      if (std::optional<TuneCandidate> c = combinedMove(tech.center, moves))
        if (std::none_of(tech.full.begin(), tech.full.end(), [&](const auto& e) { return e.first == *c; }))
          combined.push_back({t, std::move(*c)});
    }
    if (!combined.empty()) {
      progress.stage(fmt::format("3/4 descent, round {} combined", round + 1), eval.unmeasured(combined, fullW, fullH, kFullFrames),
                     fullSecondsLeft(4, 0) + std::max(0, kExpectedDescentRounds - round - 1) * stepSeconds);
      const std::vector<std::optional<TuneRow>> moved = eval.run(combined, fullW, fullH, kFullFrames);
      for (size_t i = 0; i < combined.size(); ++i)
        if (moved[i]) techniques[combined[i].technique].full.emplace_back(combined[i].candidate, *moved[i]);
    }
    for (TuneTechnique& tech : techniques) {
      const std::optional<size_t> best = pickRecommended(points(tech.full, cost, request.allowArtifacts), budget);
      tech.descending = best && tech.full[*best].first != tech.center;
    }
  }

  // 4. Confirm: each technique's full-size front within the memory budget, its best within the
  // budget and its default. Their errors are the full-size rows' (the frames are deterministic);
  // with the measured cost, their costs are timed again in interleaved rounds on every view, each
  // technique's default among them, and the budget is checked at the upper end of each spread.
  std::vector<TuneJob> finalists;
  for (size_t t = 0; t < techniques.size(); ++t) {
    const TuneTechnique& tech = techniques[t];
    for (const auto& [c, row] : tech.full) res.explored.push_back(row);
    const std::vector<TunePoint> pts = points(tech.full, cost, request.allowArtifacts);
    std::vector<TuneCandidate> picks = {defaultCandidate(tech.space)};
    for (const size_t i : tuneFront(pts, budget.memoryMiB)) picks.push_back(tech.full[i].first);
    if (const std::optional<size_t> best = pickRecommended(pts, budget)) picks.push_back(tech.full[*best].first);
    for (TuneCandidate& c : picks) {
      const bool dup = std::any_of(finalists.begin(), finalists.end(), [&](const TuneJob& j) { return j.technique == t && j.candidate == c; });
      if (!dup) finalists.push_back({t, std::move(c)});
    }
  }
  const std::vector<std::optional<TuneRow>> confirmed = eval.run(finalists, fullW, fullH, kFullFrames);  // read back
  std::vector<size_t> finalistOf;  // per confirmed row, its finalist
  for (size_t i = 0; i < finalists.size(); ++i) {
    if (!confirmed[i]) continue;
    if (confirmed[i]->isDefault) res.defaults.push_back(res.confirmed.size());
    res.confirmed.push_back(*confirmed[i]);
    finalistOf.push_back(i);
  }
  if (res.defaults.empty()) throw usageError(fmt::format("tune: no default configuration could be rendered on {}", firstScene));
  for (TuneRow& r : res.confirmed)  // the bars against the technique's own default
    for (const size_t d : res.defaults)
      if (res.confirmed[d].filter == r.filter && res.confirmed[d].projection == r.projection)
        r.withinBars = request.allowArtifacts || withinBars(r.metrics, res.confirmed[d].metrics);
  const bool defaultBudget = !request.budget.costMs && !request.budget.maxError && costDecides;
  if (cost == TuneCost::Measured) {
    std::vector<TuneJob> timed;
    for (const size_t f : finalistOf) timed.push_back(finalists[f]);
    progress.stage(fmt::format("4/4 confirm, {} interleaved rounds", kConfirmRounds), timed.size() * request.views.size(), 0.0);
    const std::vector<std::vector<std::vector<double>>> ms = eval.timeRounds(timed, fullW, fullH, kConfirmRounds);
    const double reference = confirmCosts(res, ms, request.aggregate, defaultBudget ? std::optional<double>() : request.budget.costMs);
    progress.finish();
    if (defaultBudget) budget.costMs = reference;  // the dearest default's, timed in the same rounds
  } else if (defaultBudget) {
    budget.costMs.reset();
    for (const size_t d : res.defaults) budget.costMs = std::max(budget.costMs.value_or(0.0), res.confirmed[d].point(cost).costMs);
  }
  std::vector<TunePoint> pts;
  for (const TuneRow& r : res.confirmed) pts.push_back(r.point(cost));
  res.front = tuneFront(pts, budget.memoryMiB);
  res.recommended = pickRecommended(pts, budget);
  if (res.recommended && request.objective == TuneObjective::Acne && pts[*res.recommended].error >= kAcneRejectedError)
    res.recommended.reset();  // every configuration has acne
  res.budget = budget.costMs.value_or(0.0);
  res.evaluations = eval.measured();
  res.resumed = eval.resumed();
  res.machine.clock = eval.clock();
  res.seconds = elapsed();
  res.machine.loadEnd = loadAverage();
  return res;
}

}  // namespace penumbra::report
