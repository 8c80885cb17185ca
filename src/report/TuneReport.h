#pragma once
// What `penumbra tune` writes: tune.json (also its --json stdout) and tune.html (the front as a
// chart, SvgChart), and the answer's two forms: a --set command line and a scene-file snippet.
#include "tuner/TuneRunner.h"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>

namespace penumbra::report {

/// "pen, city from 0,2,5:0,0,0": the views of a request, for titles.
std::string tuneViewsText(const TuneRequest& request);

/// "--projection uniform --filter pcf --shadow-map 2048 --set pcf.radiusTexels=3.5 …": what to
/// add to `penumbra compare` or `render` for the row.
std::string tuneSetLine(const TuneRow& row);

/// The "shadow" block of a scene file (docs/scene-format.md) that makes the row the scene's own.
std::string tuneSceneSnippet(const TuneRow& row);

/// One row: {"filter", "projection", "params": {key: value}, "shadow_map", "shadow_budget", "rmse",
/// …, "shadow_cost_ms", "work_mops", "shadow_memory_mb", "command", "set", "views": [{"scene",
/// "camera", "error", "rmse", …, "command"}, …]} (aggregated over the views: worst or mean).
nlohmann::json tuneRowJson(const TuneRow& row, TuneObjective objective);

/// The whole result: recommended, default (the recommended technique's default), defaults,
/// front, explored, the request, the machine.
nlohmann::json tuneJson(const TuneResults& results);

/// tune.json and tune.html in `dir`.
void writeTuneOutputs(const std::filesystem::path& dir, const TuneResults& results);

/// The row `"default"` reports: the recommended technique's default, else the first default.
const TuneRow* tuneDefaultFor(const TuneResults& results);

}  // namespace penumbra::report
