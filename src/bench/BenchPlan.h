#pragma once
// What `penumbra bench` runs: lists of scenes × projections × filters, parameter sweeps over any
// ParamDesc key (light.size included), and the settings every configuration shares. Pure C++
// (no GL): the expansion into configurations is unit-tested (tests/unit/BenchReportTest.cpp).
#include <penumbra/Params.h>
#include <penumbra/Reference.h>
#include <penumbra/Renderer.h>

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace penumbra::report {

/// `--sweep key=from:to:count`: count values evenly spaced from `from` to `to` (both included);
/// `--sweep key=a,b,c`: those values (e.g. light.count=1,2,4,8, or by name: translucent.method=map,stochastic).
struct Sweep {
  std::string key;
  float from = 0.0f, to = 0.0f;
  int count = 1;
  std::vector<float> list;  ///< the values as listed; when not empty, from/to/count are unused
  /// The values as listed by name where one of them is not a number (a choice:
  /// translucent.method=stochastic, contact.shadows=on), read with the parameter's description.
  std::vector<std::string> names;
  /// The values; rounded and de-duplicated for integer and choice parameters of `desc`. Throws a
  /// usage Error for a name the parameter does not have.
  std::vector<float> values(const ParamDesc& desc) const;
};

/// Parses "key=from:to:count" or "key=a,b,…"; throws a usage Error naming the text on bad syntax,
/// count < 1 or more than kMaxSweepCount values.
Sweep parseSweep(std::string_view text);

/// Highest count one sweep may have: a guard against a typo that would run for hours.
inline constexpr int kMaxSweepCount = 64;

/// The plan that sweeps light.count, and the scene it runs on.
inline constexpr std::string_view kLightCountPlan = "light-count";
inline constexpr std::string_view kLightCountScene = "night";

/// One cross product of scenes × projections × filters, each run once per combination of the
/// values of the sweeps that apply to it (a sweep applies when its key is a scene parameter or
/// is declared by the configuration's projection or filter).
struct BenchPlan {
  std::string name;  ///< "matrix", "light-size", "custom": the group a row belongs to
  std::vector<std::string> scenes, projections, filters;
  std::vector<Sweep> sweeps;
};

/// What a row is scored over besides its still frame.
enum class MotionKind {
  None,       ///< the still frame only
  Animation,  ///< the scene's own animation (a camera walk where it has none): casters may move
  Walk,       ///< a camera walk around the target (SequenceComparison.h): nothing in the scene moves
};

/// One configuration to measure.
struct BenchConfig {
  std::string plan;
  std::string scene, projection, filter;
  /// Swept values as "key" → "value" text (parseParamValue form), applied after the scene's own
  /// parameters. Empty: the technique's defaults.
  std::vector<std::pair<std::string, std::string>> params;
  /// Shown in the report's image grid (technique | reference | heatmap).
  bool inGrid = false;
  /// Also scored in motion (BenchSettings::motionFrames): the rows a recommendation's situation
  /// judges (markMotion, Recommendation.h).
  MotionKind motion = MotionKind::None;
  /// "key=value;key=value" of `params`, "" when there are none.
  std::string paramsText() const;
};

/// Settings shared by every configuration of a run. The defaults are those of `render` and
/// `compare` (RenderOptions, the scene's ShadowSettings, ReferenceOptions), so that a row's
/// numbers are what `compare` gives for the same technique (BenchRow's compare command).
struct BenchSettings {
  int width = RenderOptions{}.width, height = RenderOptions{}.height;  ///< image size (pixels)
  /// Texels per side of each shadow map; unset = each scene's own (ShadowSettings::mapSize).
  std::optional<int> shadowMapSize;
  /// Texels every light's maps share (RenderOptions::shadowBudgetTexels, compare's
  /// --shadow-budget); 0 = none.
  int64_t shadowBudgetTexels = 0;
  int warmupFrames = 1;           ///< untimed frames first: the first one compiles the shaders
  /// Timed frames per configuration (median and spread over them). Nine keeps the median steady
  /// on a loaded machine (llvmpipe shares the CPU with everything else) at ~1 s per configuration.
  int timedFrames = 9;
  /// A configuration stops after this many seconds of timed frames (at least one frame is
  /// always timed): a technique that is very slow on this machine does not hold up the run.
  double maxSecondsPerConfig = 4.0;
  int referenceSamples = ReferenceOptions{}.samples;  ///< light samples per pixel of the reference
  bool useCache = true;           ///< on-disk reference cache
  /// Cap of the cache folder in bytes (ReferenceOptions::cacheMaxBytes); unset = the default.
  std::optional<std::uintmax_t> cacheMaxBytes;
  /// Timed rounds of the micro-benchmarks (each round runs every block once, interleaved). Nine,
  /// as timedFrames: each visibility pass is timed in a whole frame, ~0.4 s at 1280×720 on llvmpipe.
  int microRepetitions = 9;
  /// `--camera` of the run's one scene (cameraArgument form, as typed); "" = each scene's own.
  std::string camera;
  /// Frames a BenchConfig::motion row is also scored over, at kMotionFps from t = 0 (frame 0 is
  /// the still frame): the scene's own animation, or a camera walk (addCameraWalk) where the scene
  /// does not move. Its error over the frames and its flicker decide the recommendation. Six
  /// frames give five frame pairs for flicker at about twice a still frame's cost per row; 0 or 1
  /// = still frames only.
  int motionFrames = 6;
  /// Rounds in which the recommendation's contenders are timed again, interleaved (one frame
  /// each per round), for costs that share the machine's load; 0 = none (tune).
  int retimeRounds = 9;
  /// `--quick`: small images and maps, few frames, a noisy reference: its recommendation is a
  /// first look at the tool, not one to decide on, and its pages say so.
  bool quick = false;
};

/// The frame rate of the bench's motion: consecutive frames as a game shows them.
inline constexpr float kMotionFps = 30.0f;

/// The plan that measures light through translucent casters (translucentPlans).
inline constexpr std::string_view kTranslucentPlan = "translucent";
/// The filters the translucent plan shadows through the add-on's map: one of each family the
/// three techniques build on (a hard edge, a filtered edge, moments).
inline constexpr const char* kTranslucentPlanFilters[] = {"hard", "pcf", "msm"};

/// What a run adds for its scenes with translucent casters (any material with a transmittance):
/// the three ways Penumbra shadows through them (docs/translucent.md), beside the run's own rows
/// on those scenes, which draw them as opaque (the baseline that ignores translucency):
/// translucent.shadows=on (the add-on's coloured transmittance map) with each of the run's
/// filters among kTranslucentPlanFilters; msm.translucent=on with msm; translucent.method=
/// stochastic with temporal.accumulate=on with pcf (its dither resolved over frames). At the
/// uniform projection where the run has it, else at the run's projections. Empty where no scene
/// of the run has translucent casters, or none of those filters is in it.
std::vector<BenchPlan> translucentPlans(const BenchPlan& run);

/// Every configuration of the plans, in run order: grouped by scene (one upload; one reference
/// per light of the scene), in plan order within a scene, so a technique's swept values run one
/// after the other. One configuration per scene and filter is
/// marked inGrid: the first with the scene's own projection and no swept value (else the
/// closest to that). Throws a usage Error for an unknown scene or id, a sweep
/// whose key no technique of its plan declares, or swept values outside the parameter's range.
std::vector<BenchConfig> expandPlans(const std::vector<BenchPlan>& plans);

/// The plans of `penumbra bench` with no arguments (quick = the `--quick` variant): every
/// registered filter and projection on every built-in scene, plus a light-size sweep of every
/// filter on the `pen` scene (cost vs light size), contact shadows off and on, the light-count
/// plan and the translucent plans on `glass` (translucentPlans). Also sets the matching settings.
std::vector<BenchPlan> defaultPlans(bool quick, BenchSettings& settings);

}  // namespace penumbra::report
