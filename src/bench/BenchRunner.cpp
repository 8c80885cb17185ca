#include "bench/BenchRunner.h"

#include "platform/Context.h"
#include "frame/PassTimer.h"
#include "base/ProgressBar.h"
#include "comparison/FrameComparison.h"
#include "bench/MicroBenchmarks.h"
#include "bench/Recommendation.h"
#include "bench/ReferenceBaseline.h"
#include "comparison/SequenceComparison.h"
#include "bench/VisibilityBaselines.h"

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

void writeImage(const std::filesystem::path& dir, const std::string& relative, const ColorImage& img) {
  writePng(dir / relative, img.width, img.height, img.rgba);
}

RenderOptions renderOptions(const BenchSettings& set) {
  return {.width = set.width, .height = set.height, .shadowBudgetTexels = set.shadowBudgetTexels, .debugView = 0};
}

// The whole cost of the renderer's last frame: its kShadowCostPasses.
double frameShadowCost(const Renderer& renderer) {
  FrameSamples frame;
  for (const auto& [name, ms] : renderer.timings().ms) frame.emplace_back(name, std::vector<double>{ms});
  return shadowCostStats(frame).median;
}

// The recommendation's contenders timed again in interleaved rounds (timeInterleaved).
void retimeContenders(BenchResults& results, const SetupFactory& makeSetup, const RunOptions& options) {
  const BenchSettings& set = options.settings;
  for (const SituationPicks& p : recommend(results)) {
    if (p.contenders.size() < 2) continue;  // nothing to compare: its own frames stand
    std::vector<BenchConfig> configs;
    std::vector<RenderOptions> renders;
    std::vector<int> mapSizes;
    for (const size_t i : p.contenders) {
      configs.push_back(results.rows[i].config);
      renders.push_back(renderOptions(set));
      mapSizes.push_back(results.rows[i].shadowMapSize);
    }
    const std::vector<std::vector<double>> ms =
        timeInterleaved(configs, renders, mapSizes, makeSetup, set.warmupFrames, set.retimeRounds);
    for (size_t k = 0; k < p.contenders.size(); ++k)
      results.rows[p.contenders[k]].rounds = RoundCosts{.group = p.situation->id, .ms = ms[k], .stats = timeStats(ms[k])};
    if (options.verbose || options.progress)
      std::fprintf(stderr, "penumbra bench: %s: %zu contenders timed again in %d interleaved rounds\n", p.situation->id,
                   p.contenders.size(), set.retimeRounds);
  }
}

ReferenceOptions referenceOptions(const BenchSettings& set) {
  ReferenceOptions ro;
  ro.samples = set.referenceSamples;
  ro.useCache = set.useCache;
  ro.cacheMaxBytes = set.cacheMaxBytes;
  ro.progress = false;  // the bench's own bar is on screen
  return ro;
}

// A moving row's score: its frames' metrics (and colour), flicker and a paged projection's pages.
MotionScore motionScore(const SequenceComparison& seq, bool walk) {
  MotionScore motion{.what = walk ? kWalkMotion : kAnimationMotion, .fps = kMotionFps, .frames = {},
                     .colourFrames = {}, .flicker = seq.flicker, .pagesDrawn = {}};
  for (const SequenceFrame& f : seq.frames) {
    motion.frames.push_back(f.metrics);
    if (f.colour) motion.colourFrames.push_back(*f.colour);
  }
  if (motion.colourFrames.size() != motion.frames.size()) motion.colourFrames.clear();
  // A paged projection's pages drawn a frame (a light that pages has a pool).
  for (const SequenceFrame& f : seq.frames) {
    int drawn = 0;
    bool paged = false;
    for (const LightShadowReport& l : f.lights) {
      drawn += l.pages.drawn;
      paged = paged || l.pages.poolPages > 0;
    }
    if (paged) motion.pagesDrawn.push_back(drawn);
  }
  return motion;
}

// The configurations measured one after another on one renderer, with the state they share: per
// scene its reference tracer, and per light key the references and reference images made so far.
class ConfigSweep {
public:
  ConfigSweep(const std::vector<BenchConfig>& configs, const SetupFactory& makeSetup, const RunOptions& options,
              BenchResults& results);
  // One configuration: a row in results.rows, or an entry in results.skipped.
  void run(const BenchConfig& c);
  void finish() { mBar.reset(); }  // its last line before the next stage's

private:
  struct FrameReference {
    GBufferData gbuffer;
    std::vector<ReferenceResult> lights;
  };
  void show(const BenchConfig& c, const BenchSetup& s, const std::string& light);
  void measure(const BenchConfig& c, const BenchSetup& s, const std::string& light, Clock::time_point configStart);
  const FrameReference& reference(const std::string& light);
  BenchRow benchRow(const BenchConfig& c, const Technique& technique, WarmTimes& times, const FrameComparison& cmp);
  MotionScore scoreMotion(const BenchConfig& c, const Scene& scene, const RenderOptions& render, const std::string& light);
  void writeGridImages(BenchRow& row, const BenchConfig& c, const FrameComparison& cmp, const std::string& light);
  void printRow(const BenchRow& b, const BenchConfig& c, Clock::time_point configStart) const;
  void done();

