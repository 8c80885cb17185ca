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

// The parameters a technique's search leaves at their defaults.
std::vector<std::string> fixedKeys(const TuneRequest& request, const BenchSetup& s, const std::vector<ParamDesc>& descs,
                                   unsigned lightBits) {
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
  return fixed;
}

// One projection × filter as the search sees it: its space of parameters and maps, its default
// maps and tap counts, its centre at the default.
TuneTechnique tuneTechnique(const TuneRequest& request, const TuneSetupFactory& makeSetup, const std::string& p,
                            const std::string& f, unsigned lightBits) {
  const TuneView& first = request.views.front();
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
  const std::vector<std::string> fixed = fixedKeys(request, s, descs, lightBits);
  const TuneMapDefault searchedMaps = request.objective == TuneObjective::Acne ? TuneMapDefault{} : t.maps;
  t.space = tuneSpace(descs, current, searchedMaps, fixed);
  if (t.space.empty())
    throw usageError(fmt::format("tune: {} · {} has no parameter to search{}", f, p,
                                 request.objective == TuneObjective::Acne ? " (no bias parameter)"
                                 : request.searchKeys.empty()            ? ""
                                                                         : " among --params " + joinNames(request.searchKeys, ",")));
  t.center = defaultCandidate(t.space);
  return t;
}

// Every projection × filter of the request.
std::vector<TuneTechnique> tuneTechniques(const TuneRequest& request, const TuneSetupFactory& makeSetup) {
  std::vector<TuneTechnique> techniques;
  // A parameter of a light kind no view has cannot change a frame: it is not searched.
  const unsigned lightBits = sceneLightBits(request, makeSetup);
  for (const std::string& p : request.projections)
    for (const std::string& f : request.filters) techniques.push_back(tuneTechnique(request, makeSetup, p, f, lightBits));
  return techniques;
}

// The state the search's stages share: the request, the techniques with their full-size rows so
// far, the evaluator, the progress line and the image sizes of the screen and full-size stages.
class TuneStages {
public:
  TuneStages(const TuneRequest& request, std::vector<TuneTechnique>& techniques, TuneEvaluator& eval, TuneProgress& progress,
             Clock::time_point start);

  double elapsed() const { return std::chrono::duration<double>(Clock::now() - mStart).count(); }
  std::vector<TuneJob> screenJobs() const;
  std::vector<std::optional<TuneRow>> screen(const std::vector<TuneJob>& jobs);
  std::vector<TuneJob> promote(const std::vector<TuneJob>& jobs, const std::vector<std::optional<TuneRow>>& screened) const;
  void measureFull(const std::vector<TuneJob>& promoted);
  TuneBudget budget() const;
  void descend(const TuneBudget& budget);
  std::vector<TuneJob> finalists(TuneResults& res, const TuneBudget& budget) const;
  std::vector<size_t> readBack(TuneResults& res, const std::vector<TuneJob>& finalists);
  void timeConfirmed(TuneResults& res, TuneBudget& budget, const std::vector<TuneJob>& finalists,
                     const std::vector<size_t>& finalistOf);
  void pick(TuneResults& res, const TuneBudget& budget) const;

private:
  double fullSecondsLeft(int stage, int roundsDone) const;
  std::vector<TuneJob> descentStep(const TuneBudget& budget);
  std::vector<TuneJob> combinedMoves(const std::vector<TuneJob>& step, const std::vector<std::optional<TuneRow>>& rows,
                                     const TuneBudget& budget) const;
  void keepFull(const std::vector<TuneJob>& jobs, const std::vector<std::optional<TuneRow>>& rows);
  // Whether a default budget (neither --budget-ms nor --max-error) is made from the defaults' cost.
  bool defaultBudget() const { return !mRequest.budget.costMs && !mRequest.budget.maxError && costDecides(); }
  bool costDecides() const { return mRequest.objective != TuneObjective::Acne; }  // a bias costs nothing

  const TuneRequest& mRequest;
  std::vector<TuneTechnique>& mTechniques;
  TuneEvaluator& mEval;
  TuneProgress& mProgress;
  Clock::time_point mStart;
  TuneCost mCost;
  int mFullW, mFullH, mScreenW = 0, mScreenH = 0;
  size_t mKeep;
};

