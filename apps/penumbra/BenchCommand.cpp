// penumbra bench: every configuration of scenes × projections × filters (× sweeps) timed and
// measured against the reference; writes results.csv, results.json and report.html (docs/bench.md).
#include "Commands.h"
#include "Common.h"

#include "platform/Context.h"
#include "bench/BenchRunner.h"
#include "report/ChoosingPage.h"
#include "report/HtmlReport.h"
#include "bench/Recommendation.h"
#include "bench/ResultsIO.h"
#include "bench/ScaleBench.h"

#include <penumbra/Error.h>
#include <penumbra/Reference.h>

#include <fmt/format.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <optional>

namespace penumbra::app {
namespace {
constexpr double kMaxSecondsPerConfig = 3600.0;  // --max-seconds: an hour of timing per configuration
constexpr double kMaxScaleMTriangles = 100.0;    // --scale: millions of triangles of one generated grid
}  // namespace

void addBenchCommand(CLI::App& app, std::vector<Command>& commands) {
  struct Options {
    std::vector<std::string> scenes, filters, projections, sweeps;
    std::optional<std::string> size, camera;
    std::optional<int> shadowMap, frames, warmup, samples, microRounds, motionFrames;
    std::optional<double> maxSeconds;
    std::optional<std::uintmax_t> cacheMaxMb;
    std::string out = "bench";
    std::string choosing;  ///< "" = <out>/choosing.md
    bool quick = false, noCache = false, verbose = false, microOnly = false, scaleOnly = false;
    std::vector<double> scale;  ///< --scale; empty = the default run's plan (kDefaultScalePlan), none elsewhere
  };
  auto o = std::make_shared<Options>();
  CLI::App* sub = app.add_subcommand(
      "bench", "time and measure every technique against the reference; write results.csv, results.json, report.html");
  sub->add_option("--scenes", o->scenes, "built-in scene names or scene files, comma-separated (default: every built-in scene); "
                  "a scene with translucent casters (glass) also gets, without --sweep, the techniques that shadow through them "
                  "on hard, pcf and msm (translucent.shadows, msm.translucent, translucent.method=stochastic)")
      ->delimiter(',');
  sub->add_option("--filters", o->filters, "filter ids or technique folders, comma-separated (default: every filter)")
      ->delimiter(',')
      ->transform(techniqueFolderFilter());
  sub->add_option("--projections", o->projections, "projection ids, comma-separated (default: every projection)")->delimiter(',');
  sub->add_option("--sweep", o->sweeps,
                  "key=from:to:count or key=a,b,..., repeatable: run each technique that has the parameter at "
                  "count values, or at the listed ones (light.size and light.count apply to all; e.g. "
                  "pcss.filterSamples=8:64:4, light.count=1,2,4,8; a choice by its names: translucent.method=map,stochastic)");
  sub->add_option("--frames", o->frames, "timed frames per configuration (default 9; --quick 3)")->check(CLI::Range(1, 1000));
  sub->add_option("--motion-frames", o->motionFrames,
                  "frames at 30 fps over which each row of a recommendation's scene is also scored: the scene's "
                  "animation, or a camera walk where nothing moves; the still frame is the first (default 6; --quick 3; "
                  "1 = still frames only)")
      ->check(CLI::Range(1, 100));
  sub->add_option("--warmup", o->warmup, "untimed frames first; the first compiles the shaders (default 1)")->check(CLI::Range(1, 100));
  sub->add_option("--size", o->size, fmt::format("image size WxH (default {}, as render and compare; --quick 96x64)", defaultSizeText()));
  sub->add_option("--shadow-map", o->shadowMap,
                  fmt::format("shadow-map texels per side (default: each scene's own, as render and compare; --quick {}); {}",
                              kMinDefaultsMapSizeTexels, mapSizeLimitText()))
      ->check(mapSizeOption());
  sub->add_option("--samples", o->samples,
                  fmt::format("reference light samples per pixel (default {}, as compare; --quick 36)", ReferenceOptions{}.samples))
      ->check(CLI::Range(1, kMaxReferenceSamples));
  sub->add_option("--max-seconds", o->maxSeconds, "stop timing a configuration after this many seconds (default 4)")
      ->check(finiteNumber(0.0, kMaxSecondsPerConfig));
  sub->add_option("--camera", o->camera,
                  "the view of the run's one scene (--scenes NAME): X,Y,Z:TX,TY,TZ[:FOV], position and target in "
                  "metres, vertical field of view in degrees (default: each scene's own camera)");
  sub->add_option("--out", o->out, "output folder")->capture_default_str();
  sub->add_option("--choosing", o->choosing,
                  "where to write the recommendation page, Markdown (default: OUT/choosing.md; the repository's is "
                  "docs/choosing.md)");
  sub->add_flag("--quick", o->quick, "a small run for tests: seconds, not minutes (the recommendation's four scenes, small images, few frames)");
  sub->add_flag("--no-cache", o->noCache, "recompute references even if cached ones exist");
  addCacheCapOption(*sub, o->cacheMaxMb, "after each reference is stored");
  sub->add_flag("--micro-only", o->microOnly,
                "only the micro-benchmarks (prefilters against a copy, each filter's visibility pass against its minimal "
                "kernel) at --size and --shadow-map: no configurations, no references");
  sub->add_option("--scale", o->scale,
                  "the triangle-count plan: millions of triangles of a generated height-field grid, comma-separated, each loaded "
                  "from OBJ, rendered (G-buffer and shadow pass times per triangle) and given to the reference (BVH build time "
                  "and memory); 0 = none (default: 0.5,2,8 in the default run, none in --quick and custom runs)")
      ->delimiter(',')
      ->check(finiteNumber(0.0, kMaxScaleMTriangles));
  sub->add_flag("--scale-only", o->scaleOnly, "only the triangle-count plan (--scale, default 0.5,2,8): no configurations, no micro-benchmarks");
  sub->add_option("--micro-rounds", o->microRounds, "timed rounds of the micro-benchmarks (default 9; --quick 3)")
      ->check(CLI::Range(1, 1000));
  sub->add_flag("--verbose", o->verbose, "one line per configuration on stderr instead of the progress bar");
  commands.push_back({sub, [o] {
    report::BenchSettings settings;
    std::vector<report::BenchPlan> plans = report::defaultPlans(o->quick, settings);
    const bool custom = !o->scenes.empty() || !o->filters.empty() || !o->projections.empty() || !o->sweeps.empty();
    if (custom) {
      report::BenchPlan custom{.name = "custom", .scenes = plans.front().scenes,
                               .projections = plans.front().projections, .filters = plans.front().filters, .sweeps = {}};
      if (!o->scenes.empty()) custom.scenes = o->scenes;
      if (!o->filters.empty()) custom.filters = o->filters;
      if (!o->projections.empty()) custom.projections = o->projections;
      for (const std::string& s : o->sweeps) custom.sweeps.push_back(report::parseSweep(s));
      plans = {custom};
      // Scenes with translucent casters also get the techniques that shadow through them (a run
      // with its own --sweep measures what it sweeps).
      if (custom.sweeps.empty())
        for (report::BenchPlan& p : report::translucentPlans(custom)) plans.push_back(std::move(p));
    }
    if (o->size) std::tie(settings.width, settings.height) = parseSize(*o->size);
    if (o->shadowMap) settings.shadowMapSize = *o->shadowMap;
    if (o->frames) settings.timedFrames = *o->frames;
    if (o->warmup) settings.warmupFrames = *o->warmup;
    if (o->samples) settings.referenceSamples = *o->samples;
    if (o->microRounds) settings.microRepetitions = *o->microRounds;
    if (o->motionFrames) settings.motionFrames = *o->motionFrames;
    if (o->maxSeconds) settings.maxSecondsPerConfig = *o->maxSeconds;
    settings.useCache = !o->noCache;
    settings.cacheMaxBytes = cacheCapBytes(o->cacheMaxMb);
    std::vector<report::BenchConfig> configs = report::expandPlans(plans);  // usage errors before any GL
    report::markMotion(configs);
    if (o->microOnly || o->scaleOnly) configs.clear();
    if (o->microOnly && o->scaleOnly) throw usageError("--micro-only and --scale-only: give one");
    const bool defaultRun = !o->quick && !custom;
    std::vector<double> scalePlan = !o->scale.empty() ? o->scale : (defaultRun || o->scaleOnly) ? report::kDefaultScalePlan : std::vector<double>{};
    std::erase(scalePlan, 0.0);
    if (o->camera) {
      // A viewpoint belongs to one scene: the same coordinates would look at nothing in another.
      std::vector<std::string> scenes;
      for (const report::BenchConfig& c : configs)
        if (std::find(scenes.begin(), scenes.end(), c.scene) == scenes.end()) scenes.push_back(c.scene);
      if (scenes.size() != 1)
        throw usageError(fmt::format("--camera: the run has {} scenes; a viewpoint belongs to one (add --scenes NAME)",
                                     scenes.size()));
      (void)parseCameraArgument(*o->camera, Camera{});  // a malformed camera fails here, before any GL
      settings.camera = *o->camera;
    }

    checkOutputDir("--out", o->out);
    if (!o->choosing.empty()) checkOutput("--choosing", o->choosing);
    gl::HeadlessContext context({.debug = gl::kDebugBuild, .verbose = o->verbose});
    checkImageFits(context, settings.width, settings.height, kCompareHostBytesPerPixel);  // each configuration is a compare
    const report::SetupFactory factory = benchSetupFactory(o->camera);
    const std::filesystem::path dir(o->out);
    report::BenchResults results = report::runBench(context, configs, factory,
                                                    {.settings = settings, .outDir = dir, .progress = true, .verbose = o->verbose,
                                                     .microBenchmarks = !o->scaleOnly});
    if (!scalePlan.empty()) results.scale = report::runScalePlan(context, scalePlan, settings, dir, true);
    results.machine.command = commandLine();
    report::writeResults(dir, results);
    report::writeHtmlReport(dir, results);
    const std::filesystem::path choosing = o->choosing.empty() ? dir / "choosing.md" : std::filesystem::path(o->choosing);
    report::writeChoosingPage(choosing, dir, results);

    size_t failed = 0;
    for (const report::SkippedConfig& k : results.skipped)
      if (k.failed) {
        ++failed;
        std::fprintf(stderr, "penumbra bench: %s --projection %s --filter %s %s failed: %s\n", k.config.scene.c_str(),
                     k.config.projection.c_str(), k.config.filter.c_str(), k.config.paramsText().c_str(), k.reason.c_str());
      }
    for (const report::ScaleRow& r : results.scale)
      if (!r.error.empty()) {
        ++failed;
        std::fprintf(stderr, "penumbra bench: triangle-count plan, %.2f M triangles, failed: %s\n", static_cast<double>(r.triangles) / 1e6,
                     r.error.c_str());
      }
    size_t microFailed = 0;
    for (const report::MicroResult& m : results.micro)
      if (!m.error.empty()) {
        ++microFailed;
        std::fprintf(stderr, "penumbra bench: micro-benchmark %s failed: %s\n", m.name.c_str(), m.error.c_str());
      }
    if (!results.rows.empty()) std::printf("%s", report::picksSummary(results, report::recommend(results)).c_str());
    std::printf("%zu configurations measured, %zu skipped (%zu failed) in %.1f s on %s (%s)\nreport: %s\nchoosing: %s\n",
                results.rows.size(), results.skipped.size(), failed, results.seconds, results.machine.glRenderer.c_str(),
                results.machine.clock.c_str(), (dir / "report.html").string().c_str(), choosing.string().c_str());
    if (failed > 0 || microFailed > 0) {
      std::fprintf(stderr, "penumbra bench: %zu configuration(s) and %zu micro-benchmark(s) failed; the report lists them\n",
                   failed, microFailed);
      return 1;
    }
    return 0;
  }});
}

}  // namespace penumbra::app