  const SetupFactory& mMakeSetup;
  const RunOptions& mOptions;
  const BenchSettings& mSet;
  BenchResults& mResults;
  Renderer mRenderer;
  std::optional<std::string> mCurrentScene, mCurrentLight;
  std::unique_ptr<ReferenceTracer> mTracer;
  std::map<std::string, FrameReference> mReferences;  // by light key, for the current scene
  std::map<std::string, SequenceReferences> mMotionReferences;  // by light key: the motion's frames
  std::map<std::string, std::string> mReferenceImages;  // by light key: file written for the grid
  std::optional<ProgressBar> mBar;
};

ConfigSweep::ConfigSweep(const std::vector<BenchConfig>& configs, const SetupFactory& makeSetup, const RunOptions& options,
                         BenchResults& results)
    : mMakeSetup(makeSetup), mOptions(options), mSet(options.settings), mResults(results) {
  mBar.emplace("penumbra bench: configurations", configs.size(), options.progress && !options.verbose,
               ProgressBar::Elsewhere::Lines);
}

void ConfigSweep::done() {
  mBar->advance(1);
  if (mOptions.configDone) mOptions.configDone();
}

void ConfigSweep::run(const BenchConfig& c) {
  BenchSetup s = mMakeSetup(c);
  const std::string light = lightKey(c);
  show(c, s, light);
  if (mSet.shadowMapSize) s.technique.setMapSize(*mSet.shadowMapSize);
  const auto configStart = Clock::now();
  try {
    mRenderer.setTechnique(s.technique);
  } catch (const Error& e) {
    if (e.kind() != ErrorKind::Usage) throw;
    mResults.skipped.push_back({c, e.what(), false});
    done();
    return;
  }
  try {
    measure(c, s, light, configStart);
  } catch (const std::exception& e) {
    mResults.skipped.push_back({c, e.what(), true});
    if (mOptions.verbose) std::fprintf(stderr, "bench: %s %s %s failed: %s\n", c.scene.c_str(), c.projection.c_str(), c.filter.c_str(), e.what());
  }
  done();
}

// The configuration's scene in the renderer: a new scene starts afresh (tracer, references,
// images); a new light key on the same scene moves only the camera and lights.
void ConfigSweep::show(const BenchConfig& c, const BenchSetup& s, const std::string& light) {
  if (mCurrentScene != c.scene) {
    mRenderer.setScene(s.scene);
    mTracer = std::make_unique<ReferenceTracer>(s.scene);
    mReferences.clear();
    mMotionReferences.clear();
    mReferenceImages.clear();
    mCurrentScene = c.scene;
    mCurrentLight = light;
  } else if (mCurrentLight != light) {
    mRenderer.setCameraAndLights(s.scene.camera, s.scene.lights);
    mCurrentLight = light;
  }
}

// Times the configuration's frames, compares its frame (and its motion) with the reference,
// writes its grid images and keeps its row.
void ConfigSweep::measure(const BenchConfig& c, const BenchSetup& s, const std::string& light, Clock::time_point configStart) {
  const RenderOptions render = renderOptions(mSet);
  WarmTimes times = timeWarmFrames(mRenderer, render, mSet.warmupFrames, mSet.timedFrames, mSet.maxSecondsPerConfig);
  mResults.machine.clock = times.clock;
  const FrameReference& ref = reference(light);
  const FrameComparison cmp = compareFrame(mRenderer, ref.gbuffer, ref.lights, c.inGrid);
  BenchRow row = benchRow(c, s.technique, times, cmp);
  // One-off work (a bake) is redone as casters move: such a row is left out where they may.
  const bool rebakes = c.motion == MotionKind::Animation && !row.oneOff.empty();
  if (c.motion != MotionKind::None && mSet.motionFrames > 1 && !rebakes) row.motion = scoreMotion(c, s.scene, render, light);
  if (c.inGrid) writeGridImages(row, c, cmp, light);
  mResults.rows.push_back(std::move(row));
  if (mOptions.verbose) printRow(mResults.rows.back(), c, configStart);
}

