#pragma once
// What a bench run measured: one row per configuration (per-pass time statistics and quality
// metrics against the reference), the configurations that were refused or failed, the
// micro-benchmarks, and the machine. Written as CSV/JSON (ResultsIO.h) and HTML (HtmlReport.h).
#include "bench/BenchPlan.h"

#include "comparison/Flicker.h"

#include "frame/Filter.h"
#include <penumbra/Metrics.h>

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace penumbra::gl { struct GlInfo; }

namespace penumbra::report {

/// Spread of one pass's time over the timed frames, in milliseconds.
struct TimeStats {
  double median = 0.0, p10 = 0.0, p90 = 0.0;
};

/// Median and 10th/90th percentiles (linear interpolation between order statistics; with one
/// sample all three are that sample). Empty input: all zero.
TimeStats timeStats(std::span<const double> samplesMs);

/// The time row a chart reads: the named pass, "total" for the sum of every pass.
inline constexpr const char* kTotalPass = "total";

struct PassStats {
  std::string name;  ///< a Renderer pass ("shadow", "visibility", ...) or kTotalPass
  TimeStats ms;
};

/// The passes a technique runs every frame (the core's: docs/design.md), "contact" only when
/// contact shadows are on, "projection" only for a projection that measures the pixels (sdsm):
/// their sum is its frame cost of shadowing. The G-buffer and lit passes are the same for every
/// technique.
inline constexpr const char* kShadowCostPasses[] = {"projection", "shadow", "prefilter", "visibility", "contact"};

/// Per pass, the time of each timed frame (ms), in frame order.
using FrameSamples = std::vector<std::pair<std::string, std::vector<double>>>;

/// The frame cost of shadowing: per timed frame, the sum of the kShadowCostPasses it ran; then
/// the median and p10/p90 of those sums (timeStats). Quantiles of the per-frame sum, not sums
/// of per-pass quantiles: a frame whose shadow pass was slow counts once, as a slow frame.
TimeStats shadowCostStats(const FrameSamples& frames);

/// Bytes per MiB: shadow_memory_mb is in MiB (2²⁰ bytes).
inline constexpr double kBytesPerMiB = 1024.0 * 1024.0;

/// A row over the motion it was scored on (BenchConfig::motion): per frame the combined V against
/// V_ref (frame 0 is the still frame), and the flicker between consecutive frames.
inline constexpr const char* kAnimationMotion = "the scene's animation";
inline constexpr const char* kWalkMotion = "a camera walk";  ///< addCameraWalk
struct MotionScore {
  std::string what;  ///< kAnimationMotion or kWalkMotion
  float fps = kMotionFps;
  std::vector<VisibilityMetrics> frames;
  /// Each frame's colour metrics (SequenceFrame::colour), one per `frames` entry where the scene
  /// has translucent casters; empty otherwise.
  std::vector<ColourMetrics> colourFrames;
  FlickerCounts flicker;
  /// A paged projection's pages drawn in each frame, every light's together (LightShadowReport::
  /// pages); empty for a projection that does not page.
  std::vector<int> pagesDrawn;
};

/// A row's whole cost timed again in interleaved rounds with the other contenders of its
/// situation (BenchSettings::retimeRounds): one frame per round, so each round's times share
/// the machine's load and a ratio taken within a round cancels it.
struct RoundCosts {
  std::string group;       ///< the situation whose contenders ran in these rounds
  std::vector<double> ms;  ///< the whole cost of the row's frame in each round, in round order
  TimeStats stats;         ///< median and p10–p90 over the rounds
};

struct BenchRow {
  BenchConfig config;
  float lightSize = 0.0f;  ///< the light size in effect (scene's own or swept)
  int lights = 1;          ///< lights rendered, each with its own maps (light.count or all the scene's)
  int width = 0, height = 0, shadowMapSize = 0;
  /// The side the first shadowed light's maps got: shadowMapSize, or less under a budget.
  int grantedMapSize = 0;
  int frames = 0;  ///< timed frames actually run (fewer than asked when the time cap hit)
  std::vector<PassStats> passes;  ///< in frame order, then kTotalPass
  FrameSamples frameMs;           ///< the samples behind `passes` (no total)
  TimeStats shadowCost;           ///< shadowCostStats(frameMs): the whole per-frame cost
  /// GPU memory the technique keeps (Shadows::techniqueMemoryBytes) after the last timed frame.
  std::size_t memoryBytes = 0;
  /// Work done once and kept while the casters do not move (Filter::oneOffCosts): in no frame.
  std::vector<OneOffCost> oneOff;
  VisibilityMetrics metrics;
  /// The still frame's V (RGB, or grey) against the RGB V_ref (FrameComparison::colour): on a
  /// scene with translucent casters and one shadowed light; empty otherwise.
  std::optional<ColourMetrics> colour;
  std::optional<MotionScore> motion;  ///< for BenchConfig::motion rows
  std::optional<RoundCosts> rounds;   ///< for the recommendation's contenders
  /// Image files relative to the output folder; empty when the row is not in the grid.
  std::string imagePath, heatmapPath, referencePath;