TuneStages::TuneStages(const TuneRequest& request, std::vector<TuneTechnique>& techniques, TuneEvaluator& eval,
                       TuneProgress& progress, Clock::time_point start)
    : mRequest(request), mTechniques(techniques), mEval(eval), mProgress(progress), mStart(start), mCost(request.cost),
      mFullW(request.settings.width), mFullH(request.settings.height),
      mKeep(std::max<size_t>(2, static_cast<size_t>(request.candidates / kHalvingDivisor))) {
  // The screen stage's image: the full one's sides divided, its aspect kept, never below the minimum.
  const double screenScale = std::min(1.0, std::max(1.0 / kScreenSizeDivisor,
                                                    static_cast<double>(kMinScreenSidePixels) / std::min(mFullW, mFullH)));
  mScreenW = static_cast<int>(std::lround(mFullW * screenScale));
  mScreenH = static_cast<int>(std::lround(mFullH * screenScale));
}

// Rough plan of the full-size measurements from `stage` on, for the estimate of the time left:
// the promoted, each descent round's neighbours (two per dimension) for the rounds it is
// expected to take, the confirmed (about half the promoted); each on every view.
double TuneStages::fullSecondsLeft(int stage, int roundsDone) const {
  const auto views = static_cast<double>(mRequest.views.size());
  double jobs = 0.0;
  for (const TuneTechnique& t : mTechniques) {
    const int rounds = std::max(1, kExpectedDescentRounds - roundsDone);
    jobs += (stage <= 2 ? static_cast<double>(mKeep + 1) : 0.0) +
            (stage <= 3 ? 2.0 * static_cast<double>(t.space.size() * static_cast<size_t>(rounds)) : 0.0) +
            static_cast<double>(mKeep / 2 + 1);
  }
  return jobs * views * mEval.secondsPerJob(mFullW, mFullH);
}

// The screen's jobs: per technique its default and its Latin-hypercube candidates; with --shard
// only this machine's share.
std::vector<TuneJob> TuneStages::screenJobs() const {
  std::vector<TuneJob> jobs;
  for (size_t t = 0; t < mTechniques.size(); ++t) {
    jobs.push_back({t, defaultCandidate(mTechniques[t].space)});
    for (TuneCandidate& c : latinHypercube(mTechniques[t].space, mRequest.candidates, mRequest.seed + t))
      if (c != jobs.back().candidate) jobs.push_back({t, std::move(c)});
  }
  if (mRequest.shard) {  // this machine's share of the screen, then stop: --merge goes on from all shares
    std::vector<TuneJob> share;
    for (size_t i = 0; i < jobs.size(); ++i)
      if (static_cast<int>(i % static_cast<size_t>(mRequest.shard->count)) == mRequest.shard->index - 1) share.push_back(jobs[i]);
    jobs = std::move(share);
  }
  return jobs;
}

std::vector<std::optional<TuneRow>> TuneStages::screen(const std::vector<TuneJob>& jobs) {
  mProgress.stage("1/4 screen", mEval.unmeasured(jobs, mScreenW, mScreenH, kScreenFrames),
                  mRequest.shard ? 0.0 : fullSecondsLeft(2, 0));
  return mEval.run(jobs, mScreenW, mScreenH, kScreenFrames);
}

// Per technique, the small-size front and the most accurate, and the default.
std::vector<TuneJob> TuneStages::promote(const std::vector<TuneJob>& jobs, const std::vector<std::optional<TuneRow>>& screened) const {
  std::vector<TuneJob> promoted;
  for (size_t t = 0; t < mTechniques.size(); ++t) {
    std::vector<size_t> index;
    std::vector<std::pair<TuneCandidate, TuneRow>> rows;
    for (size_t i = 0; i < jobs.size(); ++i)
      if (jobs[i].technique == t && screened[i]) {
        index.push_back(i);
        rows.emplace_back(jobs[i].candidate, *screened[i]);
      }
    const std::vector<TunePoint> pts = points(rows, mCost, mRequest.allowArtifacts);
    promoted.push_back({t, defaultCandidate(mTechniques[t].space)});
    for (const size_t k : halvingSurvivors(pts, mKeep))
      if (jobs[index[k]].candidate != promoted.back().candidate) promoted.push_back(jobs[index[k]]);
  }
  return promoted;
}