// The light key's reference on the current scene, traced from the renderer's G-buffer the first time.
const ConfigSweep::FrameReference& ConfigSweep::reference(const std::string& light) {
  if (!mReferences.contains(light)) {
    FrameReference& r = mReferences[light];
    r.gbuffer = mRenderer.readGBuffer();
    r.lights = traceLights(*mTracer, r.gbuffer, mRenderer.scene().lights, referenceOptions(mSet));
  }
  return mReferences[light];
}

// The row of the frame just measured (its times moved in).
BenchRow ConfigSweep::benchRow(const BenchConfig& c, const Technique& technique, WarmTimes& times, const FrameComparison& cmp) {
  BenchRow row;
  row.config = c;
  row.lightSize = mRenderer.scene().light().size;
  row.lights = static_cast<int>(mRenderer.lightCount());
  row.width = mSet.width;
  row.height = mSet.height;
  row.shadowMapSize = technique.mapSize();
  row.grantedMapSize = technique.mapSize();
  for (const LightShadowReport& l : mRenderer.shadows().lightReports())
    if (l.views > 0) {
      row.grantedMapSize = l.mapSize;
      break;
    }
  row.frames = times.frames;
  row.passes = std::move(times.passes);
  row.frameMs = std::move(times.frameMs);
  row.shadowCost = times.shadowCost;
  row.memoryBytes = mRenderer.shadows().techniqueMemoryBytes();
  row.oneOff = oneOffCosts(mRenderer.shadows());
  row.metrics = cmp.metrics;
  row.colour = cmp.colour;
  return row;
}

// The still frame again, then the scene's animation (or a camera walk where nothing moves) at
// kMotionFps; the renderer goes back to the still pose for the next row.
MotionScore ConfigSweep::scoreMotion(const BenchConfig& c, const Scene& scene, const RenderOptions& render, const std::string& light) {
  const SequenceTiming timing{mSet.motionFrames, kMotionFps, 0.0f};
  Scene moving = scene;
  const bool walk = c.motion == MotionKind::Walk || moving.animation.empty();
  if (walk) addCameraWalk(moving, timing);
  const SequenceComparison seq =
      compareSequence(mRenderer, moving, render, timing, referenceOptions(mSet), {}, {}, {}, &mMotionReferences[light]);
  mRenderer.setPose(scene);
  return motionScore(seq, walk);
}

// The grid's images of the row: the technique's frame, its heatmap, and the light key's reference
// (written once per scene and light key).
void ConfigSweep::writeGridImages(BenchRow& row, const BenchConfig& c, const FrameComparison& cmp, const std::string& light) {
  const std::string scene = fileStem(mRenderer.scene().name);
  // The suffix through fmt rather than "-" + string: GCC 12 inlines that into a false -Wrestrict.
  const std::string params = c.params.empty() ? std::string() : fmt::format("-{}", fileStem(c.paramsText()));
  const std::string stem = fmt::format("images/{}-{}-{}{}", scene, fileStem(c.projection), fileStem(c.filter), params);
  row.imagePath = stem + ".png";
  row.heatmapPath = stem + "-heatmap.png";
  writeImage(mOptions.outDir, row.imagePath, cmp.technique);
  writeImage(mOptions.outDir, row.heatmapPath, cmp.heatmap);
  if (!mReferenceImages.contains(light)) {
    const std::string path = fmt::format("images/{}-reference{}.png", scene, light.empty() ? "" : "-" + fileStem(light));
    writeImage(mOptions.outDir, path, cmp.reference);
    mReferenceImages[light] = path;
  }
  row.referencePath = mReferenceImages[light];
}

void ConfigSweep::printRow(const BenchRow& b, const BenchConfig& c, Clock::time_point configStart) const {
  const std::string motion = b.motion ? fmt::format(", flicker {:.3f}% over {} frames", b.motion->flicker.pct(), b.motion->frames.size())
                                      : std::string();
  const std::string colour = b.colour ? fmt::format(", colour RMSE {:.4f}", b.colour->rmse) : std::string();
  std::fprintf(stderr, "bench: %s %s %s %s: shadow cost %.2f ms, %.1f MiB, RMSE %.4f%s%s (%d frames, %.1f s)\n",
               c.scene.c_str(), c.projection.c_str(), c.filter.c_str(), c.paramsText().c_str(), b.shadowCost.median,
               b.memoryMiB(), b.metrics.rmse, colour.c_str(), motion.c_str(), b.frames,
               std::chrono::duration<double>(Clock::now() - configStart).count());
}

