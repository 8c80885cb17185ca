#pragma once
// Runs the configurations of a bench: per configuration, warm-up frames (the first compiles the
// shaders), then timed frames; per-pass median and p10–p90; quality against the ray-traced
// reference, traced once per scene and light (a sweep over a technique parameter reuses it, a
// light.size sweep does not) and cached on disk; the image-grid images; micro-benchmarks.
#include "report/BenchResults.h"

#include <penumbra/Filter.h>
#include <penumbra/Registry.h>
#include <penumbra/Projection.h>
#include <penumbra/Scene.h>

#include <filesystem>
#include <functional>
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
  std::unique_ptr<Projection> projection;
  std::unique_ptr<Filter> filter;
  std::unique_ptr<Parameterized> addOns = makeAddOns();  ///< "contact.*", "temporal.*"
};
using SetupFactory = std::function<BenchSetup(const BenchConfig&)>;

struct RunOptions {
  BenchSettings settings;
  std::filesystem::path outDir;  ///< images go to outDir/images/
  bool progress = true;          ///< progress bar on stderr (drawn only when it is a terminal)
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

/// "city-csm-pcss" → a file-name-safe stem (letters, digits, '.', '-', '_').
std::string fileStem(std::string_view text);

}  // namespace penumbra::report
