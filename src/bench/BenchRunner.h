#pragma once
// Runs the configurations of a bench: per configuration, warm-up frames (the first compiles the
// shaders), then timed frames; per-pass median and p10–p90; quality against the ray-traced
// reference, traced once per scene and light (a sweep over a technique parameter reuses it, a
// light.size sweep does not) and cached on disk; the image-grid images; micro-benchmarks.
#include "bench/BenchResults.h"

#include <penumbra/Scene.h>
#include <penumbra/Technique.h>

#include <penumbra/Renderer.h>

#include <filesystem>
#include <functional>
#include <limits>
#include <memory>

namespace penumbra {
namespace gl { class Context; }
}

namespace penumbra::report {

/// A configuration made concrete: the scene with its parameters (light.size …) applied, and the
/// technique with its own. Made by the caller (the CLI's makeSetup), so that scene files,
/// scene-level params and --set rules live in one place.
struct BenchSetup {
  Scene scene;
  Technique technique;  ///< ids, map size (the scene's) and every parameter (add-ons included)
};
using SetupFactory = std::function<BenchSetup(const BenchConfig&)>;

struct RunOptions {
  BenchSettings settings;
  std::filesystem::path outDir;  ///< images go to outDir/images/
  /// Progress on stderr: a bar on a terminal, elsewhere a line every 15 s; and a line per stage.
  bool progress = true;
  bool verbose = false;          ///< one line per configuration on stderr
  /// The micro-benchmarks after the configurations (off: only the rows; `penumbra tune`).
  bool microBenchmarks = true;
  /// Called after each configuration, measured or not (`penumbra tune`'s progress line).
  std::function<void()> configDone = {};
};

/// Runs every configuration on `context` (current on this thread). A pair the renderer refuses
/// (usage Error from setTechnique) is recorded as skipped; an Error while rendering one is
/// recorded as failed and the run goes on. Errors of the factory propagate.
BenchResults runBench(gl::Context& context, const std::vector<BenchConfig>& configs, const SetupFactory& makeSetup,
                      const RunOptions& options);

/// Warm per-pass times: `warmupFrames` untimed frames (at least one: the first compiles the
/// technique's shaders), then up to `timedFrames` timed ones, stopping after `maxSeconds` of
/// them (at least one frame is timed). What bench and compare print.
struct WarmTimes {
  std::vector<PassStats> passes;  ///< per pass median and p10–p90, in frame order, then kTotalPass
  FrameSamples frameMs;           ///< the samples behind them (no total)
  TimeStats shadowCost;           ///< shadowCostStats(frameMs): the whole cost per frame
  int frames = 0;                 ///< timed frames run
  std::string clock;              ///< PassTimings::clock
};
WarmTimes timeWarmFrames(Renderer& renderer, const RenderOptions& render, int warmupFrames, int timedFrames,
                         double maxSeconds = std::numeric_limits<double>::infinity());

/// Times configurations in interleaved rounds: each in a renderer of its own (scene and technique
/// from `makeSetup`, its maps of its `mapSizes` entry, rendered with its `renders` entry), `warmupFrames` untimed frames each, then
/// `rounds` rounds of one frame of each, so that a round's times share the machine's load and a
/// ratio taken within a round cancels it. Returns per configuration its whole cost (the
/// kShadowCostPasses of the frame) in each round. Errors of the factory or the renderer propagate.
std::vector<std::vector<double>> timeInterleaved(const std::vector<BenchConfig>& configs, const std::vector<RenderOptions>& renders,
                                                 const std::vector<int>& mapSizes, const SetupFactory& makeSetup, int warmupFrames,
                                                 int rounds);

/// "city-csm-pcss" → a file-name-safe stem (letters, digits, '.', '-', '_').
std::string fileStem(std::string_view text);

}  // namespace penumbra::report