// Building blocks on a map of the run's size: the one asked for, else the largest a scene used.
void runMicro(BenchResults& results, const RunOptions& options, bool cpuClock) {
  const BenchSettings& set = options.settings;
  int microMapSize = set.shadowMapSize.value_or(0);
  for (const BenchRow& row : results.rows) microMapSize = std::max(microMapSize, row.shadowMapSize);
  if (microMapSize == 0) microMapSize = ShadowSettings{}.mapSize;
  if (options.verbose || options.progress)
    std::fprintf(stderr, "penumbra bench: micro-benchmarks, %d rounds\n", set.microRepetitions);
  results.micro = runMicroBenchmarks(microMapSize, set.microRepetitions, cpuClock);
  for (MicroResult& m : runVisibilityBaselines({.width = set.width, .height = set.height, .mapSize = microMapSize,
                                                .rounds = set.microRepetitions, .cpuClock = cpuClock}))
    results.micro.push_back(std::move(m));
  for (MicroResult& m : runReferenceBaseline(set.width, set.height, set.microRepetitions)) results.micro.push_back(std::move(m));
}

}  // namespace

std::vector<std::vector<double>> timeInterleaved(const std::vector<BenchConfig>& configs, const std::vector<RenderOptions>& renders,
                                                 const std::vector<int>& mapSizes, const SetupFactory& makeSetup, int warmupFrames,
                                                 int rounds) {
  PN_CHECK(configs.size() == renders.size() && configs.size() == mapSizes.size(),
           "timeInterleaved: one render setting and map size per configuration");
  std::vector<std::unique_ptr<Renderer>> renderers;
  for (size_t k = 0; k < configs.size(); ++k) {
    BenchSetup s = makeSetup(configs[k]);
    auto r = std::make_unique<Renderer>();
    r->setScene(std::move(s.scene));
    r->setTechnique(s.technique.setMapSize(mapSizes[k]));
    for (int w = 0; w < std::max(warmupFrames, 1); ++w) r->render(renders[k]);
    renderers.push_back(std::move(r));
  }
  std::vector<std::vector<double>> ms(configs.size());
  for (int round = 0; round < rounds; ++round)
    for (size_t k = 0; k < renderers.size(); ++k) {
      renderers[k]->render(renders[k]);
      ms[k].push_back(frameShadowCost(*renderers[k]));
    }
  return ms;
}

WarmTimes timeWarmFrames(Renderer& renderer, const RenderOptions& render, int warmupFrames, int timedFrames, double maxSeconds) {
  for (int i = 0; i < std::max(warmupFrames, 1); ++i) renderer.render(render);
  // Per-pass samples over the timed frames, in first-seen pass order.
  std::vector<std::string> order;
  std::map<std::string, std::vector<double>> ms;
  const auto add = [&](const std::string& name, double value) {
    if (!ms.contains(name)) order.push_back(name);
    ms[name].push_back(value);
  };
  WarmTimes out;
  const auto timedStart = Clock::now();
  while (out.frames < std::max(timedFrames, 1)) {
    renderer.render(render);
    const PassTimings& t = renderer.timings();
    for (const auto& [name, v] : t.ms) add(name, v);
    add(kTotalPass, t.total());
    out.clock = t.clock;
    ++out.frames;
    if (std::chrono::duration<double>(Clock::now() - timedStart).count() > maxSeconds) break;
  }
  for (const std::string& name : order) {
    out.passes.push_back({name, timeStats(ms[name])});
    if (name != kTotalPass) out.frameMs.emplace_back(name, ms[name]);
  }
  out.shadowCost = shadowCostStats(out.frameMs);
  return out;
}

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

  // Every configuration measured in turn on one renderer: its times, its error against the
  // reference (and over its motion), its grid images; refused or failed ones are skipped.
  ConfigSweep sweep(configs, makeSetup, options, results);
  for (const BenchConfig& c : configs) sweep.run(c);
  sweep.finish();
  // The recommendation's contenders timed again in interleaved rounds.
  if (set.retimeRounds > 0 && !results.rows.empty()) retimeContenders(results, makeSetup, options);
  // The micro-benchmarks: building blocks and baselines on their own.
  const bool cpuClock = context.info().softwareRenderer;
  if (options.microBenchmarks) runMicro(results, options, cpuClock);
  if (results.machine.clock.empty()) results.machine.clock = PassTimer(cpuClock).endFrame().clock;  // no frame ran: its name
  results.seconds = std::chrono::duration<double>(Clock::now() - runStart).count();
  results.machine.loadEnd = loadAverage();
  return results;
}

}  // namespace penumbra::report
