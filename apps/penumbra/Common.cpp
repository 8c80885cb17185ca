#include "Common.h"

#include "base/ProgressBar.h"
#include "core/ShadowBudget.h"

#include <penumbra/Error.h>
#include <penumbra/Files.h>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <cctype>
#include <charconv>
#include <cmath>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <memory>
#include <set>

namespace penumbra::app {

namespace {

/// A CLI11 check from a parser: its Error's message, or "" when the text parses.
std::function<std::string(const std::string&)> parseCheck(std::function<void(const std::string&)> parse) {
  return [parse = std::move(parse)](const std::string& text) {
    try {
      parse(text);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string();
  };
}

}  // namespace

std::string defaultSizeText() { return fmt::format("{}x{}", RenderOptions{}.width, RenderOptions{}.height); }

void addTechniqueOptions(CLI::App& app, TechniqueOptions& o) {
  app.add_option("--scene", o.scene, "built-in scene name (penumbra list shows them), scene .json file, or model file (.gltf, .glb, .obj)")
      ->capture_default_str();
  app.add_option("--filter", o.filter,
                 "shadow filter id, or the path of a technique folder (docs/own-technique.md) (default: the scene's own, else hard)")
      ->transform(techniqueFolderFilter());
  app.add_option("--projection", o.projection, "light projection id (default: the scene's own, else uniform)");
  app.add_option("--set", o.sets, "parameter override key=value, repeatable (e.g. hard.bias=slope, light.size=0.1)");
  app.add_option("--size", o.size, "image size WxH in pixels")->capture_default_str();
  app.add_option("--shadow-map", o.shadowMapSize,
                 fmt::format("shadow-map resolution in texels per side (default: the scene's own, 2048 for the built-in scenes); {}",
                             mapSizeLimitText()))
      ->check(mapSizeOption());
  app.add_option("--camera", o.camera,
                 "camera position and target in metres, and optionally the vertical field of view in degrees: "
                 "X,Y,Z:TX,TY,TZ[:FOV] (default: the scene's camera; given, it stays put in an animated scene)");
  app.add_flag("--verbose", o.verbose, "print GL_RENDERER and GL_VERSION and per-pass details");
  app.add_option("--max-memory", o.maxMemory,
                 "most memory a model file may take once loaded (its meshes, the renderer's buffers where they live in host "
                 "memory, the reference's BVH), estimated before anything is built: MiB, or with a unit (512M, 8G); a larger "
                 "model is refused with the estimate (default: the memory this machine has available)")
      ->check(parseCheck([](const std::string& text) { parseMemorySize(text); }));
}

uint64_t parseMemorySize(const std::string& text) {
  double value = 0.0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  std::string unit(end, text.data() + text.size());
  for (const char* suffix : {"iB", "B"})
    if (unit.size() > std::string(suffix).size() && unit.ends_with(suffix)) unit.resize(unit.size() - std::string(suffix).size());
  const std::string units = "KMGT";
  const size_t power = unit.empty() ? 2 : unit.size() == 1 ? units.find(static_cast<char>(std::toupper(static_cast<unsigned char>(unit[0])))) + 1 : 0;
  const double bytes = value * std::pow(1024.0, static_cast<double>(power));
  if (text.empty() || ec != std::errc() || power == 0 || power > units.size() || !(value > 0.0) || !(bytes < 1e18))
    throw usageError(fmt::format("'{}' is not a size: expected MiB, or a number with a unit K, M, G or T (e.g. 512M, 8G)", text));
  return static_cast<uint64_t>(bytes);
}

void addShadowBudgetOption(CLI::App& app, TechniqueOptions& o) {
  app.add_option("--shadow-budget", o.shadowBudgetTexels,
                 "texels every light's shadow maps share, cascades and cube faces counted (e.g. 16777216 = 4096², "
                 "64 MiB of 32-bit depth); each light's map side follows its share of the image, never above "
                 "--shadow-map; 0 = no budget")
      ->check(CLI::Range(int64_t{0}, int64_t{1} << 32));
}

void addTimeOptions(CLI::App& app, CLI::Option* frames, float& fps, float& timeS, const std::string& timeHelp) {
  constexpr double kMinFps = 0.001, kMaxFps = 1000.0, kMaxTimeS = 1e6;
  app.add_option("--fps", fps, "frames per second of the sequence (--frames)")
      ->check(finiteNumber(kMinFps, kMaxFps))
      ->capture_default_str()
      ->needs(frames);
  app.add_option("--time", timeS, timeHelp)->check(finiteNumber(-kMaxTimeS, kMaxTimeS))->capture_default_str();
}

void addMapUpdatesOption(CLI::App& app, TechniqueOptions& o) {
  app.add_option("--map-updates", o.mapUpdates,
                 "when shadow maps are drawn again: 'every' map every frame (no cache); 'invalid': each map keeps its "
                 "static casters and redraws them only when its view or a static caster changes, the dynamic "
                 "(animated) casters drawn over every frame and the light's views fitted to the static casters; N: "
                 "as 'invalid', but only N maps per frame across every light are updated (the least recently "
                 "updated first), the others keep an earlier frame's map and view (docs/embedding.md#cached-maps); "
                 "--verbose counts the maps restored, drawn and kept and their staleness in frames")
      ->check(parseCheck([](const std::string& text) { parseMapUpdates(text); }))
      ->capture_default_str();
}

bool mapsCached(const Shadows& shadows) {
  if (shadows.mapUpdates().cached()) return true;
  for (const LightShadowReport& r : shadows.lightReports())
    if (r.updates.cached()) return true;
  return false;
}

std::string mapUpdatesSummary(const Shadows& shadows) {
  const Shadows::MapCacheStats c = shadows.mapCacheStats();
  std::string policies = "--map-updates " + mapUpdatesName(shadows.mapUpdates());
  const std::vector<LightShadowReport>& lights = shadows.lightReports();
  for (size_t i = 0; i < lights.size(); ++i)  // the lights whose own policy differs from --map-updates
    if (lights[i].views > 0 && lights[i].updates != shadows.mapUpdates())
      policies += fmt::format(", light {} {}", i, mapUpdatesName(lights[i].updates));
  return fmt::format("cached maps: {} restored, {} drawn, {} kept ({}); staleness max {}, mean {:.2f} frames", c.restored,
                     c.rendered, c.kept, policies, c.maxStaleness, c.meanStaleness);
}

void addCacheCapOption(CLI::App& app, std::optional<std::uintmax_t>& mib, const std::string& what) {
  app.add_option("--cache-max-mb", mib,
                 fmt::format("cap of the cache folder in MiB, applied {}: the least recently used entries are removed "
                             "until the rest fit (default: ${}, else {})",
                             what, kCacheMaxEnv, kDefaultCacheMaxMiB))
      ->check(CLI::Range(std::uintmax_t{0}, UINTMAX_MAX >> 20));
}

std::optional<std::uintmax_t> cacheCapBytes(const std::optional<std::uintmax_t>& mib) {
  constexpr std::uintmax_t kBytesPerMiB = std::uintmax_t{1} << 20;
  return mib ? std::optional(*mib * kBytesPerMiB) : std::nullopt;
}

CLI::Validator techniqueFolderFilter() {
  return CLI::Validator(
      [](std::string& text) {
        try {
          text = resolveFilter(text);
        } catch (const Error& e) {
          return std::string(e.what());
        }
        return std::string();
      },
      "ID|FOLDER");
}

CLI::Validator finiteNumber(double lo, double hi, bool aboveLo) {
  const char* open = aboveLo ? "(" : "[";
  const std::string range = fmt::format("{}{}, {}]", open, lo, hi);
  return CLI::Validator(
      [=](std::string& text) {
        double v = 0.0;
        const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
        if (ec == std::errc() && end == text.data() + text.size() && std::isfinite(v) && (aboveLo ? v > lo : v >= lo) && v <= hi)
          return std::string();
        return fmt::format("{} is not a number in {}", text, range);
      },
      fmt::format("FLOAT in {}{} - {}]", open, lo, hi));  // CLI::Range's form in --help
}

std::string mapSizeLimitText() {
  return fmt::format("{}..{}: below {} a texel grows wider than the built-in scenes' casters and the default bias and "
                     "filters no longer keep acne and detached shadows away (docs/hard.md#map-sizes)",
                     kMinDefaultsMapSizeTexels, kMaxMapSizeTexels, kMinDefaultsMapSizeTexels);
}

CLI::Validator mapSizeOption() {
  return CLI::Validator(
      [](std::string& text) {
        int v = 0;
        const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
        if (ec == std::errc() && end == text.data() + text.size() && v >= kMinDefaultsMapSizeTexels && v <= kMaxMapSizeTexels)
          return std::string();
        return fmt::format("{} texels: a map side is {}", text, mapSizeLimitText());
      },
      fmt::format("INT in [{} - {}]", kMinDefaultsMapSizeTexels, kMaxMapSizeTexels));
}

CLI::Validator unsignedNumber() {
  return CLI::Validator(
      [](std::string& text) {
        uint64_t v = 0;
        const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
        if (ec == std::errc() && end == text.data() + text.size() && !text.empty()) return std::string();
        return fmt::format("{} is not a whole number in [0, {}]", text, UINT64_MAX);
      },
      fmt::format("UINT in [0 - {}]", UINT64_MAX));
}

std::pair<int, int> parseSize(const std::string& text) {
  const size_t x = text.find('x');
  int w = 0, h = 0;
  auto parse = [](std::string_view s, int& out) {
    const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), out);
    return ec == std::errc() && end == s.data() + s.size();
  };
  if (x == std::string::npos || !parse(std::string_view(text).substr(0, x), w) ||
      !parse(std::string_view(text).substr(x + 1), h) || w < 1 || h < 1 || w > 16384 || h > 16384)
    throw usageError(fmt::format("--size {}: expected WxH with each side in 1..16384, e.g. 640x360", text));
  return {w, h};
}

