#include "bench/ReferenceBaseline.h"

#include "bench/MicroBenchmarks.h"
#include "frame/PassTimer.h"
#include "reference/RayBenchmark.h"

#include <penumbra/Renderer.h>
#include <penumbra/SceneIO.h>

#include <fmt/format.h>

#include <memory>

namespace penumbra::report {
namespace {

constexpr double kMsPerSecond = 1e3;

// boxes' G-buffer from Penumbra's renderer (the technique does not matter: only the G-buffer is
// read) and the rays the reference casts on it.
std::shared_ptr<reference::RayBenchmark> makeBenchmark(int width, int height) {
  const Scene scene = makeBuiltinScene("boxes");
  Renderer renderer;
  renderer.setScene(scene);
  constexpr int kMapSize = 512;  // any: the G-buffer does not depend on it
  renderer.setTechnique(Technique("uniform", "hard").setMapSize(kMapSize));
  renderer.render({.width = width, .height = height, .debugView = 0});
  return std::make_shared<reference::RayBenchmark>(scene, renderer.readGBuffer(), scene.light(), kReferenceBaselineSamples);
}

}  // namespace

std::vector<MicroResult> runReferenceBaseline(int width, int height, int rounds) {
  auto shared = std::make_shared<std::shared_ptr<reference::RayBenchmark>>();
  auto get = [shared, width, height] {
    if (!*shared) *shared = makeBenchmark(width, height);
    return *shared;
  };
  const std::string where = fmt::format("boxes at {}x{}, its sun at {} samples a pixel", width, height, kReferenceBaselineSamples);
  constexpr const char* kPlainLoop = "reference: plain Embree loop";
  // One row: a RayBenchmark run timed in milliseconds, by the process's CPU time with
  // PENUMBRA_CLOCK=cpu (every thread's: steady on a shared machine), else its wall seconds.
  const bool cpu = processCpuClockWanted();
  auto row = [&](const char* name, const std::string& what, const char* baseline, double (reference::RayBenchmark::*run)() const) {
    return MicroItem{name, fmt::format("{} ({}; {})", what, where, cpu ? "process CPU time" : "wall clock"), baseline, [get, run, cpu] {
                       auto b = get();
                       return std::function<double()>([b, run, cpu] {
                         if (!cpu) return kMsPerSecond * ((*b).*run)();
                         const double start = processCpuMs();
                         ((*b).*run)();
                         return processCpuMs() - start;
                       });
                     }};
  };
  constexpr const char* kSingleRays = "reference: one rtcOccluded1 call a ray";
  constexpr const char* kTrace = "reference: ReferenceTracer::trace";
  std::vector<MicroItem> items = {
      row(kPlainLoop, "the reference's rays, recorded up front, each pixel's one coherent rtcOccluded1M stream skipping its triangle, rows over every core",
          "", &reference::RayBenchmark::tracePlainLoop),
      row(kSingleRays, "the same recorded rays cast the plainest way: one rtcOccluded1 call a ray, no stream, skipping the pixel's triangle, rows over every core",
          kPlainLoop, &reference::RayBenchmark::traceSingleRays),
      row("reference: plain loop generating the rays",
          "the same rays generated per pixel by the tracer's own generator and cast as the plain loop casts them, nothing summed or kept",
          kPlainLoop, &reference::RayBenchmark::traceGeneratingLoop),
      row(kTrace, "the same rays generated, cast and summed by the reference, cache off", kPlainLoop,
          &reference::RayBenchmark::traceReference),
  };
  // The tracer's times once more, over the loop that casts the recorded rays one call each.
  MicroItem again = items.back();
  again.name = fmt::format("{}, against one call a ray", kTrace);
  again.baseline = kSingleRays;
  again.sameAs = kTrace;
  items.push_back(std::move(again));
  return runMicroItems(items, rounds);
}

}  // namespace penumbra::report
