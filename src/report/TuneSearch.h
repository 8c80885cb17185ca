#pragma once
// The search of `penumbra tune` without GL (docs/tune.md): the space of one technique's
// parameters (ranges from its ParamDesc table, plus the shadow-map size), Latin-hypercube
// candidates in it, the neighbours of a point for coordinate descent, the successive-halving
// cut, and the pick of the recommended configuration from measured (error, cost, memory).
// Unit-tested in tests/unit/TuneSearchTest.cpp.
#include <penumbra/Params.h>

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

namespace penumbra::report {

/// How a dimension is sampled: Log for positive ranges that span orders of magnitude (biases,
/// radii, tap counts: a factor matters, not a difference), Linear otherwise, Choice for names.
enum class TuneScale { Linear, Log, Choice };

/// The key of the shadow-map size dimension: not a --set key (it is compare's --shadow-map).
inline constexpr std::string_view kMapSizeKey = "shadow.mapSize";

/// One searched dimension.
struct TuneDim {
  ParamDesc desc;    ///< the table's entry (kMapSizeKey: a synthetic one, integer texels)
  TuneScale scale = TuneScale::Linear;
  float lo = 0.0f, hi = 1.0f;  ///< the sampled range, inside [desc.min, desc.max]
  float def = 0.0f;            ///< the default configuration's value (scene params applied)
  bool powerOfTwo = false;     ///< the map size: sampled on powers of two
};

/// A point of the space: one value per dimension, in the space's order.
using TuneCandidate = std::vector<float>;

/// A searched range spans the default ÷ / × this factor where the table allows (Log scale):
/// wide enough to reach 16× fewer or more taps, narrow enough that 24 samples cover it.
inline constexpr float kLogSpanFactor = 16.0f;
/// Map sizes searched: the default's ÷ / × this factor (powers of two).
inline constexpr int kMapSizeSpanFactor = 2;
inline constexpr int kMinTuneMapSize = 256, kMaxTuneMapSize = 8192;

/// The space of `descs` around `current` (the default configuration's values, same order as
/// descs), minus the keys in `fixed` (e.g. "csm.stabilize": not a quality trade). A map-size
/// dimension is added when mapSize > 0.
std::vector<TuneDim> tuneSpace(std::span<const ParamDesc> descs, std::span<const float> current, int mapSize,
                               std::span<const std::string> fixed = {});

/// The default configuration: every dimension at `def`.
TuneCandidate defaultCandidate(std::span<const TuneDim> space);

/// `count` candidates spread by a Latin hypercube (each dimension's range cut into `count`
/// strata, one sample per stratum, strata shuffled per dimension), values snapped (integers,
/// powers of two, choices) and inside [lo, hi]; duplicates after snapping are dropped, so fewer
/// may come back. Deterministic for a seed.
std::vector<TuneCandidate> latinHypercube(std::span<const TuneDim> space, int count, uint64_t seed);

/// Coordinate-descent steps from `center`: per dimension one step down and one up (Log: ÷/×
/// kDescentFactor; Linear: ∓ an eighth of the range; Choice: every other choice; map size: one
/// power of two), clamped to [lo, hi]; steps that change nothing are dropped.
inline constexpr float kDescentFactor = 1.5f;
std::vector<TuneCandidate> neighbours(std::span<const TuneDim> space, const TuneCandidate& center);

/// The --set assignments of a candidate: "key" → value text (formatParamValue), only the
/// parameters whose value differs from the default's, without the map size.
std::vector<std::pair<std::string, std::string>> tuneParams(std::span<const TuneDim> space, const TuneCandidate& c);
/// The candidate's map size (the default `fallback` when the space has no map dimension).
int tuneMapSize(std::span<const TuneDim> space, const TuneCandidate& c, int fallback);

/// A bias parameter (acne against peter-panning): its name after the technique holds "bias" or
/// "offset" (hard.bias, pcf.constantBias, hard.normalOffsetTexels). `--objective acne` searches these only.
bool isBiasKey(std::string_view key);

/// How much bias a candidate applies, for ties of `--objective acne`: the sum over its numeric
/// dimensions of the value's place in [lo, hi] on the dimension's scale (0 at lo, 1 at hi).
double tuneBiasSize(std::span<const TuneDim> space, const TuneCandidate& c);

/// One measured configuration as the pick sees it.
struct TunePoint {
  double error = 0.0;   ///< the objective (lower is better)
  double costMs = 0.0;  ///< whole shadow cost per frame, median
  double memoryMiB = 0.0;
};

/// Successive halving's cut: the indices of `keep` points to evaluate at the next rung. The
/// (cost, error) Pareto front first (so the cheap end of the front survives), then the rest by
/// error; never more than `keep`, front points by ascending error when the front alone is larger.
std::vector<size_t> halvingSurvivors(std::span<const TunePoint> points, size_t keep);

/// The (cost, error) Pareto front of the points that fit the memory budget, ascending cost.
std::vector<size_t> tuneFront(std::span<const TunePoint> points, std::optional<double> budgetMiB = std::nullopt);

/// What the user asked for.
struct TuneBudget {
  std::optional<double> costMs;    ///< --budget-ms: whole shadow cost per frame at most this
  std::optional<double> memoryMiB; ///< --budget-mb
  std::optional<double> maxError;  ///< --max-error: then the cheapest with error at most this
};

/// The recommended point among those within the cost and memory budgets: with maxError, the
/// cheapest whose error is at most it (ties: lower error); else the lowest error (ties: lower
/// cost). Nothing when no point qualifies.
std::optional<size_t> pickRecommended(std::span<const TunePoint> points, const TuneBudget& budget);

}  // namespace penumbra::report
