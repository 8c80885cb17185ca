#pragma once
// Options shared by the subcommands that render (render, compare, bench, view) and the one
// place that turns them into a scene + technique.
#include "bench/BenchRunner.h"

#include "techniques/Registry.h"
#include <penumbra/MapSizes.h>
#include <penumbra/Renderer.h>
#include <penumbra/SceneIO.h>

#include <CLI/CLI.hpp>

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace penumbra::gl { class Context; }

namespace penumbra::app {

/// "640x360": the image size render, compare and bench share (RenderOptions' default).
std::string defaultSizeText();

struct TechniqueOptions {
  std::string scene = "boxes";
  std::optional<std::string> filter, projection;  ///< unset = the scene's own choice
  std::vector<std::string> sets;                  ///< "key=value"
  std::string size = defaultSizeText();
  std::optional<int> shadowMapSize;
  int64_t shadowBudgetTexels = 0;  ///< 0 = no budget
  std::string mapUpdates = "every";  ///< --map-updates: every | invalid | N
  std::optional<std::string> camera;  ///< "X,Y,Z:TX,TY,TZ[:FOV]"; unset = the scene's camera
  bool verbose = false;
  std::string maxMemory;  ///< --max-memory: "" = the memory available (LoadOptions::maxMemoryBytes)
  /// The command builds the reference's BVH over the scene (compare): the load's estimate counts it.
  bool referenceBvh = false;
};

/// Adds --scene --filter --projection --set --size --shadow-map --camera --verbose --max-memory to a
/// subcommand.
void addTechniqueOptions(CLI::App& app, TechniqueOptions& o);
/// Adds --shadow-budget (render and compare; the viewer sizes maps without a budget).
void addShadowBudgetOption(CLI::App& app, TechniqueOptions& o);
/// Adds --map-updates every|invalid|N (render and compare): Shadows::setMapUpdates.
void addMapUpdatesOption(CLI::App& app, TechniqueOptions& o);
/// Whether any light's maps are cached (--map-updates, or a light's own shadow.updates).
bool mapsCached(const Shadows& shadows);
/// One line of what the map updates did (Shadows::mapCacheStats), for stderr and reports.
std::string mapUpdatesSummary(const Shadows& shadows);

struct Setup {
  Scene scene;
  Technique technique;    ///< ids, map size and every parameter (add-ons included)
  RenderOptions render;
  MapUpdates mapUpdates;  ///< --map-updates
};

/// Loads the scene, makes the technique (the scene's own, --projection/--filter over it, the map
/// size from --shadow-map or the scene), applies the scene's params then --set (usage errors for
/// anything unknown or out of range).
Setup makeSetup(const TechniqueOptions& o);

/// The scene's times (s) of a sequence's frames, as renderSequence and compareSequence pose them:
/// --time, --time + 1/--fps, … (--frames N); without --frames --time alone, none when it is 0
/// (the still scene).
std::vector<float> sequenceTimes(float timeS, std::optional<int> frames, float fps);
/// Throws penumbra::Error (exit 1) naming the scene's file when the scene posed at one of
/// `timesS` leaves what its still pose keeps (poseProblem: a camera with no view, geometry beyond
/// ±1e6 m): before any frame is drawn, so that nothing is written.
void checkPoses(const Scene& scene, std::span<const float> timesS);

/// The factory runBench (bench, tune) makes each configuration with: makeSetup on its scene,
/// technique and params (as --set), with `camera` (--camera) when given.
report::SetupFactory benchSetupFactory(const std::optional<std::string>& camera);

/// A renderer with the setup's scene and technique, which it takes over from `s` (s.scene is
/// left empty: use the renderer's scene()).
std::unique_ptr<Renderer> makeRenderer(gl::Context& context, Setup& s);

/// Adds --cache-max-mb N: the cache folder's cap in MiB for this run (unset: PENUMBRA_CACHE_MAX_MB,
/// else the default). `what` says when it applies.
void addCacheCapOption(CLI::App& app, std::optional<std::uintmax_t>& mib, const std::string& what);
/// The cap in bytes that --cache-max-mb gave, or nothing.
std::optional<std::uintmax_t> cacheCapBytes(const std::optional<std::uintmax_t>& mib);

/// Checks an output file (`option` names it in the message: "--out: x/: is a folder, not a
/// file") or output folder before any work, so that no run writes one output and then fails on
/// the next (penumbra/Files.h). Throws penumbra::Error (exit 1).
void checkOutput(const char* option, const std::string& path);
void checkOutputDir(const char* option, const std::string& path);

/// Host memory (RAM) read back per pixel by each command, besides the renderer's GPU targets
/// (Renderer::screenBytes). render: the colour image, its flipped copy and the PNG encoder's rows
/// (+ the visibility and its copy with --visibility); compare: the G-buffer read back, the
/// reference's buffers and the five images, measured as the peak at 2048² and 4096² (218 B per
/// pixel in all) less the 48 on the GPU.
inline constexpr uint64_t kRenderHostBytesPerPixel = 16, kVisibilityHostBytesPerPixel = 8;
inline constexpr uint64_t kCompareHostBytesPerPixel = 170;

/// Refuses (penumbra::Error, exit 1) an image size whose targets and read-backs cannot fit, with
/// the estimate and a size that would: before anything is allocated (a 16384² render took minutes
/// and more memory than the machine had). On a software renderer (llvmpipe) the targets live in
/// host memory too; a GPU's free memory is checked where the driver tells it
/// (GL_NVX_gpu_memory_info, GL_ATI_meminfo). Needs the context current.
void checkImageFits(const gl::Context& context, int width, int height, uint64_t hostBytesPerPixel);

/// The command line as typed (/proc/self/cmdline), the program's path shortened to its name and
/// words with spaces quoted, after PENUMBRA_CLOCK=… when that variable is set (it decides what
/// every time means): what bench and tune record of their run.
std::string commandLine();

/// --max-memory's text ("1500" MiB, or with a unit: "512M", "8G", "1.5GiB") in bytes; throws a
/// usage error otherwise.
uint64_t parseMemorySize(const std::string& text);

/// Adds --fps (frames per second of the sequence --frames gives, refused without it) and --time
/// (the scene's time in seconds, as far as a scene file's key times reach: ±1e6 s), each checked
/// finite and in range while the command line is read (render and compare).
void addTimeOptions(CLI::App& app, CLI::Option* frames, float& fps, float& timeS, const std::string& timeHelp);

/// Turns a --filter value that names a technique folder (a path) into the id it registers
/// (penumbra::resolveFilter); a folder that fails to load fails the parse with its message.
CLI::Validator techniqueFolderFilter();

/// The check of a floating-point option: a finite number in [lo, hi] ((lo, hi] with `aboveLo`).
/// CLI::Range and CLI::PositiveNumber let NaN through (every comparison with it is false).
CLI::Validator finiteNumber(double lo, double hi, bool aboveLo = false);
/// The check of a --shadow-map option (render, compare, view, bench, tune): a whole number of
/// texels per side in [kMinDefaultsMapSizeTexels, kMaxMapSizeTexels]; its refusal says why the
/// least is that (mapSizeLimitText, also the options' --help).
CLI::Validator mapSizeOption();
std::string mapSizeLimitText();
/// The check of an unsigned whole-number option (a seed): digits only, at most UINT64_MAX (the
/// conversion alone would read "-1" as 2^64 - 1).
CLI::Validator unsignedNumber();

/// "640x360" → (640, 360); throws a usage error otherwise.
std::pair<int, int> parseSize(const std::string& text);

}  // namespace penumbra::app
