#pragma once
// `penumbra tune`'s run (docs/tune.md): per technique (projection × filter), a search over its
// parameters and maps on one or several views (scene × camera), measured by runBench against the
// cached reference, the views' errors and costs aggregated (worst or mean):
//  1. screen:  Latin-hypercube candidates (and the default) at a small image, few frames;
//  2. promote: successive halving keeps the small-size front and the most accurate to the full size;
//  3. descend: coordinate descent around the best configuration within the budget, at full size;
//  4. confirm: the full-size front, the best within the budget and the default timed again in
//     interleaved rounds (their errors are the full-size rows': frames are deterministic); the
//     recommendation and the front come from these rows only, the budget checked at the upper
//     end of each cost's spread.
// Unless asked, a pick keeps acne and umbra leak within the acne objective's bars (withinBars).
// Every evaluation is kept in OUT/evaluations.jsonl, so that an interrupted run resumes.
#include "bench/BenchRunner.h"
#include "tuner/TuneSearch.h"

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace penumbra::report {

/// Acne: the filter's bias parameters only (isBiasKey), the map size fixed. A configuration
/// whose acne (VisibilityMetrics::acnePct) is at most kMaxAcnePct is acceptable; among those the
/// least leak inside the reference's umbra (detached, peter-panned shadows: umbra_leak_pct)
/// wins, then the smallest bias (tuneBiasSize). Cost is no criterion unless --budget-ms is given.
enum class TuneObjective { Rmse, PenumbraRmse, Leak, Acne };
/// "rmse", "penumbra_rmse", "leak", "acne"; parseObjective throws a usage Error naming the choices.
const char* objectiveKey(TuneObjective o);
TuneObjective parseObjective(std::string_view text);
/// The objective's value on a row (leak: leak_pct; acne: umbra_leak_pct when acne is at most
/// kMaxAcnePct, else kAcneRejectedError + acne_pct, above any acceptable value).
double objectiveValue(TuneObjective o, const VisibilityMetrics& m);
/// The bar for acne, % of the fully lit pixels: one pixel in a thousand.
inline constexpr double kMaxAcnePct = 0.1;
/// Added to a rejected configuration's error: above any percentage.
inline constexpr double kAcneRejectedError = 1000.0;
/// The bars every pick keeps unless asked not to (TuneRequest::allowArtifacts), the acne
/// objective's own: acne at most kMaxAcnePct (or the default's, where that is more), and no more
/// umbra leak (detached shadows) than the default's plus this slack — about fifteen pixels of a
/// 640×360 frame, so that a pixel or two of difference does not decide.
inline constexpr double kUmbraLeakSlackPct = 0.01;
/// Whether `m` keeps the bars against its technique's default `def`.
bool withinBars(const VisibilityMetrics& m, const VisibilityMetrics& def);
/// Weight of tuneBiasSize in the acne error: far below one pixel's share of any percentage
/// (one pixel of 640×360 is 4e-4 %), so that it only breaks ties.
inline constexpr double kBiasTieWeight = 1e-7;

struct TuneShard {
  int index = 1, count = 1;  ///< K and N of --shard K/N
};

/// One view a configuration is measured on.
struct TuneView {
  std::string scene;   ///< built-in name or scene file
  std::string camera;  ///< compare's --camera text; "" = the scene's own
};

/// How the views' errors and costs make a configuration's: the worst view's, or the mean.
enum class TuneAggregate { Worst, Mean };
/// "worst", "mean"; parseAggregate throws a usage Error naming the choices.
const char* aggregateKey(TuneAggregate a);
TuneAggregate parseAggregate(std::string_view text);

/// What the search ranks cost by. Measured: the whole shadow cost per frame on this machine
/// (median ms): what a budget in ms means, but noisy, so two runs (or shards and one run) may
/// decide differently. Model: a count of work that a configuration implies, the same on every
/// machine and every run (TuneRow::workM), so the search is a function of the errors and the
/// configurations alone: shards, merges and reruns give the same front.
enum class TuneCost { Measured, Model };
/// "measured", "model"; parseCost throws a usage Error naming the choices.
const char* costKey(TuneCost c);
TuneCost parseCost(std::string_view text);

struct TuneRequest {
  std::vector<TuneView> views;  ///< at least one; the first scene's map size is the default's
  TuneAggregate aggregate = TuneAggregate::Worst;
  TuneCost cost = TuneCost::Measured;
  std::vector<std::string> projections, filters;  ///< each pair is one technique searched
  /// --params: the keys searched (parameter keys, kMapSizeKey, kMapBudgetKey); empty = all.
  std::vector<std::string> searchKeys;
  BenchSettings settings;  ///< the full size, reference samples, cache; its map size = the default's
  TuneObjective objective = TuneObjective::Rmse;
  TuneBudget budget;  ///< no cost budget and no error target: the default configuration's own cost
  double maxMinutes = 10.0;  ///< descent stops when the estimate says the run would pass this
  int candidates = 24;       ///< Latin-hypercube candidates per technique (the default comes on top)
  uint64_t seed = 1;
  std::filesystem::path outDir;
  bool verbose = false;
  bool progress = true;  ///< the progress line on stderr
  /// --allow-artifacts: the pick may raise acne and umbra leak past the bars (withinBars).
  bool allowArtifacts = false;
  /// --shard K/N: measure only every N-th screen configuration from the K-th (1-based) into
  /// OUT/evaluations.jsonl and stop; `--merge` of the shards' folders goes on from all of them.
  std::optional<TuneShard> shard;
};

/// Divisor of the screen stage's image sides (1/16 of the pixels), its shorter side at least the minimum.
inline constexpr int kScreenSizeDivisor = 4;
inline constexpr int kMinScreenSidePixels = 32;
/// Timed frames: enough for a median at the cheap stages.
inline constexpr int kScreenFrames = 2, kFullFrames = 3;
/// The confirm stage's interleaved rounds: each round renders one frame of every finalist (each
/// technique's default among them), so that their costs share the machine's load.
inline constexpr int kConfirmRounds = 9;
/// Successive halving keeps this fraction of the screened candidates.
inline constexpr int kHalvingDivisor = 3;
/// Rounds of coordinate descent at most (--max-minutes may stop it earlier): each moves the
/// centre by one step, a factor of 1.5 or an eighth of a range.
inline constexpr int kMaxDescentRounds = 8;
/// Rounds the descent usually takes before it settles (pen, city: 4 to 8): the estimate of the
/// time left assumes it.
inline constexpr int kExpectedDescentRounds = 4;

/// The work model of TuneCost::Model, in millions of operations per frame: every texel of
/// the GPU memory the technique keeps written once (maps, moments, tables are rebuilt each
/// frame; kModelBytesPerTexel bytes a texel), plus one read per declared tap per pixel (the
/// parameters whose unit is "taps", at least one).
inline constexpr double kModelBytesPerTexel = 4.0;
/// The unit that marks a parameter as taps per pixel (pcf.samples, pcss.filterSamples).
inline constexpr std::string_view kTapsUnit = "taps";

/// One configuration measured on one view, or (views non-empty) aggregated over several.
struct TuneRow {
  std::string projection, filter;
  std::vector<std::pair<std::string, std::string>> params;  ///< --set keys and values
  int mapSize = 0, width = 0, height = 0, frames = 0;
  int64_t budgetTexels = 0;  ///< --shadow-budget; 0 = none
  int grantedMapSize = 0;    ///< the side the first shadowed light's maps got (= mapSize without a budget)
  VisibilityMetrics metrics;
  double error = 0.0;  ///< the objective's value
  double costMs = 0.0, costP10Ms = 0.0, costP90Ms = 0.0;
  double workM = 0.0;  ///< TuneCost::Model's work, millions of operations per frame
  double memoryMiB = 0.0;
  bool isDefault = false;
  /// Acne and umbra leak within the bars against the technique's default (withinBars).
  bool withinBars = true;
  /// Confirmed rows (measured cost): the whole cost over the interleaved rounds is costMs /
  /// costP10Ms / costP90Ms; its per-round ratio to the budget's default (the default itself when
  /// the budget is the default's cost) is costRatio; budgetCostMs is what the budget is checked
  /// against: the cost's p90, or the ratio's p90 times that default's median. -1: not confirmed.
  int rounds = 0;
  TimeStats costRatio;
  double budgetCostMs = -1.0;
  std::string scene, camera;  ///< the view (of the first view when aggregated)
  std::string command;  ///< the `penumbra compare` line that reproduces the row (the first view's)
  std::vector<TuneRow> views;  ///< per view, when measured on several (or one) views
  /// What the search ranks: error, the cost of `cost`'s kind, memory.
  TunePoint point(TuneCost cost) const {
    const bool model = cost == TuneCost::Model;
    return {.error = error, .costMs = model ? workM : costMs, .memoryMiB = memoryMiB,
            .costHighMs = model ? -1.0 : budgetCostMs, .withinBars = withinBars};
  }
};

struct TuneResults {
  TuneRequest request;
  MachineInfo machine;
  std::vector<TuneRow> confirmed;     ///< stage 4's rows: the front, the defaults
  std::vector<size_t> front;          ///< indices into confirmed, ascending cost
  std::optional<size_t> recommended;  ///< into confirmed; empty when nothing fits the budget
  std::vector<size_t> defaults;       ///< into confirmed, one per technique
  double budget = 0.0;                ///< the cost budget applied (given or the default's), in the cost's unit
  size_t evaluations = 0, resumed = 0;  ///< configurations measured, and read back from a past run
  double seconds = 0.0;
  std::vector<TuneRow> explored;  ///< every full-size row of stages 2 and 3 (the chart's cloud)
};

/// Turns a configuration seen from a camera (compare's --camera text, "" = the scene's own) into
/// scene + technique (the CLI's makeSetup).
using TuneSetupFactory = std::function<BenchSetup(const BenchConfig&, const std::string& camera)>;

/// Runs the search. Throws a usage Error when no technique's default can be rendered.
TuneResults runTune(gl::Context& context, const TuneRequest& request, const TuneSetupFactory& makeSetup);

}  // namespace penumbra::report