// Each measured row joins its technique's full-size rows.
void TuneStages::keepFull(const std::vector<TuneJob>& jobs, const std::vector<std::optional<TuneRow>>& rows) {
  for (size_t i = 0; i < jobs.size(); ++i)
    if (rows[i]) mTechniques[jobs[i].technique].full.emplace_back(jobs[i].candidate, *rows[i]);
}

void TuneStages::measureFull(const std::vector<TuneJob>& promoted) {
  mProgress.stage("2/4 full size", mEval.unmeasured(promoted, mFullW, mFullH, kFullFrames), fullSecondsLeft(3, 0));
  keepFull(promoted, mEval.run(promoted, mFullW, mFullH, kFullFrames));
}

// The budget: the one given, else (no error target either) the dearest default's own cost.
TuneBudget TuneStages::budget() const {
  TuneBudget budget = mRequest.budget;
  const auto defaultCost = [&](const std::vector<std::pair<TuneCandidate, TuneRow>>& rows, size_t t) {
    std::optional<double> c;
    for (const auto& [cand, r] : rows)
      if (cand == defaultCandidate(mTechniques[t].space)) c = std::max(c.value_or(0.0), r.point(mCost).costMs);
    return c;
  };
  if (!budget.costMs && !budget.maxError && costDecides()) {
    for (size_t t = 0; t < mTechniques.size(); ++t)
      if (const std::optional<double> c = defaultCost(mTechniques[t].full, t))
        budget.costMs = std::max(budget.costMs.value_or(0.0), *c);
    if (!budget.costMs)
      throw usageError(fmt::format("tune: no default configuration could be rendered on {}", mRequest.views.front().scene));
  }
  return budget;
}

// A descent round's jobs: each descending technique's centre moved to its best within the budget,
// and that centre's neighbours not measured yet.
std::vector<TuneJob> TuneStages::descentStep(const TuneBudget& budget) {
  std::vector<TuneJob> step;
  for (size_t t = 0; t < mTechniques.size(); ++t) {
    TuneTechnique& tech = mTechniques[t];
    if (!tech.descending) continue;
    if (const std::optional<size_t> best = pickRecommended(points(tech.full, mCost, mRequest.allowArtifacts), budget)) tech.center = tech.full[*best].first;
    for (TuneCandidate& c : neighbours(tech.space, tech.center)) {
      const bool seen = std::any_of(tech.full.begin(), tech.full.end(), [&](const auto& e) { return e.first == c; });
      if (!seen) step.push_back({t, std::move(c)});
    }
  }
  return step;
}

