#include "report/BenchRunner.h"

#include "platform/Context.h"
#include "frame/PassTimer.h"
#include "base/ProgressBar.h"
#include "report/FrameComparison.h"
#include "report/MicroBenchmarks.h"
#include "report/ReferenceBaseline.h"
#include "report/VisibilityBaselines.h"

#include <penumbra/Error.h>
#include <penumbra/ImageIO.h>
#include <penumbra/Reference.h>
#include <penumbra/Renderer.h>

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <map>
#include <optional>

namespace penumbra::report {
namespace {

using Clock = std::chrono::steady_clock;

// The light.* parameters of a configuration: configurations that share them (and the scene)
// share one reference.
std::string lightKey(const BenchConfig& c) {
  std::string key;
  for (const auto& [k, v] : c.params)
    if (k.starts_with("light.")) key += k + "=" + v + ";";
  return key;
}

// Per-pass samples over the timed frames, in first-seen pass order.
struct PassSamples {
  std::vector<std::string> order;
  std::map<std::string, std::vector<double>> ms;
  void add(const std::string& name, double value) {
    if (!ms.contains(name)) order.push_back(name);
    ms[name].push_back(value);
  }
};

void writeImage(const std::filesystem::path& dir, const std::string& relative, const ColorImage& img) {
  writePng(dir / relative, img.width, img.height, img.rgba);
}

}  // namespace

std::string fileStem(std::string_view text) {
  std::string out;
  for (const char ch : text) {
    const bool safe = (ch >= 'a' && ch <= 'z') || (ch >= 'A' && ch <= 'Z') || (ch >= '0' && ch <= '9') || ch == '.' ||
                      ch == '-' || ch == '_';
    out += safe ? ch : '_';
  }
  return out;
}

BenchResults runBench(gl::Context& context, const std::vector<BenchConfig>& configs, const SetupFactory& makeSetup,
                      const RunOptions& options) {
  const BenchSettings& set = options.settings;
  const auto runStart = Clock::now();
  BenchResults results;
  results.settings = set;
  results.machine = describeMachine(context.info());

  Renderer renderer;
  std::optional<std::string> currentScene, currentLight;
  std::unique_ptr<ReferenceTracer> tracer;
  struct FrameReference {
    GBufferData gbuffer;
    std::vector<ReferenceResult> lights;
  };
  std::map<std::string, FrameReference> references;  // by light key, for the current scene
  std::map<std::string, std::string> referenceImages;  // by light key: file written for the grid
  ProgressBar bar("bench", configs.size(), options.progress && !options.verbose);

  for (const BenchConfig& c : configs) {
    BenchSetup s = makeSetup(c);
    const std::string light = lightKey(c);
    if (currentScene != c.scene) {
      renderer.setScene(s.scene);
      tracer = std::make_unique<ReferenceTracer>(s.scene);
      references.clear();
      referenceImages.clear();
      currentScene = c.scene;
      currentLight = light;
    } else if (currentLight != light) {
      renderer.setCameraAndLights(s.scene.camera, s.scene.lights);
      currentLight = light;
    }
    const RenderOptions render{.width = set.width, .height = set.height,
                               .shadowMapSize = set.shadowMapSize.value_or(s.scene.shadow.mapSize),
                               .shadowBudgetTexels = set.shadowBudgetTexels, .debugView = 0};
    const auto done = [&] {
      bar.advance(1);
      if (options.configDone) options.configDone();
    };
    const auto configStart = Clock::now();
    try {
      renderer.setTechnique(std::move(s.projection), std::move(s.filter));
      renderer.shadows().addOns() = *s.addOns;
    } catch (const Error& e) {
      if (e.kind() != ErrorKind::Usage) throw;
      results.skipped.push_back({c, e.what(), false});
      done();
      continue;
    }
    try {
      for (int i = 0; i < std::max(set.warmupFrames, 1); ++i) renderer.render(render);
      PassSamples samples;
      int frames = 0;
      const auto timedStart = Clock::now();
      while (frames < set.timedFrames) {
        renderer.render(render);
        const PassTimings& t = renderer.timings();
        for (const auto& [name, ms] : t.ms) samples.add(name, ms);
        samples.add(kTotalPass, t.total());
        results.machine.clock = t.clock;
        ++frames;
        if (std::chrono::duration<double>(Clock::now() - timedStart).count() > set.maxSecondsPerConfig) break;
      }

      if (!references.contains(light)) {
        ReferenceOptions ro;
        ro.samples = set.referenceSamples;
        ro.useCache = set.useCache;
        ro.cacheMaxBytes = set.cacheMaxBytes;
        ro.progress = false;  // the bench's own bar is on screen
        FrameReference& r = references[light];
        r.gbuffer = renderer.readGBuffer();
        r.lights = traceLights(*tracer, r.gbuffer, renderer.scene().lights, ro);
      }
      const FrameReference& ref = references[light];
      const FrameComparison cmp = compareFrame(renderer, ref.gbuffer, ref.lights, c.inGrid);

      BenchRow row;
      row.config = c;
      row.lightSize = renderer.scene().light().size;
      row.lights = static_cast<int>(renderer.lightCount());
      row.width = set.width;
      row.height = set.height;
      row.shadowMapSize = render.shadowMapSize;
      row.grantedMapSize = render.shadowMapSize;
      for (const LightShadowReport& l : renderer.shadows().lightReports())
        if (l.views > 0) {
          row.grantedMapSize = l.mapSize;
          break;
        }
      row.frames = frames;
      for (const std::string& name : samples.order) {
        row.passes.push_back({name, timeStats(samples.ms[name])});
        if (name != kTotalPass) row.frameMs.emplace_back(name, samples.ms[name]);
      }
      row.shadowCost = shadowCostStats(row.frameMs);
      row.memoryBytes = renderer.shadows().techniqueMemoryBytes();
      row.oneOff = renderer.filter().oneOffCosts();
      row.metrics = cmp.metrics;
      if (c.inGrid) {
        const std::string scene = fileStem(renderer.scene().name);
        const std::string stem = fmt::format("images/{}-{}-{}", scene, fileStem(c.projection), fileStem(c.filter));
        row.imagePath = stem + ".png";
        row.heatmapPath = stem + "-heatmap.png";
        writeImage(options.outDir, row.imagePath, cmp.technique);
        writeImage(options.outDir, row.heatmapPath, cmp.heatmap);
        if (!referenceImages.contains(light)) {
          const std::string path = fmt::format("images/{}-reference{}.png", scene, light.empty() ? "" : "-" + fileStem(light));
          writeImage(options.outDir, path, cmp.reference);
          referenceImages[light] = path;
        }
        row.referencePath = referenceImages[light];
      }
      results.rows.push_back(std::move(row));
      if (options.verbose)
        std::fprintf(stderr, "bench: %s %s %s %s: shadow cost %.2f ms, %.1f MiB, RMSE %.4f (%d frames, %.1f s)\n",
                     c.scene.c_str(), c.projection.c_str(), c.filter.c_str(), c.paramsText().c_str(),
                     results.rows.back().shadowCost.median, results.rows.back().memoryMiB(), cmp.metrics.rmse, frames,
                     std::chrono::duration<double>(Clock::now() - configStart).count());
    } catch (const std::exception& e) {
      results.skipped.push_back({c, e.what(), true});
      if (options.verbose) std::fprintf(stderr, "bench: %s %s %s failed: %s\n", c.scene.c_str(), c.projection.c_str(), c.filter.c_str(), e.what());
    }
    done();
  }
  if (!options.microBenchmarks) {
    if (results.machine.clock.empty()) results.machine.clock = PassTimer(context.info().softwareRenderer).endFrame().clock;
    results.seconds = std::chrono::duration<double>(Clock::now() - runStart).count();
    results.machine.loadEnd = loadAverage();
    return results;
  }
  // Building blocks on a map of the run's size: the one asked for, else the largest a scene used.
  int microMapSize = set.shadowMapSize.value_or(0);
  for (const BenchRow& row : results.rows) microMapSize = std::max(microMapSize, row.shadowMapSize);
  if (microMapSize == 0) microMapSize = ShadowSettings{}.mapSize;
  const bool cpuClock = context.info().softwareRenderer;
  results.micro = runMicroBenchmarks(microMapSize, set.microRepetitions, cpuClock);
  for (MicroResult& m : runVisibilityBaselines({.width = set.width, .height = set.height, .mapSize = microMapSize,
                                                .rounds = set.microRepetitions, .cpuClock = cpuClock}))
    results.micro.push_back(std::move(m));
  for (MicroResult& m : runReferenceBaseline(set.width, set.height, set.microRepetitions)) results.micro.push_back(std::move(m));
  if (results.machine.clock.empty()) results.machine.clock = PassTimer(cpuClock).endFrame().clock;  // no frame ran: its name
  results.seconds = std::chrono::duration<double>(Clock::now() - runStart).count();
  results.machine.loadEnd = loadAverage();
  return results;
}

}  // namespace penumbra::report
