#pragma once
// The recommendation (Recommendation.h) as people read it: the report's first section and the
// Markdown page docs/choosing.md, both written by `penumbra bench` from the run's own rows, with
// the rule, each pick's measured error, cost and memory, the command that reproduces it and the
// machine it was measured on.
#include "bench/Recommendation.h"

#include <filesystem>
#include <string>
#include <vector>

namespace penumbra::report {

/// `penumbra bench` options that re-time these rows on their own (the run's settings, the rows'
/// scenes, projections, filters and swept values).
std::string benchCommand(const BenchResults& results, const std::vector<size_t>& rows);

/// The picks as plain text for the terminal: per situation its picks, error, cost and flicker
/// (`penumbra bench` prints it; a --quick run says it is a quick look).
std::string picksSummary(const BenchResults& results, const std::vector<SituationPicks>& picks);

/// The report's section (an <h2 id="choose"> and what follows).
std::string recommendationHtml(const BenchResults& results, const std::vector<SituationPicks>& picks);

/// The Markdown page. `reportLink` is report.html's path relative to the page's folder.
std::string choosingMarkdown(const BenchResults& results, const std::vector<SituationPicks>& picks,
                             const std::string& reportLink);

/// Writes the page to `path` (atomically), linking the report in `reportDir`.
void writeChoosingPage(const std::filesystem::path& path, const std::filesystem::path& reportDir,
                       const BenchResults& results);

}  // namespace penumbra::report
