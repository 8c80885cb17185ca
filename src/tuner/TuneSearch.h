#pragma once
// The search of `penumbra tune` without GL (docs/tune.md): the space of one technique's
// parameters (ranges from its ParamDesc table, plus the shadow-map size), Latin-hypercube
// candidates in it, the neighbours of a point for coordinate descent, the successive-halving
// cut, and the pick of the recommended configuration from measured (error, cost, memory).
// Unit-tested in tests/unit/TuneSearchTest.cpp.
#include <penumbra/MapSizes.h>
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
/// The key of the map-budget dimension, which replaces the map size when the technique has a
/// map-count parameter (unit "maps": csm.cascades): the texels of all maps together, compare's
/// --shadow-budget, each map's side following from it (core::allocateMapSizes). Equal memory is
/// then one value of one dimension, and a step in the count alone trades resolution for coverage
/// at that memory; with the map size as the dimension, that trade needs two steps at once.
inline constexpr std::string_view kMapBudgetKey = "shadow.budgetTexels";
/// The unit that marks a parameter as a count of shadow maps per light.
inline constexpr std::string_view kMapCountUnit = "maps";

/// One searched dimension.
struct TuneDim {
  ParamDesc desc;    ///< the table's entry (kMapSizeKey: a synthetic one, integer texels)
  TuneScale scale = TuneScale::Linear;
  float lo = 0.0f, hi = 1.0f;  ///< the sampled range, inside [desc.min, desc.max]
  float def = 0.0f;            ///< the default configuration's value (scene params applied)
  bool powerOfTwo = false;     ///< map size and budget: sampled on the default's octaves (def × 2^k)
};

/// A point of the space: one value per dimension, in the space's order.
using TuneCandidate = std::vector<float>;

/// A searched range spans the default ÷ / × this factor where the table allows (Log scale):
/// wide enough to reach 16× fewer or more taps, narrow enough that 24 samples cover it.
inline constexpr float kLogSpanFactor = 16.0f;
/// Map sizes searched: the default's ÷ / × this factor (powers of two).
inline constexpr int kMapSizeSpanFactor = 2;
inline constexpr int kMinTuneMapSize = kMinDefaultsMapSizeTexels, kMaxTuneMapSize = 8192;

/// The default configuration's maps: the side of each and the texels of all together.
struct TuneMapDefault {
  int size = 0;           ///< texels per side; 0: no map dimension
  int64_t texels = 0;     ///< Σ views × side² over the shadowed lights (the map-budget dimension's default)
};

/// The space of `descs` around `current` (the default configuration's values, same order as
/// descs), minus the keys in `fixed` (e.g. "csm.stabilize": not a quality trade). A map
/// dimension is added when maps.size > 0 and its key is not in `fixed`: the map budget when a
/// searched parameter counts maps (kMapCountUnit), else the map size; both span the same memory,
/// ÷ / × kMapSizeSpanFactor² around the default's.
std::vector<TuneDim> tuneSpace(std::span<const ParamDesc> descs, std::span<const float> current, TuneMapDefault maps,
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

/// Coordinate descent's combined move: `center` with every dimension in which one of `better`
/// (neighbours of center, each differing in one dimension, that improved on it; best first) moved,
/// set to the best such neighbour's value. Empty when they moved fewer than two dimensions (the
/// best single neighbour is then the move). Without it, a round moves one dimension, and the
/// dimensions that gain most (a filter's radius) take every round while the others (cascades'
/// splits) never move within the rounds allowed.
std::optional<TuneCandidate> combinedMove(const TuneCandidate& center, std::span<const TuneCandidate> better);

/// The --set assignments of a candidate: "key" → value text (formatParamValue), only the
/// parameters whose value differs from the default's, without the map size and budget (tuneMaps).
std::vector<std::pair<std::string, std::string>> tuneParams(std::span<const TuneDim> space, const TuneCandidate& c);
/// What compare needs for a candidate's maps: --shadow-map and --shadow-budget.
struct TuneMaps {
  int size = 0;                 ///< --shadow-map: the side each map asks for
  int64_t budgetTexels = 0;     ///< --shadow-budget; 0 = none
  bool operator==(const TuneMaps&) const = default;
};
/// The candidate's maps. A map-size dimension: that size. With a map count (kMapCountUnit): no
/// budget when the count and the budget are the default's (the default configuration as compare
/// renders it), else the budget (the dimension's value, or the default's texels when the budget
/// is fixed: equal memory), asking for the side one map would take of all of it, so that one map
/// gets the whole budget and N maps share it. Otherwise the default's side.
TuneMaps tuneMaps(std::span<const TuneDim> space, const TuneCandidate& c, const TuneMapDefault& maps);

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
  /// The upper end of the cost's spread: what the budget is checked against, so that a pick is
  /// never over the budget within the noise (negative: costMs).
  double costHighMs = -1.0;
  /// Acne and umbra leak within the bars the pick keeps (TuneRunner.h: withinBars).
  bool withinBars = true;
  double budgetCost() const { return costHighMs >= 0.0 ? costHighMs : costMs; }
};

/// Successive halving's cut: the indices of `keep` points to evaluate at the next rung. The
/// (cost, error) Pareto front first (so the cheap end of the front survives), then the rest by
/// error; never more than `keep`, front points by ascending error when the front alone is larger.
std::vector<size_t> halvingSurvivors(std::span<const TunePoint> points, size_t keep);

/// The (cost, error) Pareto front of the points within the bars that fit the memory budget,
/// ascending cost.
std::vector<size_t> tuneFront(std::span<const TunePoint> points, std::optional<double> budgetMiB = std::nullopt);

/// What the user asked for.
struct TuneBudget {
  std::optional<double> costMs;    ///< --budget-ms: whole shadow cost per frame at most this
  std::optional<double> memoryMiB; ///< --budget-mb
  std::optional<double> maxError;  ///< --max-error: then the cheapest with error at most this
};

/// The recommended point among those within the bars and the cost and memory budgets (the cost
/// checked at TunePoint::budgetCost): with maxError, the cheapest whose error is at most it
/// (ties: lower error); else the lowest error (ties: lower cost). Nothing when no point qualifies.
std::optional<size_t> pickRecommended(std::span<const TunePoint> points, const TuneBudget& budget);

}  // namespace penumbra::report
