#pragma once
// report.html: one self-contained page (no script, no network; the grid's PNGs lie beside it in
// images/) that a user reads to choose a technique: the recommendation (ChoosingPage.h),
// 1. quality vs whole cost and vs memory with their Pareto fronts, where the time goes,
// 2. cost vs light size, 3. the image grid per scene (technique | reference | heatmap),
// 4. tables (cost ratios such as msm/vsm, every row, skipped configurations, the machine). The
// micro-benchmarks (building blocks such as the SAT build against a copy) are a page of their
// own, micro.html: they time the tool's parts, not the user's choice.
#include "bench/BenchResults.h"

#include <filesystem>
#include <string>

namespace penumbra::report {

/// Pairs of filters whose cost ratio the report tabulates (numerator, denominator): more moments
/// against fewer, a warp against the plain moments, a soft variant against its base, and rays
/// traced through the map against pcss's one blocker estimate.
inline constexpr std::pair<const char*, const char*> kCostRatioPairs[] = {
    {"msm", "vsm"}, {"msm-soft", "vssm"}, {"pcss", "pcf"}, {"esm", "vsm"}, {"evsm", "vsm"}, {"evsm-soft", "vssm"}, {"smrt", "pcss"}};

/// The page as text.
std::string htmlReport(const BenchResults& results);
/// The micro-benchmarks' page as text.
std::string microHtml(const BenchResults& results);

/// Writes dir/report.html and dir/micro.html (atomically). The images the rows name must
/// already be in dir.
void writeHtmlReport(const std::filesystem::path& dir, const BenchResults& results);

}  // namespace penumbra::report