// The combined move: every dimension whose step improved on the centre (within the budget), at once.
std::vector<TuneJob> TuneStages::combinedMoves(const std::vector<TuneJob>& step, const std::vector<std::optional<TuneRow>>& rows,
                                               const TuneBudget& budget) const {
  std::vector<TuneJob> combined;
  for (size_t t = 0; t < mTechniques.size(); ++t) {
    const TuneTechnique& tech = mTechniques[t];
    const auto centre = std::find_if(tech.full.begin(), tech.full.end(), [&](const auto& e) { return e.first == tech.center; });
    if (centre == tech.full.end()) continue;
    const auto def = std::find_if(tech.full.begin(), tech.full.end(), [](const auto& e) { return e.second.isDefault; });
    std::vector<std::pair<double, TuneCandidate>> better;
    for (size_t i = 0; i < step.size(); ++i) {
      if (step[i].technique != t || !rows[i]) continue;
      TunePoint p = rows[i]->point(mCost);
      p.withinBars = mRequest.allowArtifacts || def == tech.full.end() || withinBars(rows[i]->metrics, def->second.metrics);
      if (pickRecommended(std::vector<TunePoint>{p}, budget) && p.error < centre->second.point(mCost).error)
        better.emplace_back(p.error, step[i].candidate);
    }
    std::stable_sort(better.begin(), better.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    std::vector<TuneCandidate> moves;
    for (auto& [e, c] : better) moves.push_back(std::move(c));
    if (std::optional<TuneCandidate> c = combinedMove(tech.center, moves))
      if (std::none_of(tech.full.begin(), tech.full.end(), [&](const auto& e) { return e.first == *c; }))
        combined.push_back({t, std::move(*c)});
  }
  return combined;
}

// Rounds of coordinate descent until no technique's best moves, the rounds run out or (measured
// cost) --max-minutes would pass.
void TuneStages::descend(const TuneBudget& budget) {
  for (int round = 0; round < kMaxDescentRounds; ++round) {
    const std::vector<TuneJob> step = descentStep(budget);
    if (step.empty()) break;
    const size_t fresh = mEval.unmeasured(step, mFullW, mFullH, kFullFrames);
    const double stepSeconds = static_cast<double>(fresh) * mEval.secondsPerJob(mFullW, mFullH);
    // A deterministic run (--cost model) must not stop on the clock: its rounds are its own.
    if (mCost == TuneCost::Measured && elapsed() + stepSeconds + fullSecondsLeft(4, 0) > mRequest.maxMinutes * kSecondsPerMinute) {
      mProgress.finish();
      std::fprintf(stderr, "penumbra tune: descent stopped after %d round(s): --max-minutes %g would pass\n", round,
                   mRequest.maxMinutes);
      break;
    }
    const double laterSeconds = fullSecondsLeft(4, 0) + std::max(0, kExpectedDescentRounds - round - 1) * stepSeconds;
    mProgress.stage(fmt::format("3/4 descent, round {}", round + 1), fresh, laterSeconds);
    const std::vector<std::optional<TuneRow>> rows = mEval.run(step, mFullW, mFullH, kFullFrames);
    keepFull(step, rows);
    const std::vector<TuneJob> combined = combinedMoves(step, rows, budget);
    if (!combined.empty()) {
      mProgress.stage(fmt::format("3/4 descent, round {} combined", round + 1),
                      mEval.unmeasured(combined, mFullW, mFullH, kFullFrames),
                      fullSecondsLeft(4, 0) + std::max(0, kExpectedDescentRounds - round - 1) * stepSeconds);
      keepFull(combined, mEval.run(combined, mFullW, mFullH, kFullFrames));
    }
    for (TuneTechnique& tech : mTechniques) {
      const std::optional<size_t> best = pickRecommended(points(tech.full, mCost, mRequest.allowArtifacts), budget);
      tech.descending = best && tech.full[*best].first != tech.center;
    }
  }
}

// Each technique's full-size front within the memory budget, its best within the budget and its
// default; every full-size row joins res.explored.
std::vector<TuneJob> TuneStages::finalists(TuneResults& res, const TuneBudget& budget) const {
  std::vector<TuneJob> finalists;
  for (size_t t = 0; t < mTechniques.size(); ++t) {
    const TuneTechnique& tech = mTechniques[t];
    for (const auto& [c, row] : tech.full) res.explored.push_back(row);
    const std::vector<TunePoint> pts = points(tech.full, mCost, mRequest.allowArtifacts);
    std::vector<TuneCandidate> picks = {defaultCandidate(tech.space)};
    for (const size_t i : tuneFront(pts, budget.memoryMiB)) picks.push_back(tech.full[i].first);
    if (const std::optional<size_t> best = pickRecommended(pts, budget)) picks.push_back(tech.full[*best].first);
    for (TuneCandidate& c : picks) {
      const bool dup = std::any_of(finalists.begin(), finalists.end(), [&](const TuneJob& j) { return j.technique == t && j.candidate == c; });
      if (!dup) finalists.push_back({t, std::move(c)});
    }
  }
  return finalists;
}

// The finalists' full-size rows read back into res.confirmed (res.defaults: the defaults among
// them), each marked within or beyond the bars. Returns per confirmed row its finalist.
std::vector<size_t> TuneStages::readBack(TuneResults& res, const std::vector<TuneJob>& finalists) {
  const std::vector<std::optional<TuneRow>> confirmed = mEval.run(finalists, mFullW, mFullH, kFullFrames);  // read back
  std::vector<size_t> finalistOf;  // per confirmed row, its finalist
  for (size_t i = 0; i < finalists.size(); ++i) {
    if (!confirmed[i]) continue;
    if (confirmed[i]->isDefault) res.defaults.push_back(res.confirmed.size());
    res.confirmed.push_back(*confirmed[i]);
    finalistOf.push_back(i);
  }
  if (res.defaults.empty())
    throw usageError(fmt::format("tune: no default configuration could be rendered on {}", mRequest.views.front().scene));
  for (TuneRow& r : res.confirmed)  // the bars against the technique's own default
    for (const size_t d : res.defaults)
      if (res.confirmed[d].filter == r.filter && res.confirmed[d].projection == r.projection)
        r.withinBars = mRequest.allowArtifacts || withinBars(r.metrics, res.confirmed[d].metrics);
  return finalistOf;
}

// With the measured cost, the confirmed rows timed again in interleaved rounds; a default budget
// becomes the dearest default's cost (timed in those rounds, or its model cost).
void TuneStages::timeConfirmed(TuneResults& res, TuneBudget& budget, const std::vector<TuneJob>& finalists,
                               const std::vector<size_t>& finalistOf) {
  const bool defaulted = defaultBudget();
  if (mCost == TuneCost::Measured) {
    std::vector<TuneJob> timed;
    for (const size_t f : finalistOf) timed.push_back(finalists[f]);
    mProgress.stage(fmt::format("4/4 confirm, {} interleaved rounds", kConfirmRounds), timed.size() * mRequest.views.size(), 0.0);
    const std::vector<std::vector<std::vector<double>>> ms = mEval.timeRounds(timed, mFullW, mFullH, kConfirmRounds);
    const double reference =
        confirmCosts(res, ms, mRequest.aggregate, defaulted ? std::optional<double>() : mRequest.budget.costMs);
    mProgress.finish();
    if (defaulted) budget.costMs = reference;  // the dearest default's, timed in the same rounds
  } else if (defaulted) {
    budget.costMs.reset();
    for (const size_t d : res.defaults) budget.costMs = std::max(budget.costMs.value_or(0.0), res.confirmed[d].point(mCost).costMs);
  }
}

// The front and the recommendation among the confirmed rows, and the budget they were held to.
void TuneStages::pick(TuneResults& res, const TuneBudget& budget) const {
  std::vector<TunePoint> pts;
  for (const TuneRow& r : res.confirmed) pts.push_back(r.point(mCost));
  res.front = tuneFront(pts, budget.memoryMiB);
  res.recommended = pickRecommended(pts, budget);
  if (res.recommended && mRequest.objective == TuneObjective::Acne && pts[*res.recommended].error >= kAcneRejectedError)
    res.recommended.reset();  // every configuration has acne
  res.budget = budget.costMs.value_or(0.0);
}

}  // namespace

