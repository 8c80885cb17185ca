#include "bench/Recommendation.h"

#include <penumbra/Technique.h>

#include <fmt/format.h>

#include <algorithm>
#include <cstring>
#include <tuple>

namespace penumbra::report {

const char* budgetName(Budget b) {
  switch (b) {
    case Budget::CheapestAcceptable: return "cheapest acceptable";
    case Budget::Balanced: return "balanced";
    case Budget::Best: return "best";
  }
  return "";
}

const char* budgetKey(Budget b) {
  switch (b) {
    case Budget::CheapestAcceptable: return "cheapest_acceptable";
    case Budget::Balanced: return "balanced";
    case Budget::Best: return "best";
  }
  return "";
}

namespace {

// One frame's error: the colour RMSE where the frame has colour metrics (else the RMSE: V_ref
// is grey, and so is the colour RMSE's), the others from the frame's visibility metrics.
double metricOf(ErrorMetric metric, const VisibilityMetrics& m, const ColourMetrics* colour) {
  switch (metric) {
    case ErrorMetric::Rmse: return m.rmse;
    case ErrorMetric::PenumbraRmse: return m.penumbraRmse;
    case ErrorMetric::ColourRmse: return colour ? colour->rmse : m.rmse;
  }
  return m.rmse;
}

// p10 ≤ 1 ≤ p90: a ratio that goes either way over its samples.
bool spansOne(const TimeStats& ratio) { return ratio.p10 <= 1.0 && ratio.p90 >= 1.0; }

}  // namespace

double situationError(ErrorMetric metric, const BenchRow& row) {
  return metricOf(metric, row.metrics, row.colour ? &*row.colour : nullptr);
}

std::vector<double> frameErrors(ErrorMetric metric, const BenchRow& row) {
  if (!row.motion || row.motion->frames.empty()) return {situationError(metric, row)};
  const std::vector<ColourMetrics>& colour = row.motion->colourFrames;
  std::vector<double> out;
  for (size_t f = 0; f < row.motion->frames.size(); ++f)
    out.push_back(metricOf(metric, row.motion->frames[f], f < colour.size() ? &colour[f] : nullptr));
  return out;
}

double motionError(ErrorMetric metric, const BenchRow& row) {
  const std::vector<double> e = frameErrors(metric, row);
  double sum = 0.0;
  for (const double v : e) sum += v;
  return sum / static_cast<double>(e.size());
}

double flickerPct(const BenchRow& row) { return row.motion ? row.motion->flicker.pct() : 0.0; }

const TimeStats& pickCost(const BenchRow& row) { return row.rounds ? row.rounds->stats : row.shadowCost; }

std::optional<TimeStats> costRatio(const BenchRow& a, const BenchRow& b) {
  if (!a.rounds || !b.rounds || a.rounds->group != b.rounds->group || a.rounds->ms.size() != b.rounds->ms.size() ||
      a.rounds->ms.empty())
    return std::nullopt;
  std::vector<double> ratio;
  for (size_t r = 0; r < a.rounds->ms.size(); ++r)
    if (b.rounds->ms[r] > 0.0) ratio.push_back(a.rounds->ms[r] / b.rounds->ms[r]);
  if (ratio.empty()) return std::nullopt;
  return timeStats(ratio);
}

bool costsTie(const BenchRow& a, const BenchRow& b) {
  if (const std::optional<TimeStats> r = costRatio(a, b)) return spansOne(*r);
  return a.shadowCost.p10 <= b.shadowCost.p90 && b.shadowCost.p10 <= a.shadowCost.p90;
}

std::optional<TimeStats> errorRatio(ErrorMetric metric, const BenchRow& a, const BenchRow& b) {
  const std::vector<double> ea = frameErrors(metric, a), eb = frameErrors(metric, b);
  if (ea.size() != eb.size()) return std::nullopt;
  std::vector<double> ratio;
  for (size_t f = 0; f < ea.size(); ++f)
    if (eb[f] > 0.0) ratio.push_back(ea[f] / eb[f]);
  if (ratio.empty()) return std::nullopt;
  return timeStats(ratio);
}

bool errorsTie(ErrorMetric metric, const BenchRow& a, const BenchRow& b) {
  const std::optional<TimeStats> r = errorRatio(metric, a, b);
  return r ? spansOne(*r) : motionError(metric, a) == motionError(metric, b);
}

void markMotion(std::vector<BenchConfig>& configs) {
  for (BenchConfig& c : configs) {
    const auto situation = std::find_if(std::begin(kSituations), std::end(kSituations),
                                        [&](const Situation& s) { return c.scene == s.scene; });
    const bool ownLight = std::none_of(c.params.begin(), c.params.end(), [](const auto& kv) { return kv.first.starts_with("light."); });
    c.motion = situation == std::end(kSituations) || !ownLight ? MotionKind::None
               : situation->staticCasters                      ? MotionKind::Walk  // its casters never move
                                                               : MotionKind::Animation;
  }
}

const char* metricName(ErrorMetric metric) {
  switch (metric) {
    case ErrorMetric::Rmse: return "RMSE";
    case ErrorMetric::PenumbraRmse: return "penumbra RMSE";
    case ErrorMetric::ColourRmse: return "colour RMSE";
  }
  return "";
}

const char* metricKey(ErrorMetric metric) {
  switch (metric) {
    case ErrorMetric::Rmse: return "rmse";
    case ErrorMetric::PenumbraRmse: return "penumbra_rmse";
    case ErrorMetric::ColourRmse: return "rmse_rgb";
  }
  return "";
}

std::optional<size_t> SituationPicks::pick(Budget b) const {
  switch (b) {
    case Budget::CheapestAcceptable: return cheapestAcceptable;
    case Budget::Balanced: return balanced;
    case Budget::Best: return best;
  }
  return std::nullopt;
}

std::vector<Budget> SituationPicks::budgetsOf(size_t row) const {
  std::vector<Budget> out;
  for (const Budget b : kBudgets)
    if (pick(b) == row) out.push_back(b);
  return out;
}

namespace {

/// True when every swept parameter of `c` is a technique parameter at its default (the contact
/// plan's `contact.shadows=off` row): the same configuration as the plain row, measured again.
bool sweepsOnlyDefaults(const BenchConfig& c) {
  if (c.params.empty()) return false;
  const Technique technique(c.projection, c.filter);
  for (const auto& [key, value] : c.params) {
    if (!technique.has(key)) return false;  // a scene parameter (light.size, light.count): another scene
    const ParamDesc& d = technique.desc(key);
    if (parseParamValue(d, value) != d.def) return false;
  }
  return true;
}

}  // namespace

std::vector<SituationPicks> recommend(const BenchResults& results) {
  std::vector<SituationPicks> out;
  for (const Situation& situation : kSituations) {
    SituationPicks p;
    p.situation = &situation;
    const std::vector<size_t> rows = sceneRows(results, situation.scene);
    for (const size_t i : rows) {
      const BenchRow& r = results.rows[i];
      // The plain row stands for its re-measured twin, under the name a user would type.
      const bool twin = sweepsOnlyDefaults(r.config) && std::any_of(rows.begin(), rows.end(), [&](size_t j) {
        const BenchConfig& o = results.rows[j].config;
        return o.params.empty() && o.projection == r.config.projection && o.filter == r.config.filter;
      });
      if (twin) continue;
      if (!situation.staticCasters && !r.oneOff.empty()) {
        p.excluded.push_back(fmt::format("{}: one-off work ({}) would be redone whenever a caster moves", rowLabel(r),
                                         r.oneOff.front().what));
        continue;
      }
      p.candidates.push_back(i);
    }
    if (p.candidates.empty()) {
      out.push_back(std::move(p));
      continue;
    }
    const ErrorMetric metric = situation.metric;
    const auto row = [&](size_t i) -> const BenchRow& { return results.rows[i]; };
    const auto error = [&](size_t i) { return motionError(metric, row(i)); };
    p.motion = std::all_of(p.candidates.begin(), p.candidates.end(), [&](size_t i) { return row(i).motion.has_value(); });
    std::vector<double> xs, ys;
    for (const size_t i : p.candidates) {
      xs.push_back(row(i).shadowCost.median);
      ys.push_back(error(i));
    }
    for (const size_t k : paretoFront(xs, ys)) p.front.push_back(p.candidates[k]);

    std::vector<size_t> steady;  // flicker within the limit
    for (const size_t i : p.candidates) (flickerPct(row(i)) > kMaxFlickerPct ? p.flickering : steady).push_back(i);
    if (steady.empty()) {
      out.push_back(std::move(p));
      continue;
    }
    // Each order ends with the row index, so equal rows pick the same one every time.
    auto minBy = [&](const std::vector<size_t>& list, auto key) {
      return *std::min_element(list.begin(), list.end(), [&](size_t a, size_t b) { return key(a) < key(b); });
    };
    p.bestError = error(minBy(steady, [&](size_t i) { return std::tuple(error(i), i); }));
    p.acceptableError = kAcceptableErrorFactor * p.bestError;
    for (const size_t i : steady)
      if (error(i) <= p.acceptableError) p.acceptable.push_back(i);

    // Contenders: acceptable, and no acceptable other is cheaper beyond both spreads and more accurate.
    for (const size_t i : p.acceptable) {
      const bool beaten = std::any_of(p.acceptable.begin(), p.acceptable.end(), [&](size_t j) {
        return j != i && row(j).shadowCost.p90 < row(i).shadowCost.p10 && error(j) < error(i);
      });
      if (!beaten) p.contenders.push_back(i);
    }
    std::stable_sort(p.contenders.begin(), p.contenders.end(),
                     [&](size_t a, size_t b) { return row(a).shadowCost.median < row(b).shadowCost.median; });
    if (p.contenders.size() > kMaxContenders) {
      const size_t mostAccurate = minBy(p.contenders, [&](size_t i) { return std::tuple(error(i), i); });
      p.contenders.resize(kMaxContenders);
      if (std::find(p.contenders.begin(), p.contenders.end(), mostAccurate) == p.contenders.end())
        p.contenders.back() = mostAccurate;
    }
    // The picks compare one kind of cost: the rounds' when every contender ran in them.
    p.retimed = std::all_of(p.contenders.begin(), p.contenders.end(),
                            [&](size_t i) { return row(i).rounds && row(i).rounds->group == situation.id; });
    const auto cost = [&](size_t i) { return p.retimed ? pickCost(row(i)).median : row(i).shadowCost.median; };

    const size_t cheapest = minBy(p.contenders, [&](size_t i) { return std::tuple(cost(i), error(i), i); });
    std::vector<size_t> costTie;
    for (const size_t i : p.contenders)
      if (i != cheapest && costsTie(row(i), row(cheapest))) costTie.push_back(i);
    std::vector<size_t> tiedCheap = costTie;
    tiedCheap.push_back(cheapest);
    p.cheapestAcceptable = minBy(tiedCheap, [&](size_t i) { return std::tuple(row(i).memoryBytes, error(i), cost(i), i); });
    if (!costTie.empty()) {
      PickTie t{.with = {}, .first = cheapest};
      for (const size_t i : tiedCheap)
        if (i != *p.cheapestAcceptable) t.with.push_back(i);
      p.cheapestTie = t;
    }

    const size_t mostAccurate = minBy(p.contenders, [&](size_t i) { return std::tuple(error(i), cost(i), i); });
    std::vector<size_t> errorTie;
    for (const size_t i : p.contenders)
      if (i != mostAccurate && errorsTie(metric, row(i), row(mostAccurate))) errorTie.push_back(i);
    std::vector<size_t> tiedBest = errorTie;
    tiedBest.push_back(mostAccurate);
    p.best = minBy(tiedBest, [&](size_t i) { return std::tuple(cost(i), error(i), i); });
    if (!errorTie.empty()) {
      PickTie t{.with = {}, .first = mostAccurate};
      for (const size_t i : tiedBest)
        if (i != *p.best) t.with.push_back(i);
      p.bestTie = t;
    }
    p.balanced = minBy(p.contenders, [&](size_t i) { return std::tuple(cost(i) * error(i), cost(i), i); });
    out.push_back(std::move(p));
  }
  return out;
}

}  // namespace penumbra::report