void checkOutput(const char* option, const std::string& path) {
  try {
    checkOutputFile(path);
  } catch (const Error& e) {
    throw Error(fmt::format("{}: {}", option, e.what()));
  }
}

void checkOutputDir(const char* option, const std::string& path) {
  try {
    checkOutputFolder(path);
  } catch (const Error& e) {
    throw Error(fmt::format("{}: {}", option, e.what()));
  }
}

std::unique_ptr<Renderer> makeRenderer(gl::Context& /*current: the renderer draws on it*/, Setup& s) {
  auto renderer = std::make_unique<Renderer>();
  renderer->setScene(std::move(s.scene));  // held once, by the renderer: renderer->scene()
  renderer->setTechnique(s.technique);
  renderer->shadows().setMapUpdates(s.mapUpdates);
  return renderer;
}

namespace {

// Model files from this size on take seconds to load (a 48 MiB OBJ of 2 M triangles: 1.4 s here,
// 12 s on a slower machine): they are announced, with a bar on a terminal and the time after.
constexpr uintmax_t kAnnounceLoadBytes = uintmax_t(16) << 20;
constexpr size_t kBarSteps = 1000;

/// LoadOptions::progress for the CLI: one line when a large model file starts and one when it is
/// loaded (stderr), a progress bar between them when stderr is a terminal.
class LoadAnnouncer {
public:
  void operator()(const std::filesystem::path& file, double fraction) {
    if (fraction == 0.0) {
      mBar.reset();
      std::error_code ec;
      const uintmax_t bytes = std::filesystem::file_size(file, ec);
      mAnnounced = !ec && bytes >= kAnnounceLoadBytes;
      if (!mAnnounced) return;
      std::fprintf(stderr, "penumbra: loading %s (%.1f MiB)\n", file.string().c_str(), static_cast<double>(bytes) / (1 << 20));
      mStart = std::chrono::steady_clock::now();
      mBar = std::make_unique<ProgressBar>("loading", kBarSteps, true);
      mSteps = 0;
      return;
    }
    if (!mAnnounced) return;
    const auto steps = static_cast<size_t>(fraction * kBarSteps);
    if (steps > mSteps) mBar->advance(steps - mSteps);
    mSteps = std::max(mSteps, steps);
    if (fraction < 1.0) return;
    mBar.reset();  // finishes its line
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - mStart).count();
    std::fprintf(stderr, "penumbra: loaded %s in %.1f s\n", file.string().c_str(), seconds);
    mAnnounced = false;
  }

private:
  bool mAnnounced = false;
  std::unique_ptr<ProgressBar> mBar;
  size_t mSteps = 0;
  std::chrono::steady_clock::time_point mStart;
};