TuneResults runTune(gl::Context& context, const TuneRequest& request, const TuneSetupFactory& makeSetup) {
  PN_CHECK(!request.views.empty(), "runTune: at least one view");
  const auto start = Clock::now();
  TuneResults res;
  res.request = request;
  res.machine = describeMachine(context.info());
  // The techniques searched: every projection × filter, each with its space and default maps.
  std::vector<TuneTechnique> techniques = tuneTechniques(request, makeSetup);
  TuneProgress progress(request.progress);
  TuneEvaluator eval(context, request, makeSetup, techniques, progress);
  TuneStages stages(request, techniques, eval, progress, start);

  // 1. Screen: the default and the Latin-hypercube candidates of every technique at a small size.
  // With --shard only this machine's share, then stop: --merge goes on from all shares.
  const std::vector<TuneJob> jobs = stages.screenJobs();
  const std::vector<std::optional<TuneRow>> screened = stages.screen(jobs);
  if (request.shard) {
    progress.finish();
    res.evaluations = eval.measured();
    res.resumed = eval.resumed();
    res.seconds = stages.elapsed();
    return res;
  }

  // 2. Promote: per technique, the small-size front and the most accurate, and the default,
  // measured at full size.
  stages.measureFull(stages.promote(jobs, screened));
  // The budget: the one given, else (no error target either) the dearest default's own cost.
  TuneBudget budget = stages.budget();

  // 3. Descend: around each technique's best within the budget, one dimension at a time.
  stages.descend(budget);

  // 4. Confirm: each technique's full-size front within the memory budget, its best within the
  // budget and its default. Their errors are the full-size rows' (the frames are deterministic);
  // with the measured cost, their costs are timed again in interleaved rounds on every view, each
  // technique's default among them, and the budget is checked at the upper end of each spread.
  const std::vector<TuneJob> finalists = stages.finalists(res, budget);
  const std::vector<size_t> finalistOf = stages.readBack(res, finalists);
  stages.timeConfirmed(res, budget, finalists, finalistOf);
  stages.pick(res, budget);

  res.evaluations = eval.measured();
  res.resumed = eval.resumed();
  res.machine.clock = eval.clock();
  res.seconds = stages.elapsed();
  res.machine.loadEnd = loadAverage();
  return res;
}

}  // namespace penumbra::report
