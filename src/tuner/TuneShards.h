#pragma once
// Splitting `penumbra tune` over machines: `--shard K/N` measures a share of the screen stage into
// its own folder's evaluations.jsonl; `--merge DIR…` gathers those files into the output folder,
// whose run then reads them back (TuneRunner's resume) and measures the rest.
#include "tuner/TuneRunner.h"

#include <filesystem>
#include <span>
#include <string_view>

namespace penumbra::report {

/// "K/N" with 1 ≤ K ≤ N; throws a usage Error naming the text otherwise.
TuneShard parseShard(std::string_view text);

/// Appends to `out`/evaluations.jsonl every line of each `dirs`/evaluations.jsonl whose key it
/// does not hold yet; returns how many were added. Throws penumbra::Error for a folder without
/// evaluations.jsonl (not a shard's output).
size_t mergeEvaluations(std::span<const std::filesystem::path> dirs, const std::filesystem::path& out);

}  // namespace penumbra::report