/// Runs `f` for a choice the scene file made (shadow.filter, shadow.params.KEY): what the
/// registry refuses there is bad input in that file (exit 1, naming the file and the field), not
/// a bad command line.
std::string sceneFile(const Scene& scene) { return scene.sourceFile.empty() ? scene.name : scene.sourceFile.string(); }

template <class F>
auto sceneChoice(const Scene& scene, const std::string& field, F&& f) {
  try {
    return f();
  } catch (const Error& e) {
    throw Error(fmt::format("{}: {}: {}", sceneFile(scene), field, e.what()));
  }
}

/// Checks a scene file's technique setting (shadow.params.KEY, a light's too) against the
/// technique the key names, whether or not that technique runs now: a key or value that technique
/// refuses is bad input in the file, the same under every --filter. Returns whether the key is of
/// the technique in use (else it waits for it: bench and tune run several techniques over one
/// file; --verbose lists what is not applied).
bool checkTechniqueSetting(const Setup& s, const std::string& field, const std::pair<std::string, std::string>& kv, bool verbose) {
  const auto& [key, value] = kv;
  sceneChoice(s.scene, field, [&] {
    const std::string id = key.substr(0, key.find('.'));
    const std::vector<std::string> projections = projectionIds(), filters = filterIds();
    const bool projection = std::find(projections.begin(), projections.end(), id) != projections.end();
    if (!projection && std::find(filters.begin(), filters.end(), id) == filters.end())
      throw usageError(fmt::format("no technique '{}' (penumbra list shows them; a key is technique.name)", id));
    Technique owner;
    if (projection) owner.setProjection(id);
    else owner.setFilter(id);
    owner.set(key, std::string_view(value));
  });
  const ParamOwner owner = s.technique.owner(key);
  const bool inUse = owner == ParamOwner::Projection || owner == ParamOwner::Filter;
  if (!inUse && verbose)
    std::fprintf(stderr, "penumbra: %s: %s=%s not applied: not a parameter of --projection %s or --filter %s\n",
                 sceneFile(s.scene).c_str(), field.c_str(), value.c_str(), s.technique.projection().c_str(),
                 s.technique.filter().c_str());
  return inUse;
}