  /// Median/spread of `pass`; zeros when the row has no such pass.
  TimeStats time(std::string_view pass) const;
  double memoryMiB() const { return static_cast<double>(memoryBytes) / kBytesPerMiB; }
  /// The mean of MotionScore::pagesDrawn over the motion's frames; none for a still row or a
  /// projection that does not page.
  std::optional<double> pagesDrawnMean() const;
  /// Seconds of every one-off cost together (0 when there are none).
  double oneOffSeconds() const;
};

/// A configuration that did not produce a row.
struct SkippedConfig {
  BenchConfig config;
  std::string reason;
  bool failed = false;  ///< false: refused as an unsupported pair; true: an error during the run
};

/// A timed building block outside the frame, next to its baseline: a summed-area table against
/// a plain copy of the same texture, a filter's visibility pass against its minimal lookup
/// kernel (docs/bench.md, "Micro-benchmarks").
struct MicroResult {
  std::string name;         ///< "copy RG32F", "SAT build, 2 moments", "visibility: hard", …
  std::string description;  ///< what was timed, on what data
  std::string baseline;     ///< name of the result it is compared with; "" = none
  TimeStats ms;
  int repetitions = 0;  ///< timed rounds
  std::string error;    ///< non-empty: the block failed (GL error, …) and was not timed
  /// Its time over its baseline's, per round (the two ran in the same round): median and
  /// 10th/90th percentiles. Empty without a baseline, or when either failed.
  std::optional<TimeStats> ratio;
};

/// One count of the triangle-count plan (bench/ScaleBench.h): a generated grid's load, passes and
/// reference BVH.
struct ScaleRow {
  uint64_t triangles = 0, vertices = 0;  ///< as loaded, the box included
  uint64_t fileBytes = 0;                ///< the OBJ's size
  double loadSeconds = 0.0;              ///< loadScene, wall clock
  int frames = 0;                        ///< timed frames
  TimeStats gbufferMs, shadowMs;         ///< medians and spread over the timed frames
  double bvhSeconds = 0.0;               ///< the reference's BVH build, wall clock
  uint64_t bvhBytes = 0, bvhPeakBytes = 0;  ///< Embree's allocations once built, and their peak
  std::string error;                     ///< non-empty: this count failed (the others still ran)

  double loadSecondsPerMiB() const { return loadSeconds / (static_cast<double>(fileBytes) / kBytesPerMiB); }
  double gbufferNsPerTriangle() const { return gbufferMs.median * 1e6 / static_cast<double>(triangles); }
  double shadowNsPerTriangle() const { return shadowMs.median * 1e6 / static_cast<double>(triangles); }
};

struct MachineInfo {
  std::string glRenderer, glVersion, glVendor, clock;  ///< clock: PassTimings::clock
  std::string cpu, os;
  int hardwareThreads = 0;
  /// 1-minute load average (/proc/loadavg) when the run began and ended; -1 where unknown. Other
  /// work on the machine inflates times and makes them drift during a run.
  double loadStart = -1.0, loadEnd = -1.0;
  std::string date;     ///< UTC, ISO 8601
  std::string command;  ///< the command line of the run
};

struct BenchResults {
  MachineInfo machine;
  BenchSettings settings;
  std::vector<BenchRow> rows;
  std::vector<SkippedConfig> skipped;
  std::vector<MicroResult> micro;
  std::vector<ScaleRow> scale;  ///< the triangle-count plan (bench/ScaleBench.h); empty when not run
  double seconds = 0.0;  ///< wall-clock time of the whole run

  /// Names of every pass that occurs in some row, in first-seen order, kTotalPass last.
  std::vector<std::string> passNames() const;
};

/// The `penumbra compare` command line that renders `row`'s configuration on the same pixels
/// with the same map and reference samples: it prints the row's metrics (to every digit: the
/// frames are deterministic) and one frame's pass times. Text that a shell would split is quoted.
std::string compareCommand(const BenchResults& results, const BenchRow& row);

/// Fills cpu, os, hardwareThreads, date and loadStart (not the GL fields or the command).
MachineInfo describeMachine();
/// The same, with the GL renderer, version and vendor of `gl` (a context's info()).
MachineInfo describeMachine(const gl::GlInfo& gl);
/// The 1-minute load average, or -1 where /proc/loadavg cannot be read.
double loadAverage();

/// Indices of the rows on the Pareto front of (x, y), both minimised: no other point is at
/// least as good in both and better in one (exact duplicates of a front point are on it too).
/// Ascending x.
std::vector<size_t> paretoFront(std::span<const double> x, std::span<const double> y);

// --- a row in words (the report pages, the recommendation and the tuner say rows alike) ---

/// A time or size with about three significant digits, never in exponent form ("1030", "61.6", "2.87").
std::string numberText(double v);

/// A row's light.* parameters as text ("" when it uses the scene's own light).
std::string lightParams(const BenchRow& row);
/// A row's parameters other than light.* as text.
std::string techniqueParams(const BenchRow& row);
/// "pcss · csm" plus the technique parameters when there are any.
std::string rowLabel(const BenchRow& row);
/// " + one-off 0.57 s (static casters only)" for a row with one-off costs, else "".
std::string oneOffText(const BenchRow& row);

/// The rows of a scene at its own light (or, if it has none, at the first light it was run
/// with): the group sceneCharts draws and the recommendation ranks.
std::vector<size_t> sceneRows(const BenchResults& results, const std::string& scene);

}  // namespace penumbra::report
