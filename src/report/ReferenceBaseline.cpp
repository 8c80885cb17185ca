#include "report/ReferenceBaseline.h"

#include "report/MicroBenchmarks.h"
#include "reference/RayBenchmark.h"

#include <penumbra/Registry.h>
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
  renderer.setTechnique(makeProjection("uniform"), makeFilter("hard"));
  constexpr int kMapSize = 512;  // any: the G-buffer does not depend on it
  renderer.render({.width = width, .height = height, .shadowMapSize = kMapSize, .debugView = 0});
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
  const std::vector<MicroItem> items = {
      {"reference: plain Embree loop",
       fmt::format("the reference's rays, recorded up front, each pixel's one coherent rtcOccluded1M stream skipping its "
                   "triangle, rows over every core ({}; wall clock)", where),
       "", [get] {
         auto b = get();
         return std::function<double()>([b] { return kMsPerSecond * b->tracePlainLoop(); });
       }},
      {"reference: plain loop generating the rays",
       fmt::format("the same rays generated per pixel by the tracer's own generator and cast as the plain loop casts them, "
                   "nothing summed or kept ({}; wall clock)", where),
       "reference: plain Embree loop", [get] {
         auto b = get();
         return std::function<double()>([b] { return kMsPerSecond * b->traceGeneratingLoop(); });
       }},
      {"reference: ReferenceTracer::trace",
       fmt::format("the same rays generated, cast and summed by the reference, cache off ({}; wall clock)", where),
       "reference: plain Embree loop", [get] {
         auto b = get();
         return std::function<double()>([b] { return kMsPerSecond * b->traceReference(); });
       }},
  };
  return runMicroItems(items, rounds);
}

}  // namespace penumbra::report