/// Refuses a --shadow-budget below what the scene's maps take at their smallest (each map's side
/// at core::kMinBudgetMapSize): it could not be kept, only exceeded. The maps are counted as the
/// projection makes them for each shadowed light (cascades, cube faces), its own params applied.
void checkShadowBudget(const Setup& s) {
  const int64_t budget = s.render.shadowBudgetTexels;
  if (budget <= 0) return;
  const SceneExtent extent = s.scene.extent();
  const float aspect = static_cast<float>(s.render.width) / static_cast<float>(s.render.height);
  int64_t maps = 0, lights = 0;
  for (const Light& l : s.scene.lights) {
    if (!l.castsShadow) continue;
    Technique t;
    try {
      t = s.technique.forLight(l.shadow, "");
    } catch (const Error&) {
      continue;  // refused by name later
    }
    if (!t.problemWith(l).empty()) continue;  // the same
    const std::unique_ptr<Projection> p = makeProjection(t);
    maps += static_cast<int64_t>(p->computeFrusta(s.scene.camera, aspect, l, extent, core::kMinBudgetMapSize).views.size());
    ++lights;
  }
  const int64_t least = maps * core::kMinBudgetMapSize * core::kMinBudgetMapSize;
  if (budget < least)
    throw usageError(fmt::format("--shadow-budget {}: the scene's {} shadowed light{} draw {} maps, {} texels at the smallest side ({}²); "
                                 "give at least {}, or 0 for no budget",
                                 budget, lights, lights == 1 ? "" : "s", maps, least, core::kMinBudgetMapSize, least));
}

