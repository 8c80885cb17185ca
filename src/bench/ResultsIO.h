#pragma once
// results.csv and results.json: the same rows, the same columns, the same numbers. Both are
// built from one flattening of a row (tableColumns/tableRow), so they cannot drift apart; the
// JSON also carries the machine, the settings, the skipped configurations and micro-benchmarks.
#include "bench/BenchResults.h"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>
#include <variant>
#include <vector>

namespace penumbra::report {

/// Columns <kShadowCostColumn>_ms_{median,p10,p90}: BenchRow::shadowCost.
inline constexpr const char* kShadowCostColumn = "shadow_cost";
/// Columns <kRoundsCostColumn>_ms_{median,p10,p90}: the whole cost over the interleaved rounds
/// (BenchRow::rounds), empty for a row that was not a contender.
inline constexpr const char* kRoundsCostColumn = "rounds_cost";
/// Appended to a one_off_what cell: a one-off cost holds only while nothing it baked moves.
inline constexpr const char* kOneOffValidity = "; valid for static casters only (a moving caster redoes it)";

/// A cell: text, a number, or nothing (a pass this row does not have).
using Cell = std::variant<std::monostate, std::string, double>;

/// Column names, in order: configuration, quality, the whole cost (shadow_cost_ms_{median,p10,p90},
/// shadow_memory_mb in MiB, one_off_s and one_off_what: empty for techniques with none), the
/// motion (motion, motion_frames, flicker_pct, rmse_motion_mean, penumbra_rmse_motion_mean: empty
/// for a still row; pages_drawn, the mean pages a paged projection drew a frame over the motion's
/// frames: empty for a still row or a projection that does not page), rounds_cost_ms_{median,p10,p90}, then
/// <pass>_ms_{median,p10,p90} for every pass of results.passNames(), then image paths and the clock.
std::vector<std::string> tableColumns(const BenchResults& results);
/// One row's cells, aligned with tableColumns(results).
std::vector<Cell> tableRow(const BenchResults& results, const BenchRow& row);

/// RFC 4180 CSV: a header line, one line per row; numbers in shortest round-trip form (parsing
/// the text gives back the same double), empty for no value.
std::string resultsCsv(const BenchResults& results);
/// The micro table (BenchResults::micro), one line per row: name, baseline, ms_{median,p10,p90},
/// ratio_{median,p10,p90} (its time over its baseline's, empty without one), repetitions, error,
/// description, clock, gl_renderer. Same CSV rules as resultsCsv.
std::string microCsv(const BenchResults& results);
/// {"format", "version", "machine", "settings", "seconds", "columns", "rows": [{column: value}],
///  "skipped": [...], "per_frame": "frames.json", "recommendations", "scale", "micro": [...]};
///  rows hold numbers as numbers, null for no value.
nlohmann::json resultsJson(const BenchResults& results);
/// What results.json's rows were computed from, a row each in the same order: {"format",
///  "version", "frame_ms": [per row: {pass: [ms per timed frame]}], "samples": [per row:
///  {"motion": {what, fps, rmse: [per frame], penumbra_rmse: [...], flicker_followed,
///  flicker_points} or null, "rounds": {group, ms: [per round]} or null}]}.
nlohmann::json framesJson(const BenchResults& results);

/// Writes results.csv, results.json, frames.json and micro.csv into dir (each atomically).
void writeResults(const std::filesystem::path& dir, const BenchResults& results);

}  // namespace penumbra::report
