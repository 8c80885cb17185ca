#include "tuner/TuneSearch.h"

#include "core/ShadowBudget.h"
#include "bench/BenchResults.h"

#include <penumbra/Error.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <limits>
#include <numeric>
#include <random>

namespace penumbra::report {
namespace {

// A Log range needs the table's maximum at least this many times the default: below that the
// parameter is a fraction or a blend (csm.lambda), searched linearly.
constexpr float kLogMinRatio = 4.0f;
// Continuous values are rounded to this many significant digits: a --set line a person can
// read, and far finer than the measured error can tell apart.
constexpr int kSignificantDigits = 3;
// A Linear step of coordinate descent: this fraction of the searched range.
constexpr float kLinearStepFraction = 1.0f / 8.0f;

const ParamDesc kMapSizeDesc{kMapSizeKey, "Map size", "shadow-map texels per side (compare's --shadow-map)", "texels",
                             2048.0f, static_cast<float>(kMinTuneMapSize), static_cast<float>(kMaxTuneMapSize), 1.0f};
// The budget's range: from one smallest map to eight largest ones (a float holds these exactly
// on the default's octaves for any default below 2^24 texels per map).
const ParamDesc kMapBudgetDesc{kMapBudgetKey, "Map budget", "texels of all shadow maps together (compare's --shadow-budget)",
                               "texels", 4.0f * 2048.0f * 2048.0f, static_cast<float>(kMinTuneMapSize) * kMinTuneMapSize,
                               8.0f * kMaxTuneMapSize * kMaxTuneMapSize, 1.0f};

float roundSignificant(float v) {
  if (v == 0.0f || !std::isfinite(v)) return v;
  const double scale = std::pow(10.0, kSignificantDigits - 1 - static_cast<int>(std::floor(std::log10(std::fabs(v)))));
  return static_cast<float>(std::round(v * scale) / scale);
}

// The value as the table can hold it: power of two, integer, or rounded; inside [lo, hi].
float snap(const TuneDim& d, float v) {
  v = std::clamp(v, d.lo, d.hi);
  if (d.powerOfTwo) v = d.def * std::exp2(std::round(std::log2(v / d.def)));
  else if (d.desc.isInteger()) v = std::round(v);
  else v = roundSignificant(v);
  return std::clamp(v, d.desc.min, d.desc.max);
}

// u in [0, 1) → a value of the dimension.
float valueAt(const TuneDim& d, double u) {
  switch (d.scale) {
    case TuneScale::Choice: {
      const double n = d.hi - d.lo + 1.0;
      return d.lo + static_cast<float>(std::min(std::floor(u * n), n - 1.0));
    }
    case TuneScale::Log:
      return snap(d, static_cast<float>(std::exp(std::log(d.lo) + u * (std::log(d.hi) - std::log(d.lo)))));
    case TuneScale::Linear: break;
  }
  return snap(d, static_cast<float>(d.lo + u * (d.hi - d.lo)));
}

}  // namespace

std::vector<TuneDim> tuneSpace(std::span<const ParamDesc> descs, std::span<const float> current, TuneMapDefault maps,
                               std::span<const std::string> fixed) {
  PN_CHECK(descs.size() == current.size(), "tuneSpace: one current value per parameter");
  const auto isFixed = [&](std::string_view key) { return std::find(fixed.begin(), fixed.end(), std::string(key)) != fixed.end(); };
  std::vector<TuneDim> space;
  bool countsMaps = false;
  for (size_t i = 0; i < descs.size(); ++i) {
    const ParamDesc& p = descs[i];
    if (isFixed(p.key)) continue;
    countsMaps = countsMaps || p.unit == kMapCountUnit;
    TuneDim d{.desc = p, .scale = TuneScale::Linear, .lo = p.min, .hi = p.max, .def = current[i], .powerOfTwo = false};
    if (p.isChoice()) {
      d.scale = TuneScale::Choice;
    } else if (d.def > 0.0f && p.min >= 0.0f && p.max >= kLogMinRatio * d.def) {
      d.scale = TuneScale::Log;
      d.lo = std::max(p.min, d.def / kLogSpanFactor);
      d.hi = std::min(p.max, d.def * kLogSpanFactor);
      if (p.isInteger()) d.lo = std::max(d.lo, 1.0f);
    }
    if (d.hi > d.lo) space.push_back(d);
  }
  const bool budget = countsMaps && maps.texels > 0;
  if (maps.size > 0 && !isFixed(budget ? kMapBudgetKey : kMapSizeKey)) {
    // Texels scale as the side squared: the budget spans the span factor squared.
    const float span = budget ? static_cast<float>(kMapSizeSpanFactor * kMapSizeSpanFactor) : static_cast<float>(kMapSizeSpanFactor);
    TuneDim d{.desc = budget ? kMapBudgetDesc : kMapSizeDesc, .scale = TuneScale::Log, .lo = 0.0f, .hi = 0.0f,
              .def = budget ? static_cast<float>(maps.texels) : static_cast<float>(maps.size), .powerOfTwo = true};
    d.desc.def = d.def;
    d.lo = std::max(d.desc.min, d.def / span);
    d.hi = std::min(d.desc.max, d.def * span);
    if (d.hi > d.lo) space.push_back(d);
  }
  return space;
}

TuneCandidate defaultCandidate(std::span<const TuneDim> space) {
  TuneCandidate c;
  for (const TuneDim& d : space) c.push_back(d.def);
  return c;
}

std::vector<TuneCandidate> latinHypercube(std::span<const TuneDim> space, int count, uint64_t seed) {
  std::vector<TuneCandidate> out;
  if (count <= 0) return out;
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> jitter(0.0, 1.0);
  std::vector<TuneCandidate> all(static_cast<size_t>(count), TuneCandidate(space.size()));
  for (size_t d = 0; d < space.size(); ++d) {
    std::vector<int> strata(static_cast<size_t>(count));
    std::iota(strata.begin(), strata.end(), 0);
    std::shuffle(strata.begin(), strata.end(), rng);
    for (size_t i = 0; i < all.size(); ++i)
      all[i][d] = valueAt(space[d], (strata[i] + jitter(rng)) / static_cast<double>(count));
  }
  for (TuneCandidate& c : all)
    if (std::find(out.begin(), out.end(), c) == out.end()) out.push_back(std::move(c));
  return out;
}

std::vector<TuneCandidate> neighbours(std::span<const TuneDim> space, const TuneCandidate& center) {
  std::vector<TuneCandidate> out;
  const auto add = [&](size_t d, float v) {
    TuneCandidate c = center;
    c[d] = space[d].scale == TuneScale::Choice ? v : snap(space[d], v);
    if (c != center && std::find(out.begin(), out.end(), c) == out.end()) out.push_back(std::move(c));
  };
  for (size_t d = 0; d < space.size(); ++d) {
    const TuneDim& dim = space[d];
    const float v = center[d];
    switch (dim.scale) {
      case TuneScale::Choice:
        for (float k = dim.lo; k <= dim.hi; k += 1.0f)
          if (k != v) add(d, k);
        break;
      case TuneScale::Log: {
        const float factor = dim.powerOfTwo ? 2.0f : kDescentFactor;
        float down = v / factor, up = v * factor;
        if (dim.desc.isInteger()) {  // at least one whole step
          down = std::min(down, v - 1.0f);
          up = std::max(up, v + 1.0f);
        }
        add(d, down);
        add(d, up);
        break;
      }
      case TuneScale::Linear: {
        const float step = std::max((dim.hi - dim.lo) * kLinearStepFraction, dim.desc.isInteger() ? 1.0f : 0.0f);
        add(d, v - step);
        add(d, v + step);
        break;
      }
    }
  }
  return out;
}

std::optional<TuneCandidate> combinedMove(const TuneCandidate& center, std::span<const TuneCandidate> better) {
  TuneCandidate out = center;
  size_t moved = 0;
  for (const TuneCandidate& n : better)
    for (size_t d = 0; d < center.size(); ++d)
      if (n[d] != center[d] && out[d] == center[d]) {
        out[d] = n[d];
        ++moved;
      }
  if (moved < 2) return std::nullopt;
  return out;
}

std::vector<std::pair<std::string, std::string>> tuneParams(std::span<const TuneDim> space, const TuneCandidate& c) {
  std::vector<std::pair<std::string, std::string>> out;
  for (size_t d = 0; d < space.size(); ++d)
    if (space[d].desc.key != kMapSizeKey && space[d].desc.key != kMapBudgetKey && c[d] != space[d].def)
      out.emplace_back(std::string(space[d].desc.key), formatParamValue(space[d].desc, c[d]));
  return out;
}

TuneMaps tuneMaps(std::span<const TuneDim> space, const TuneCandidate& c, const TuneMapDefault& maps) {
  TuneMaps out{.size = maps.size, .budgetTexels = 0};
  bool countsMaps = false, atDefault = true;
  int64_t budget = maps.texels;
  for (size_t d = 0; d < space.size(); ++d) {
    if (space[d].desc.key == kMapSizeKey) out.size = static_cast<int>(c[d]);
    if (space[d].desc.key == kMapBudgetKey) budget = static_cast<int64_t>(c[d]);
    if (space[d].desc.unit == kMapCountUnit) countsMaps = true;
    if (space[d].desc.unit == kMapCountUnit || space[d].desc.key == kMapBudgetKey) atDefault = atDefault && c[d] == space[d].def;
  }
  if (!countsMaps || budget <= 0 || atDefault) return out;
  out.budgetTexels = budget;
  // The side one map would take of the whole budget, on the core's step (it rounds sides down to it).
  const int step = core::kMinBudgetMapSize;
  out.size = std::max(step, static_cast<int>(std::sqrt(static_cast<double>(budget)) / step) * step);
  return out;
}

bool isBiasKey(std::string_view key) {
  std::string name(key.substr(key.find('.') + 1));
  std::transform(name.begin(), name.end(), name.begin(), [](unsigned char ch) { return static_cast<char>(std::tolower(ch)); });
  return name.find("bias") != std::string::npos || name.find("offset") != std::string::npos;
}

double tuneBiasSize(std::span<const TuneDim> space, const TuneCandidate& c) {
  double size = 0.0;
  for (size_t d = 0; d < space.size(); ++d) {
    const TuneDim& dim = space[d];
    if (dim.scale == TuneScale::Choice || dim.hi <= dim.lo) continue;
    size += dim.scale == TuneScale::Log ? std::log(std::max(c[d], dim.lo) / dim.lo) / std::log(dim.hi / dim.lo)
                                        : (c[d] - dim.lo) / (dim.hi - dim.lo);
  }
  return size;
}

std::vector<size_t> tuneFront(std::span<const TunePoint> points, std::optional<double> budgetMiB) {
  std::vector<size_t> kept;
  std::vector<double> x, y;
  for (size_t i = 0; i < points.size(); ++i)
    if (points[i].withinBars && (!budgetMiB || points[i].memoryMiB <= *budgetMiB)) {
      kept.push_back(i);
      x.push_back(points[i].costMs);
      y.push_back(points[i].error);
    }
  std::vector<size_t> front = paretoFront(x, y);
  for (size_t& i : front) i = kept[i];
  return front;
}

std::vector<size_t> halvingSurvivors(std::span<const TunePoint> points, size_t keep) {
  std::vector<size_t> front = tuneFront(points);
  const auto byError = [&](size_t a, size_t b) { return points[a].error < points[b].error; };
  std::stable_sort(front.begin(), front.end(), byError);
  std::vector<size_t> out(front.begin(), front.begin() + static_cast<std::ptrdiff_t>(std::min(keep, front.size())));
  std::vector<size_t> rest(points.size());
  std::iota(rest.begin(), rest.end(), size_t{0});
  std::stable_sort(rest.begin(), rest.end(), byError);
  for (const size_t i : rest) {
    if (out.size() >= keep) break;
    if (std::find(out.begin(), out.end(), i) == out.end()) out.push_back(i);
  }
  return out;
}

std::optional<size_t> pickRecommended(std::span<const TunePoint> points, const TuneBudget& budget) {
  std::optional<size_t> best;
  for (size_t i = 0; i < points.size(); ++i) {
    const TunePoint& p = points[i];
    if (!p.withinBars) continue;
    if (budget.memoryMiB && p.memoryMiB > *budget.memoryMiB) continue;
    if (budget.costMs && p.budgetCost() > *budget.costMs) continue;
    if (budget.maxError) {
      if (p.error > *budget.maxError) continue;
      if (!best || p.costMs < points[*best].costMs ||
          (p.costMs == points[*best].costMs && p.error < points[*best].error))
        best = i;
    } else {
      if (!best || p.error < points[*best].error || (p.error == points[*best].error && p.costMs < points[*best].costMs))
        best = i;
    }
  }
  return best;
}

}  // namespace penumbra::report