// A scene file's own map sizes are the file's to choose (a small map is a fair experiment), but
// below kMinDefaultsMapSizeTexels the default bias and filters no longer promise no acne and no
// detached shadow: the command line says so once a run, naming the fields.
void noteSmallSceneMaps(const Scene& scene, bool sizeGiven) {
  std::vector<std::string> fields;
  if (!sizeGiven && scene.shadow.mapSize < kMinDefaultsMapSizeTexels)
    fields.push_back(fmt::format("shadow.mapSize {}", scene.shadow.mapSize));
  for (size_t i = 0; i < scene.lights.size(); ++i) {
    const int own = scene.lights[i].shadow.mapSize;
    if (own > 0 && own < kMinDefaultsMapSizeTexels) fields.push_back(fmt::format("lights[{}].shadow.mapSize {}", i, own));
  }
  if (fields.empty()) return;
  static std::set<std::string> said;
  const std::string line = fmt::format("{}: {} below {}²: the default bias and filters are held to no acne and no detached "
                                       "shadow from {}² up; below it the texel decides (docs/hard.md#map-sizes)",
                                       sceneFile(scene), fmt::join(fields, ", "), kMinDefaultsMapSizeTexels, kMinDefaultsMapSizeTexels);
  if (said.insert(line).second) std::fprintf(stderr, "penumbra: %s\n", line.c_str());
}

}  // namespace

Setup makeSetup(const TechniqueOptions& o) {
  Setup s;
  auto announcer = std::make_shared<LoadAnnouncer>();
  // The estimate counts the renderer's buffers in host memory (as llvmpipe keeps them; on a GPU
  // that is the larger guess) and, for a command that traces the reference, the BVH. A model
  // given alone gets a ground under it when it has no floor, and says so once a run (bench and
  // tune load a scene once per configuration).
  static std::set<std::string> said;
  s.scene = loadScene(o.scene, {.progress = [announcer](const std::filesystem::path& f, double x) { (*announcer)(f, x); },
                                .maxMemoryBytes = o.maxMemory.empty() ? 0 : parseMemorySize(o.maxMemory),
                                .glBuffersInHostMemory = true,
                                .referenceBvh = o.referenceBvh,
                                .groundUnderLoneModel = true,
                                .notice = [](const std::string& sentence) {
                                  if (said.insert(sentence).second) std::fprintf(stderr, "penumbra: %s\n", sentence.c_str());
                                }});
  if (o.projection) s.technique.setProjection(*o.projection);
  else sceneChoice(s.scene, "shadow.projection", [&] { s.technique.setProjection(s.scene.shadow.projection); });
  if (o.filter) s.technique.setFilter(*o.filter);
  else sceneChoice(s.scene, "shadow.filter", [&] { s.technique.setFilter(s.scene.shadow.filter); });
  const int mapSize = o.shadowMapSize.value_or(s.scene.shadow.mapSize);
  if (mapSize < kMinMapSizeTexels || mapSize > kMaxMapSizeTexels)
    throw usageError(fmt::format("--shadow-map {}: a map side is {}..{} texels (the maximum Penumbra takes; a driver may allow less)",
                                 mapSize, kMinMapSizeTexels, kMaxMapSizeTexels));
  s.technique.setMapSize(mapSize);
  // The scene's own params apply when they belong to the technique in use (a scene may carry
  // settings for several techniques), and are checked all the same; --set applies strictly.
  for (const auto& kv : s.scene.shadow.params) {
    const std::string field = "shadow.params." + kv.first;
    if (kv.first.starts_with("light."))
      sceneChoice(s.scene, field, [&] { applySettings({kv}, s.scene, s.technique); });
    else if (s.technique.owner(kv.first) == ParamOwner::AddOn || checkTechniqueSetting(s, field, kv, o.verbose))
      sceneChoice(s.scene, field, [&] { s.technique.set(kv.first, std::string_view(kv.second)); });
  }
  // A light's own params: Shadows applies those of the technique in use (penumbra/Scene.h).
  for (size_t i = 0; i < s.scene.lights.size(); ++i)
    for (const auto& kv : s.scene.lights[i].shadow.params)
      checkTechniqueSetting(s, fmt::format("lights[{}].shadow.params.{}", i, kv.first), kv, o.verbose);
  std::vector<std::pair<std::string, std::string>> cli;
  for (const std::string& a : o.sets) cli.push_back(splitAssignment(a));
  applySettings(cli, s.scene, s.technique);
  // Each light's own settings, as the core will merge them: bad input in the file, named there.
  for (size_t i = 0; i < s.scene.lights.size(); ++i)
    sceneChoice(s.scene, fmt::format("lights[{}].shadow", i), [&] { (void)s.technique.forLight(s.scene.lights[i].shadow, ""); });
  if (o.camera) {
    s.scene.camera = parseCameraArgument(*o.camera, s.scene.camera);
    s.scene.animation.camera = {};  // the camera given stays where it is
  }
  const auto [w, h] = parseSize(o.size);
  s.render.width = w;
  s.render.height = h;
  s.render.shadowBudgetTexels = o.shadowBudgetTexels;
  checkShadowBudget(s);
  s.mapUpdates = parseMapUpdates(o.mapUpdates);
  noteSmallSceneMaps(s.scene, o.shadowMapSize.has_value());  // once the file is known to be good
  return s;
}

