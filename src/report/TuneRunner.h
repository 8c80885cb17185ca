#pragma once
// `penumbra tune`'s run (docs/tune.md): per technique (projection × filter), a search over its
// parameters and map size on one scene, measured by runBench against the cached reference:
//  1. screen:  Latin-hypercube candidates (and the default) at a small image, few frames;
//  2. promote: successive halving keeps the small-size front and the most accurate to the full size;
//  3. descend: coordinate descent around the best configuration within the budget, at full size;
//  4. confirm: the full-size front and the default measured again with more frames; the
//     recommendation and the front come from these rows only.
// Every evaluation is kept in OUT/evaluations.jsonl, so that an interrupted run resumes.
#include "report/BenchRunner.h"
#include "report/TuneSearch.h"

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
/// Weight of tuneBiasSize in the acne error: far below one pixel's share of any percentage
/// (one pixel of 640×360 is 4e-4 %), so that it only breaks ties.
inline constexpr double kBiasTieWeight = 1e-7;

struct TuneShard {
  int index = 1, count = 1;  ///< K and N of --shard K/N
};

struct TuneRequest {
  std::string scene;  ///< built-in name or scene file
  std::vector<std::string> projections, filters;  ///< each pair is one technique searched
  BenchSettings settings;  ///< the full size, reference samples, cache, camera; its map size = the default's
  TuneObjective objective = TuneObjective::Rmse;
  TuneBudget budget;  ///< no cost budget and no error target: the default configuration's own cost
  double maxMinutes = 10.0;  ///< descent stops when the estimate says the run would pass this
  int candidates = 24;       ///< Latin-hypercube candidates per technique (the default comes on top)
  uint64_t seed = 1;
  std::filesystem::path outDir;
  bool verbose = false;
  /// --shard K/N: measure only every N-th screen configuration from the K-th (1-based) into
  /// OUT/evaluations.jsonl and stop; `--merge` of the shards' folders goes on from all of them.
  std::optional<TuneShard> shard;
};

/// Divisor of the screen stage's image sides (1/16 of the pixels), its shorter side at least the minimum.
inline constexpr int kScreenSizeDivisor = 4;
inline constexpr int kMinScreenSidePixels = 32;
/// Timed frames: enough for a median at the cheap stages, more when a cost decides (confirm).
inline constexpr int kScreenFrames = 2, kFullFrames = 3, kConfirmFrames = 7;
/// Successive halving keeps this fraction of the screened candidates.
inline constexpr int kHalvingDivisor = 3;
/// Rounds of coordinate descent at most (--max-minutes may stop it earlier): each moves the
/// centre by one step, a factor of 1.5 or an eighth of a range.
inline constexpr int kMaxDescentRounds = 8;
/// Rounds the descent usually takes before it settles (pen, city: 4 to 8): the estimate of the
/// time left assumes it.
inline constexpr int kExpectedDescentRounds = 4;

/// One measured configuration.
struct TuneRow {
  std::string projection, filter;
  std::vector<std::pair<std::string, std::string>> params;  ///< --set keys and values
  int mapSize = 0, width = 0, height = 0, frames = 0;
  VisibilityMetrics metrics;
  double error = 0.0;  ///< the objective's value
  double costMs = 0.0, costP10Ms = 0.0, costP90Ms = 0.0;
  double memoryMiB = 0.0;
  bool isDefault = false;
  std::string command;  ///< the `penumbra compare` line that reproduces the row
  TunePoint point() const { return {.error = error, .costMs = costMs, .memoryMiB = memoryMiB}; }
};

struct TuneResults {
  TuneRequest request;
  MachineInfo machine;
  std::vector<TuneRow> confirmed;     ///< stage 4's rows: the front, the defaults
  std::vector<size_t> front;          ///< indices into confirmed, ascending cost
  std::optional<size_t> recommended;  ///< into confirmed; empty when nothing fits the budget
  std::vector<size_t> defaults;       ///< into confirmed, one per technique
  double budgetMs = 0.0;              ///< the cost budget applied (given or the default's)
  size_t evaluations = 0, resumed = 0;  ///< configurations measured, and read back from a past run
  double seconds = 0.0;
  std::vector<TuneRow> explored;  ///< every full-size row of stages 2 and 3 (the chart's cloud)
};

/// Runs the search. `makeSetup` turns a configuration into scene + technique (the CLI's
/// makeSetup). Throws a usage Error when no technique's default can be rendered.
TuneResults runTune(gl::Context& context, const TuneRequest& request, const SetupFactory& makeSetup);

}  // namespace penumbra::report
