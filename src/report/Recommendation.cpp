#include "report/Recommendation.h"

#include "report/ReportCharts.h"

#include <penumbra/Registry.h>

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

double situationError(ErrorMetric metric, const BenchRow& row) {
  return metric == ErrorMetric::PenumbraRmse ? row.metrics.penumbraRmse : row.metrics.rmse;
}

const char* metricName(ErrorMetric metric) { return metric == ErrorMetric::PenumbraRmse ? "penumbra RMSE" : "RMSE"; }
const char* metricKey(ErrorMetric metric) { return metric == ErrorMetric::PenumbraRmse ? "penumbra_rmse" : "rmse"; }

std::optional<size_t> SituationPicks::pick(Budget b) const {
  switch (b) {
    case Budget::CheapestAcceptable: return cheapestAcceptable;
    case Budget::Balanced: return balanced;
    case Budget::Best: return best;
  }
  return std::nullopt;
}

namespace {

/// True when every swept parameter of `c` is a technique parameter at its default (the contact
/// plan's `contact.shadows=off` row): the same configuration as the plain row, measured again.
bool sweepsOnlyDefaults(const BenchConfig& c) {
  if (c.params.empty()) return false;
  const std::unique_ptr<Parameterized> owners[] = {makeFilter(c.filter), makeProjection(c.projection), makeAddOns()};
  for (const auto& [key, value] : c.params) {
    const Parameterized* owner = nullptr;
    for (const auto& o : owners)
      if (o->hasParam(key)) owner = o.get();
    if (!owner) return false;  // a scene parameter (light.size, light.count): another scene
    const auto descs = owner->paramDescs();
    const auto d = std::find_if(descs.begin(), descs.end(), [&](const ParamDesc& desc) { return desc.key == key; });
    if (parseParamValue(*d, value) != d->def) return false;
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
    auto cost = [&](size_t i) { return results.rows[i].shadowCost.median; };
    auto error = [&](size_t i) { return situationError(situation.metric, results.rows[i]); };
    std::vector<double> xs, ys;
    for (const size_t i : p.candidates) {
      xs.push_back(cost(i));
      ys.push_back(error(i));
    }
    for (const size_t k : paretoFront(xs, ys)) p.front.push_back(p.candidates[k]);

    // Each order ends with the row index, so equal rows pick the same one every time.
    auto minBy = [&](const std::vector<size_t>& rows, auto key) {
      return *std::min_element(rows.begin(), rows.end(), [&](size_t a, size_t b) { return key(a) < key(b); });
    };
    p.best = minBy(p.candidates, [&](size_t i) { return std::tuple(error(i), cost(i), i); });
    p.bestError = error(*p.best);
    p.acceptableError = kAcceptableErrorFactor * p.bestError;
    std::vector<size_t> acceptable;
    for (const size_t i : p.candidates)
      if (error(i) <= p.acceptableError) acceptable.push_back(i);
    p.cheapestAcceptable = minBy(acceptable, [&](size_t i) { return std::tuple(cost(i), error(i), i); });
    p.balanced = minBy(acceptable, [&](size_t i) { return std::tuple(cost(i) * error(i), cost(i), i); });
    out.push_back(std::move(p));
  }
  return out;
}

}  // namespace penumbra::report