std::vector<float> sequenceTimes(float timeS, std::optional<int> frames, float fps) {
  if (!frames) return timeS != 0.0f ? std::vector<float>{timeS} : std::vector<float>{};
  std::vector<float> times;
  for (int f = 0; f < *frames; ++f) times.push_back(timeS + static_cast<float>(f) / fps);
  return times;
}

void checkPoses(const Scene& scene, std::span<const float> timesS) {
  if (const std::string problem = poseProblem(scene, timesS); !problem.empty())
    throw Error(fmt::format("{}: {}", sceneFile(scene), problem));
}

report::SetupFactory benchSetupFactory(const std::optional<std::string>& camera) {
  return [camera](const report::BenchConfig& c) {
    TechniqueOptions t;
    t.camera = camera;
    t.referenceBvh = true;
    t.scene = c.scene;
    t.filter = c.filter;
    t.projection = c.projection;
    for (const auto& [k, v] : c.params) t.sets.push_back(k + "=" + v);
    Setup s = makeSetup(t);
    return report::BenchSetup{std::move(s.scene), std::move(s.technique)};
  };
}

std::string commandLine() {
  std::ifstream in("/proc/self/cmdline", std::ios::binary);
  std::string all((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>()), out;
  size_t start = 0;
  for (size_t i = 0; i <= all.size(); ++i) {
    if (i < all.size() && all[i] != '\0') continue;
    std::string arg = all.substr(start, i - start);
    if (start == 0) arg = std::filesystem::path(arg).filename().string();
    if (!arg.empty()) out += (out.empty() ? "" : " ") + (arg.find(' ') == std::string::npos ? arg : "'" + arg + "'");
    start = i + 1;
  }
  // The clock variable changes what every time means (process CPU time instead of the wall
  // clock): the run is repeated only with it.
  const char* clock = std::getenv("PENUMBRA_CLOCK");
  if (clock && *clock && std::string_view(clock).find_first_of(" '\"$`\\") == std::string_view::npos)
    out = fmt::format("PENUMBRA_CLOCK={} {}", clock, out);
  return out;
}

}  // namespace penumbra::app
