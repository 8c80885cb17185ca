#include "bench/BenchPlan.h"

#include <penumbra/Error.h>
#include <penumbra/MapSizes.h>
#include "techniques/Registry.h"
#include <penumbra/SceneIO.h>

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <map>
#include <optional>
#include <tuple>

namespace penumbra::report {
namespace {

float parseFloat(std::string_view text, std::string_view whole) {
  float v = 0.0f;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (text.empty() || ec != std::errc() || end != text.data() + text.size() || !std::isfinite(v))
    throw usageError(fmt::format("--sweep {}: '{}' is not a number (expected key=from:to:count or key=a,b,...)", whole, text));
  return v;
}

// The ParamDesc of `key` for the scene or this technique, or nullopt when neither declares it.
std::optional<ParamDesc> findDesc(std::string_view key, const Technique& technique) {
  for (const ParamDesc& d : sceneParamDescs())
    if (d.key == key) return d;
  if (technique.has(key)) return technique.desc(key);
  return std::nullopt;
}

bool isLightKey(std::string_view key) { return key.starts_with("light."); }

}  // namespace

std::vector<float> Sweep::values(const ParamDesc& desc) const {
  std::vector<float> out;
  if (!names.empty()) {
    for (const std::string& name : names) {
      const float v = parseParamValue(desc, name);
      if (std::find(out.begin(), out.end(), v) == out.end()) out.push_back(v);
    }
    return out;
  }
  const int n = list.empty() ? count : static_cast<int>(list.size());
  for (int i = 0; i < n; ++i) {
    const float t = count == 1 ? 0.0f : static_cast<float>(i) / static_cast<float>(count - 1);
    float v = list.empty() ? from + (to - from) * t : list[static_cast<size_t>(i)];
    if (desc.isInteger()) v = std::round(v);
    if (std::find(out.begin(), out.end(), v) == out.end()) out.push_back(v);
  }
  return out;
}

Sweep parseSweep(std::string_view text) {
  const size_t eq = text.find('=');
  if (eq == std::string_view::npos || eq == 0)
    throw usageError(fmt::format("--sweep {}: expected key=from:to:count or key=a,b,..., e.g. light.size=0.02:0.2:5 or light.count=1,2,4,8", text));
  Sweep s;
  s.key = std::string(text.substr(0, eq));
  const std::string_view range = text.substr(eq + 1);
  if (range.find(':') == std::string_view::npos) {  // a list
    std::vector<std::string_view> tokens;
    for (size_t start = 0; start <= range.size();) {
      const size_t comma = std::min(range.find(',', start), range.size());
      tokens.push_back(range.substr(start, comma - start));
      start = comma + 1;
    }
    if (tokens.size() > static_cast<size_t>(kMaxSweepCount))
      throw usageError(fmt::format("--sweep {}: {} values, more than {}", text, tokens.size(), kMaxSweepCount));
    // Names where every value starts with a letter (a choice's), else numbers.
    const bool named = std::all_of(tokens.begin(), tokens.end(), [](std::string_view t) {
      return !t.empty() && ((t.front() >= 'a' && t.front() <= 'z') || (t.front() >= 'A' && t.front() <= 'Z'));
    });
    for (const std::string_view t : tokens) {
      if (named) s.names.emplace_back(t);
      else s.list.push_back(parseFloat(t, text));
    }
    return s;
  }
  const size_t c1 = range.find(':'), c2 = c1 == std::string_view::npos ? c1 : range.find(':', c1 + 1);
  if (c1 == std::string_view::npos || c2 == std::string_view::npos || range.find(':', c2 + 1) != std::string_view::npos)
    throw usageError(fmt::format("--sweep {}: expected key=from:to:count or key=a,b,..., e.g. light.size=0.02:0.2:5 or light.count=1,2,4,8", text));
  s.from = parseFloat(range.substr(0, c1), text);
  s.to = parseFloat(range.substr(c1 + 1, c2 - c1 - 1), text);
  const std::string_view countText = range.substr(c2 + 1);
  const auto [end, ec] = std::from_chars(countText.data(), countText.data() + countText.size(), s.count);
  if (countText.empty() || ec != std::errc() || end != countText.data() + countText.size() || s.count < 1 ||
      s.count > kMaxSweepCount)
    throw usageError(fmt::format("--sweep {}: count must be a whole number in 1..{}", text, kMaxSweepCount));
  return s;
}

std::string BenchConfig::paramsText() const {
  std::string out;
  for (const auto& [k, v] : params) {
    if (!out.empty()) out += ';';
    out += k + "=" + v;
  }
  return out;
}

std::vector<BenchPlan> translucentPlans(const BenchPlan& run) {
  std::vector<std::string> scenes;
  for (const std::string& name : run.scenes) {
    const Scene scene = loadScene(name);
    if (std::any_of(scene.materials.begin(), scene.materials.end(), [](const Material& m) { return m.translucent(); }))
      scenes.push_back(name);
  }
  const auto has = [](const std::vector<std::string>& list, std::string_view id) {
    return std::find(list.begin(), list.end(), id) != list.end();
  };
  std::vector<std::string> filters;
  for (const char* id : kTranslucentPlanFilters)
    if (has(run.filters, id)) filters.emplace_back(id);
  if (scenes.empty() || filters.empty()) return {};
  const std::vector<std::string> projections = has(run.projections, "uniform") ? std::vector<std::string>{"uniform"} : run.projections;
  const auto on = [](const char* key) { return Sweep{key, 0.0f, 0.0f, 1, {1.0f}, {}}; };  // on / the second choice
  const std::string name(kTranslucentPlan);
  std::vector<BenchPlan> plans;
  plans.push_back({.name = name, .scenes = scenes, .projections = projections, .filters = filters, .sweeps = {on("translucent.shadows")}});
  if (has(filters, "msm"))
    plans.push_back({.name = name, .scenes = scenes, .projections = projections, .filters = {"msm"}, .sweeps = {on("msm.translucent")}});
  if (has(filters, "pcf"))  // translucent.method's second choice: stochastic
    plans.push_back({.name = name, .scenes = scenes, .projections = projections, .filters = {"pcf"},
                     .sweeps = {on("translucent.shadows"), on("translucent.method"), on("temporal.accumulate")}});
  return plans;
}

std::vector<BenchConfig> expandPlans(const std::vector<BenchPlan>& plans) {
  std::vector<BenchConfig> out;
  std::vector<std::string> sceneOrder;
  std::map<std::string, std::string> sceneProjection;  // the scene's own projection (grid rows)
  for (const BenchPlan& plan : plans) {
    for (const std::string& scene : plan.scenes) {
      if (!sceneProjection.contains(scene)) {
        sceneProjection[scene] = loadScene(scene).shadow.projection;  // usage error if unknown
        sceneOrder.push_back(scene);
      }
    }
    std::vector<bool> sweepUsed(plan.sweeps.size(), false);
    for (const std::string& scene : plan.scenes)
      for (const std::string& projectionId : plan.projections)
        for (const std::string& filterId : plan.filters) {
          const Technique technique(projectionId, filterId);
          // Cross product of the values of the sweeps that apply to this technique.
          std::vector<std::vector<std::pair<std::string, std::string>>> combos = {{}};
          for (size_t i = 0; i < plan.sweeps.size(); ++i) {
            const Sweep& sweep = plan.sweeps[i];
            const std::optional<ParamDesc> desc = findDesc(sweep.key, technique);
            if (!desc) continue;
            sweepUsed[i] = true;
            std::vector<std::vector<std::pair<std::string, std::string>>> next;
            std::vector<float> values;
            try {
              values = sweep.values(*desc);
              for (const float v : values) checkParamValue(*desc, v);
            } catch (const Error& e) {  // named by the option it came from
              throw usageError(fmt::format("--sweep {}: {}", sweep.key, e.what()));
            }
            for (const float v : values) {
              for (auto combo : combos) {
                combo.emplace_back(sweep.key, formatParamValue(*desc, v));
                next.push_back(std::move(combo));
              }
            }
            combos = std::move(next);
          }
          for (auto& combo : combos) {
            BenchConfig c;
            c.plan = plan.name;
            c.scene = scene;
            c.projection = projectionId;
            c.filter = filterId;
            c.params = std::move(combo);
            out.push_back(std::move(c));
          }
        }
    for (size_t i = 0; i < plan.sweeps.size(); ++i)
      if (!sweepUsed[i] && !plan.scenes.empty() && !isLightKey(plan.sweeps[i].key))
        throw usageError(fmt::format("--sweep {}: no projection ({}) or filter ({}) of this run has that parameter",
                                     plan.sweeps[i].key, joinNames(plan.projections), joinNames(plan.filters)));
      else if (!sweepUsed[i] && !plan.scenes.empty())
        throw usageError(fmt::format("--sweep {}: unknown scene parameter (known: light.size)", plan.sweeps[i].key));
  }
  // The image grid: one row per scene and filter, the first configuration (in plan order) that
  // best shows the technique as the scene means it: its own projection and no swept value.
  auto rank = [&](const BenchConfig& c) {
    return (c.projection == sceneProjection[c.scene] ? 0 : 2) + (c.params.empty() ? 0 : 1);
  };
  // The translucent plan's techniques each get a row of their own beside the filter's (its
  // casters drawn opaque): what a coloured shadow looks like is what they are measured for.
  std::map<std::tuple<std::string, std::string, std::string>, size_t> best;
  for (size_t i = 0; i < out.size(); ++i) {
    const auto key = std::tuple(out[i].scene, out[i].filter, out[i].plan == kTranslucentPlan ? out[i].paramsText() : "");
    const auto it = best.find(key);
    if (it == best.end() || rank(out[i]) < rank(out[it->second])) best[key] = i;
  }
  for (const auto& [key, i] : best) out[i].inGrid = true;
  // One scene upload per scene: group by scene, keeping plan order inside (the runner keeps the
  // scene's references for every light in memory). A technique's sweep values stay adjacent, so
  // the points of one curve are timed close together: slow drifts in the machine's load bend a
  // curve less than they would if each light size were run as a separate block.
  auto sceneIndex = [&](const std::string& s) { return std::find(sceneOrder.begin(), sceneOrder.end(), s) - sceneOrder.begin(); };
  std::stable_sort(out.begin(), out.end(),
                   [&](const BenchConfig& a, const BenchConfig& b) { return sceneIndex(a.scene) < sceneIndex(b.scene); });
  return out;
}

std::vector<BenchPlan> defaultPlans(bool quick, BenchSettings& settings) {
  // Light-size sweep on `pen` (a spherical spot light, its radius in metres): from nearly hard
  // to 1.7× the scene's own 0.12 m, where PCSS's search region grows tenfold.
  constexpr float kPenLightMinM = 0.02f, kPenLightMaxM = 0.2f;
  // Every scene but `night`, whose eight lamps the light-count plan measures one subset at a time.
  std::vector<std::string> matrixScenes = builtinSceneNames();
  std::erase(matrixScenes, std::string(kLightCountScene));
  BenchPlan matrix{.name = "matrix", .scenes = matrixScenes, .projections = projectionIds(), .filters = filterIds(), .sweeps = {}};
  BenchPlan light{.name = "light-size", .scenes = {"pen"}, .projections = {"uniform"}, .filters = filterIds(),
                  .sweeps = {Sweep{"light.size", kPenLightMinM, kPenLightMaxM, quick ? 3 : 5, {}, {}}}};
  // Contact shadows off and on, with the filters they are most often paired with, on the
  // scenes where casters stand on receivers.
  BenchPlan contact{.name = "contact", .scenes = {"boxes", "pen", "grazing"}, .projections = {"uniform"},
                    .filters = {"hard", "pcf", "pcss", "vsm"}, .sweeps = {Sweep{"contact.shadows", 0.0f, 1.0f, 2, {}, {}}}};
  if (quick) {
    // Seconds, not minutes: small images and maps, few frames, a noisier reference, the scenes
    // of the recommendation's situations (Recommendation.h) and two projections (enough for
    // every chart, table, recommendation and the grid).
    matrix.scenes = {"boxes", "pen", "fence", "city", "glass"};
    matrix.projections = {"uniform", "csm"};
    settings.width = 96;
    settings.height = 64;
    settings.shadowMapSize = kMinDefaultsMapSizeTexels;
    settings.warmupFrames = 1;
    settings.timedFrames = 3;
    settings.maxSecondsPerConfig = 0.5;
    settings.referenceSamples = 36;
    settings.microRepetitions = 3;
    settings.motionFrames = 3;
    settings.retimeRounds = 3;
    settings.quick = true;
  }
  // Cost, memory and error against the number of shadowed lights: night's first 1, 2, 4 and 8
  // lamps (its points and spots alternate so that each subset mixes both).
  BenchPlan lights{.name = std::string(kLightCountPlan), .scenes = {std::string(kLightCountScene)}, .projections = {"uniform"},
                   .filters = {"hard", "pcf", "pcss", "vsm", "msm"}, .sweeps = {Sweep{"light.count", 0, 0, 0, {1, 2, 4, 8}, {}}}};
  if (quick) {
    contact.scenes = {"boxes"};
    lights.filters = {"pcf"};
  }
  std::vector<BenchPlan> plans = {matrix, light, contact, lights};
  for (BenchPlan& p : translucentPlans(matrix)) plans.push_back(std::move(p));
  return plans;
}

}  // namespace penumbra::report
