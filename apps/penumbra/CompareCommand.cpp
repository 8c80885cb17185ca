// penumbra compare: a technique against the ray-traced reference on the same pixels — metrics,
// per-pass times, and images (technique, reference, error heatmap, split-approximation error),
// and the two V's as float images, so that anyone can check the ruler with another renderer.
#include "Commands.h"
#include "Common.h"

#include "platform/Context.h"
#include "comparison/Shimmer.h"
#include "comparison/TexelDensity.h"
#include "bench/BenchRunner.h"
#include "comparison/FrameComparison.h"
#include "comparison/ImageKey.h"
#include "text/ImageText.h"
#include "comparison/Sheet.h"
#include "comparison/SequenceComparison.h"

#include <penumbra/Animation.h>
#include <penumbra/Error.h>
#include <penumbra/Exr.h>
#include <penumbra/ImageIO.h>
#include <penumbra/Metrics.h>
#include <penumbra/Reference.h>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>

namespace penumbra::app {
namespace {

// Pass times are warm: one untimed frame (it compiles the shaders), then the median and p10–p90
// of this many frames, as the bench times its rows (with fewer frames: compare is interactive).
constexpr int kCompareWarmupFrames = 1;
constexpr int kCompareTimedFrames = 5;

/// Every file compare writes into --out, in the order --help names them.
constexpr std::pair<const char*, const char*> kOutputs[] = {
    {"technique.png", "the frame lit with the technique's V"},
    {"reference.png", "the same frame lit with V_ref"},
    {"heatmap.png", "V - V_ref over the dimmed frame: leaks red, over-darkening blue, its scale fitted to the frame's errors and written under it with its key"},
    {"approximation.png", "where the shadow-map model itself (V averaged outside the lighting integral) is wrong, with its key"},
    {"sheet.png", "technique, reference, heatmap and a 4x zoom of its worst region, titled, with the colour legend and the metrics"},
    {"texel-density.png", "screen pixels per shadow-map texel, log colour scale, with its key"},
    {"visibility.exr", "the technique's V"},
    {"reference-visibility.exr", "V_ref: the unoccluded fraction of the light"},
    {"reference-visibility-cos.exr", "V_ref weighted by cos(theta): exact over unshadowed shading"},
    {"heatmap-colour.png, where the scene has translucent casters",
     "the colour of V - V_ref per channel (128 grey = exact), titled, with the colour RMSE"},
    {"visibility-lightN.exr, reference-visibility-lightN.exr, reference-visibility-cos-lightN.exr",
     "with several lights: each light's own V, V_ref and cos-weighted V_ref"},
};

std::string outputsHelp() {
  std::string help = "folder for the outputs:";
  for (const auto& [name, what] : kOutputs) help += fmt::format("\n  {} ({})", name, what);
  return help + "\nEXR files: one float channel V, row 0 = top; V_ref is 0 on geometry that no part of the light reaches "
                "above its horizon (or that lies outside a spot's cone) and 1 on background; the metrics count the pixels that face the "
                "light's centre; with several lights visibility.exr and reference-visibility*.exr "
                "hold the lights' V combined, each weighted by its unshadowed light at the pixel";
}

// The colour metrics' JSON keys (a scene with translucent casters), the same at the top and per light.
void putColourMetrics(nlohmann::json& j, const ColourMetrics& m) {
  j["rmse_rgb"] = m.rmse;
  j["rmse_r"] = m.channelRmse[0];
  j["rmse_g"] = m.channelRmse[1];
  j["rmse_b"] = m.channelRmse[2];
}

/// The colour error image under a title band: what it shows, its scale and the colour metrics.
ColorImage colourErrorSheet(const ColorImage& error, const ColourMetrics& m, const std::string& title) {
  const text::TextPainter text(14.0f);
  const std::string lines[] = {
      title,
      "V - V_ref per colour channel: mid grey = exact; a channel brighter = too much of that colour,",
      "darker = too little (a black shadow under red glass reads cyan), full at ±0.5; dark grey: not measured",
      fmt::format("RMSE over RGB {:.4f} · red {:.4f} · green {:.4f} · blue {:.4f} over {} lit pixels", m.rmse, m.channelRmse[0],
                  m.channelRmse[1], m.channelRmse[2], m.pixels)};
  constexpr int kLines = static_cast<int>(std::size(lines)), kMargin = 4;
  const int line = text.ascent() + text.descent() + 4, band = kLines * line + 2 * kMargin;
  int width = error.width;
  for (const std::string& l : lines) width = std::max(width, text.width(l) + 2 * kMargin);
  ColorImage sheet{width, error.height + band, {}};
  sheet.rgba.assign(4 * static_cast<size_t>(sheet.width) * static_cast<size_t>(sheet.height), 255);
  for (int i = 0; i < kLines; ++i) text.draw(sheet, kMargin, kMargin + i * line + text.ascent(), lines[i], {0, 0, 0});
  for (int y = 0; y < error.height; ++y)
    std::copy_n(error.rgba.begin() + 4 * static_cast<std::ptrdiff_t>(y) * error.width, 4 * error.width,
                sheet.rgba.begin() + 4 * (static_cast<std::ptrdiff_t>(y + band) * sheet.width));
  return sheet;
}

// The metrics' JSON keys, the same for the combined result and for each light.
void putMetrics(nlohmann::json& j, const VisibilityMetrics& m) {
  j["rmse"] = m.rmse;
  j["mae"] = m.mae;
  j["leak_pct"] = m.leakPct;
  j["overdark_pct"] = m.overDarkPct;
  j["umbra_leak_pct"] = m.umbraLeakPct;
  j["acne_pct"] = m.acnePct;
  j["penumbra_rmse"] = m.penumbraRmse;
  j["pixels"] = m.pixels;
}

}  // namespace

void addCompareCommand(CLI::App& app, std::vector<Command>& commands) {
  struct Options {
    TechniqueOptions technique;
    int samples = ReferenceOptions{}.samples;  // as bench and the viewer's heatmap
    std::string out = "compare";
    bool json = false, noCache = false, walk = false;
    int shimmer = 0;
    std::optional<std::uintmax_t> cacheMaxMb;
    std::optional<int> frames;
    float fps = 30.0f, timeS = 0.0f;
  };
  auto o = std::make_shared<Options>();
  o->technique.referenceBvh = true;
  CLI::App* sub = app.add_subcommand("compare", "render a technique and the ray-traced reference; print the error metrics and pass times");
  addTechniqueOptions(*sub, o->technique);
  addShadowBudgetOption(*sub, o->technique);
  addMapUpdatesOption(*sub, o->technique);
  sub->add_option("--samples", o->samples, "reference light samples per pixel (soft lights)")
      ->capture_default_str()->check(CLI::Range(1, kMaxReferenceSamples));
  sub->add_option("--out", o->out, outputsHelp())->capture_default_str();
  sub->add_flag("--json", o->json, "print one JSON object on stdout instead of the table");
  sub->add_flag("--no-cache", o->noCache, "recompute the reference even if a cached one exists");
  addCacheCapOption(*sub, o->cacheMaxMb, "after the reference is stored");
  sub->add_option("--shimmer", o->shimmer,
                  "also move the camera by small steps over N frames and report shimmer_pct (world points near shadow edges whose V changes by > 0.1 between frames)")
      ->check(CLI::Range(1, 1000));
  CLI::Option* frames = sub->add_option("--frames", o->frames,
                  "also render the animated scene's frames at --time, --time + 1/--fps, ... and compare each with its reference: "
                  "rmse_mean, rmse_worst_frame, flicker_pct (followed surface points whose V changes by > 0.1 between consecutive "
                  "frames while V_ref changes by < 0.02), lag_rmse and ghost_pct (the error, and the share off by > 0.1, on pixels "
                  "whose V_ref changed by > 0.1 within the last 4 frames); the images and the other metrics are of the first frame")
      ->check(CLI::Range(1, 100000));
  sub->add_flag("--walk", o->walk,
                "with --frames: the scene holds still (at --time) and the camera walks around its target (12 degrees a "
                "second, at its distance and height): the motion penumbra bench scores a still scene over");
  addTimeOptions(*sub, frames, o->fps, o->timeS, "the scene's time in seconds of the (first) frame");
  commands.push_back({sub, [o] {
    if (o->walk && !o->frames) throw usageError("--walk moves the camera over --frames: give --frames N too");
    checkOutputDir("--out", o->out);
    Setup s = makeSetup(o->technique);
    checkPoses(s.scene, sequenceTimes(o->timeS, o->frames, o->fps));
    if (o->frames || o->timeS != 0.0f) poseScene(s.scene, o->timeS);  // unposed: the still scene exactly
    gl::HeadlessContext context({.debug = gl::kDebugBuild, .verbose = o->technique.verbose});
    checkImageFits(context, s.render.width, s.render.height, kCompareHostBytesPerPixel);
    const std::unique_ptr<Renderer> rendererPtr = makeRenderer(context, s);
    Renderer& renderer = *rendererPtr;
    const Scene& scene = renderer.scene();  // the setup's, held once
    // Warm times: the first frame includes shader compilation; the last timed frame is compared.
    const report::WarmTimes times = report::timeWarmFrames(renderer, s.render, kCompareWarmupFrames, kCompareTimedFrames);
    const GBufferData gbuffer = renderer.readGBuffer();
    // Aliasing: screen pixels covered by one shadow-map texel, per pixel.
    const std::vector<float> density = computeTexelDensity(renderer);
    const TexelDensityStats densityStats = texelDensityStats(density, gbuffer, scene.camera.position);

    ReferenceOptions ro;
    ro.samples = o->samples;
    ro.useCache = !o->noCache;
    ro.cacheMaxBytes = cacheCapBytes(o->cacheMaxMb);
    ro.progress = !o->json;
    const ReferenceTracer tracer(scene, MeshStorage::Borrowed);  // the renderer keeps the scene alive
    const std::vector<ReferenceResult> refs = report::traceLights(tracer, gbuffer, scene.lights, ro);
    const report::FrameComparison cmp = report::compareFrame(renderer, gbuffer, refs, true);
    const VisibilityMetrics& m = cmp.metrics;
    const CombinedVisibility& combined = cmp.combined;
    const double approximationRmse = compareVisibility(combined.vRef, combined.vRefCosWeighted, combined.mask).rmse;
    const int width = gbuffer.width, height = gbuffer.height;

    const std::filesystem::path dir(o->out);
    const ColorImage &technique = cmp.technique, &reference = cmp.reference;
    // The heatmap's scale adapts to this frame's errors (and is written on it), so that a soft
    // shadow off by a hundredth shows in colour; each error over a 3 × 3 spot, as kLabHeatmap.
    const float heatScale = report::adaptiveHeatmapScale(combined.v, combined.vRef, combined.mask);
    const ColorImage heat = errorHeatmap(combined.v, combined.vRef, combined.mask, width, height, &technique,
                                         {.fullScaleDeltaV = heatScale, .dilatePx = report::kLabHeatmap.dilatePx});
    const int spot = 2 * report::kLabHeatmap.dilatePx + 1;
    const std::string heatGrey = fmt::format(
        "grey: the technique's frame, dimmed, where V is right · scale fitted to this frame: {:.0f} % of its visible "
        "errors (|ΔV| > 1/255) are within ±{:g} · each error drawn over a {}×{} spot",
        100.0 * report::kHeatmapScalePercentile, heatScale, spot, spot);
    const ColorImage heatKeyed = report::withKey(
        heat, report::heatmapKey(heatScale, fmt::format("error of {} · {}: ΔV = V − V_ref, blue too dark, red too bright",
                                                        renderer.technique().filter(), renderer.technique().projection()),
                                 heatGrey));
    // The split model's own error in units of V, on the reference's grey, full colour at
    // kApproximationFullScaleV (docs/reference.md).
    constexpr float kApproximationFullScaleV = 0.1f;
    const ColorImage approx = report::withKey(
        errorHeatmap(combined.vRef, combined.vRefCosWeighted, combined.mask, width, height, nullptr,
                     HeatmapOptions{kApproximationFullScaleV}),
        report::heatmapKey(kApproximationFullScaleV,
                           "where the shadow-map model itself is wrong · V_ref − V_ref weighted by cos θ: V averaged "
                           "outside the lighting integral, as every shadow map does",
                           "grey: V_ref (light lit, dark shadowed), where the model is exact · red: the model is too "
                           "bright there, blue: too dark · a fixed scale · the same for every technique"));
    double referenceSeconds = 0.0;
    int referenceSamples = 0;
    bool referenceCached = true;
    size_t horizonPixels = 0;  // lit by part of a soft light whose centre is below their horizon: not in the metrics
    for (const ReferenceResult& r : refs) {
      horizonPixels += r.horizonPixels;
      referenceSeconds += r.traceSeconds;
      referenceSamples = std::max(referenceSamples, r.samplesPerPixel);
      referenceCached = referenceCached && (r.fromCache || r.width == 0);
    }
    const std::string lightText = scene.lights.size() > 1 ? fmt::format("{} lights", scene.lights.size())
                                                            : fmt::format("light size {:g}", scene.light().size);
    const ColorImage all = report::compareSheet(
        {.technique = &technique, .reference = &reference, .heatmap = &heat, .v = combined.v, .vRef = combined.vRef,
         .mask = combined.mask, .heatmapFullScaleDeltaV = heatScale, .heatmapScaleNote = heatGrey,
         .techniqueTitle = fmt::format("{} · {} on {}", renderer.technique().filter(), renderer.technique().projection(), scene.name),
         .referenceTitle = fmt::format("reference: Embree, {} light samples per pixel", referenceSamples),
         .metrics = {fmt::format("RMSE {:.4f} · mean |ΔV| {:.4f} · penumbra RMSE {:.4f} · leak {:.2f}% (in the umbra "
                                 "{:.2f}%) · over-dark {:.2f}% over {} lit pixels",
                                 m.rmse, m.mae, m.penumbraRmse, m.leakPct, m.umbraLeakPct, m.overDarkPct, m.pixels),
                     fmt::format("{}×{} pixels, shadow map {}², {} · --camera {}", width, height,
                                 s.technique.mapSize(), lightText, cameraArgument(scene.camera))}});
    const ColorImage densityImage = report::withKey(texelDensityHeatmap(density, gbuffer.width, gbuffer.height),
                                                    report::texelDensityKey());
    for (const auto& [name, img] : {std::pair{"technique.png", &technique}, {"reference.png", &reference},
                                    {"heatmap.png", &heatKeyed}, {"approximation.png", &approx}, {"sheet.png", &all},
                                    {"texel-density.png", &densityImage}})
      writePng(dir / name, img->width, img->height, img->rgba);
    const auto exr = [&](const std::string& name, const std::vector<float>& v) {
      writeExr(dir / name, width, height, flipRows<float>(v, width, height));
    };
    exr("visibility.exr", combined.v);
    exr("reference-visibility.exr", combined.vRef);
    exr("reference-visibility-cos.exr", combined.vRefCosWeighted);
    if (refs.size() > 1)
      for (const report::LightComparison& l : cmp.lights) {
        exr(fmt::format("visibility-light{}.exr", l.index), l.visibility);
        if (!l.castsShadow) continue;
        exr(fmt::format("reference-visibility-light{}.exr", l.index), refs[l.index].visibility);
        exr(fmt::format("reference-visibility-cos-light{}.exr", l.index), refs[l.index].visibilityCosWeighted);
      }

    // A scene with translucent casters: each light's colour metrics (compareFrame), and the
    // first such light's colour error image.
    const auto coloured = std::find_if(cmp.lights.begin(), cmp.lights.end(), [](const report::LightComparison& l) { return l.colour.has_value(); });
    if (coloured != cmp.lights.end()) {
      const report::LightComparison& l = *coloured;
      const ColorImage error = colourErrorImage(report::colourVisibility(l), refs[l.index].visibilityRgb, refs[l.index].litMask, width, height);
      const ColorImage sheet = colourErrorSheet(
          error, *l.colour,
          fmt::format("{} · {} on {}, light {}: colour error against the RGB reference", renderer.technique().filter(),
                      renderer.technique().projection(), scene.name, l.index));
      writePng(dir / "heatmap-colour.png", sheet.width, sheet.height, sheet.rgba);
    }
    const std::optional<ColourMetrics>& topColour = cmp.colour;
    std::optional<ShimmerResult> shimmer;
    if (o->shimmer > 0) {
      ShimmerOptions so;
      so.steps = o->shimmer;
      shimmer = measureShimmer(renderer, s.render, so);
    }
    std::optional<report::SequenceComparison> sequence;
    if (o->frames) {
      ReferenceOptions sro = ro;
      sro.progress = false;
      const report::SequenceTiming timing{*o->frames, o->fps, o->timeS};
      Scene moving = scene;
      if (o->walk) report::addCameraWalk(moving, timing);
      sequence = report::compareSequence(renderer, moving, s.render, timing, sro, {}, [&](int f) {
        if (!o->json) std::fprintf(stderr, "penumbra: frame %d/%d (t = %.3f s) compared\n", f + 1, timing.frames, timing.timeS(f));
      });
    }
    const std::string projection = renderer.technique().projection(), filter = renderer.technique().filter();
    // A paged projection whose pool could not hold a frame's pages says so (coarser levels served them).
    {
      int missing = 0, pool = 0;
      const auto count = [&](const std::vector<LightShadowReport>& reports) {
        for (const LightShadowReport& r : reports) {
          missing = std::max(missing, r.pages.missing);
          pool = std::max(pool, r.pages.poolPages);
        }
      };
      count(renderer.shadows().lightReports());
      if (sequence)
        for (const report::SequenceFrame& f : sequence->frames) count(f.lights);
      if (missing > 0)
        std::fprintf(stderr, "penumbra: the page pool (%d pages) was full: up to %d needed pages a frame were read from coarser levels "
                     "(virtual.poolPages raises it)\n", pool, missing);
    }
    if (o->json) {
      nlohmann::json j;
      j["scene"] = scene.name;
      j["filter"] = filter;
      j["projection"] = projection;
      j["camera"] = cameraArgument(scene.camera);  // what --camera takes: the run repeats from it
      j["width"] = gbuffer.width;
      j["height"] = gbuffer.height;
      j["shadow_map"] = s.technique.mapSize();
      j["light_size"] = scene.light().size;
      putMetrics(j, m);
      if (topColour) putColourMetrics(j, *topColour);
      j["approximation_rmse"] = approximationRmse;
      j["texel_density_median"] = densityStats.median;
      j["texel_density_p95"] = densityStats.p95;
      j["texel_density_near_median"] = densityStats.nearMedian;
      j["undersampled_pct"] = densityStats.undersampledPct;
      if (shimmer) {
        j["shimmer_pct"] = shimmer->shimmerPct;
        j["shimmer_edge_points"] = shimmer->edgePoints;
        j["shimmer_steps"] = shimmer->steps;
      }
      if (sequence) {
        j["frames"] = sequence->frames.size();
        j["fps"] = o->fps;
        j["time"] = o->timeS;
        j["rmse_mean"] = sequence->rmseMean;
        j["penumbra_rmse_mean"] = sequence->penumbraRmseMean;
        j["walk"] = o->walk;
        j["rmse_worst_frame"] = sequence->rmseWorstFrame;
        j["rmse_worst"] = sequence->rmseWorst;
        j["flicker_pct"] = sequence->flicker.pct();
        j["flicker_followed"] = sequence->flicker.followed;
        j["lag_rmse"] = sequence->lag.rmse();
        j["ghost_pct"] = sequence->lag.ghostPct();
        j["ghost_dark_pct"] = sequence->lag.darkPct();
        j["lag_pixels"] = sequence->lag.pixels;
        j["frame_rmse"] = nlohmann::json::array();
        for (const report::SequenceFrame& f : sequence->frames) j["frame_rmse"].push_back(f.metrics.rmse);
        j["sequence_reference_seconds"] = sequence->referenceSeconds;
      }
      j["map_updates"] = mapUpdatesName(renderer.shadows().mapUpdates());
      if (mapsCached(renderer.shadows())) {  // over every frame rendered, the two still ones first
        const Shadows::MapCacheStats c = renderer.shadows().mapCacheStats();
        j["maps_restored"] = c.restored;
        j["maps_drawn"] = c.rendered;
        j["maps_kept"] = c.kept;
        j["staleness_max"] = c.maxStaleness;
        j["staleness_mean"] = c.meanStaleness;
      }
      // A paged projection (virtual): its pages in the last frame, summed over the lights, and
      // with --frames one entry a frame.
      bool paged = false;
      LightShadowReport::Pages pages;
      for (const report::LightComparison& l : cmp.lights) {
        const LightShadowReport::Pages& p = l.map.pages;
        paged = paged || p.poolPages > 0;
        pages.needed += p.needed;
        pages.drawn += p.drawn;
        pages.resident += p.resident;
        pages.missing += p.missing;
        pages.poolPages += p.poolPages;
        pages.poolBytes += p.poolBytes;
      }
      if (paged) {
        j["pages_needed"] = pages.needed;
        j["pages_drawn"] = pages.drawn;
        j["pages_resident"] = pages.resident;
        j["pages_missing"] = pages.missing;
        j["pool_pages"] = pages.poolPages;
        j["pool_mb"] = static_cast<double>(pages.poolBytes) / (1024.0 * 1024.0);
        if (sequence) {
          for (const char* key : {"pages_needed", "pages_drawn", "pages_resident", "pages_missing"}) j[key] = nlohmann::json::array();
          for (const report::SequenceFrame& f : sequence->frames) {
            LightShadowReport::Pages sum;
            for (const LightShadowReport& r : f.lights) {
              sum.needed += r.pages.needed;
              sum.drawn += r.pages.drawn;
              sum.resident += r.pages.resident;
              sum.missing += r.pages.missing;
            }
            j["pages_needed"].push_back(sum.needed);
            j["pages_drawn"].push_back(sum.drawn);
            j["pages_resident"].push_back(sum.resident);
            j["pages_missing"].push_back(sum.missing);
          }
        }
      }
      j["lights"] = nlohmann::json::array();
      for (const report::LightComparison& l : cmp.lights) {
        nlohmann::json jl;
        jl["index"] = l.index;
        jl["type"] = lightTypeName(l.type);
        jl["casts_shadow"] = l.castsShadow;
        if (l.castsShadow) putMetrics(jl, l.metrics);
        if (l.colour) putColourMetrics(jl, *l.colour);
        jl["map_texels"] = l.map.texels();
        jl["map_size"] = l.map.mapSize;
        jl["map_size_requested"] = l.map.requestedMapSize;
        jl["map_views"] = l.map.views;
        jl["importance"] = l.map.importance;
        if (sequence && l.castsShadow)  // its own flicker and lag over the frames
          for (const report::LightSequence& ls : sequence->lights)
            if (ls.index == l.index) {
              jl["flicker_pct"] = ls.flicker.pct();
              jl["lag_rmse"] = ls.lag.rmse();
              jl["ghost_pct"] = ls.lag.ghostPct();
            }
        if (l.castsShadow) {  // the light's policy, and in the last frame its maps kept and the oldest one's age
          jl["map_updates"] = mapUpdatesName(l.map.updates);
          jl["maps_kept"] = l.map.keptMaps;
          jl["staleness"] = l.map.staleness;
          if (l.map.pages.poolPages > 0) {
            jl["pages_needed"] = l.map.pages.needed;
            jl["pages_drawn"] = l.map.pages.drawn;
            jl["pages_resident"] = l.map.pages.resident;
            jl["pages_missing"] = l.map.pages.missing;
            jl["pool_pages"] = l.map.pages.poolPages;
            jl["pool_mb"] = static_cast<double>(l.map.pages.poolBytes) / (1024.0 * 1024.0);
          }
        }
        j["lights"].push_back(std::move(jl));
      }
      // Warm: the median (and p10–p90) of kCompareTimedFrames frames after the warm-up.
      j["timings_ms"] = nlohmann::json::object();
      j["timings_p10_ms"] = nlohmann::json::object();
      j["timings_p90_ms"] = nlohmann::json::object();
      for (const report::PassStats& p : times.passes) {
        if (p.name == report::kTotalPass) continue;
        j["timings_ms"][p.name] = p.ms.median;
        j["timings_p10_ms"][p.name] = p.ms.p10;
        j["timings_p90_ms"][p.name] = p.ms.p90;
      }
      j["shadow_cost_ms"] = {{"median", times.shadowCost.median}, {"p10", times.shadowCost.p10}, {"p90", times.shadowCost.p90}};
      j["timed_frames"] = times.frames;
      j["warmup_frames"] = kCompareWarmupFrames;
      j["clock"] = times.clock;
      j["gl_renderer"] = context.info().renderer;
      j["reference_seconds"] = referenceSeconds;
      j["reference_samples"] = referenceSamples;
      j["reference_cached"] = referenceCached;
      j["reference_horizon_pixels"] = horizonPixels;
      std::printf("%s\n", j.dump(2).c_str());
      return 0;
    }
    std::printf("scene %s  --projection %s --filter %s  %dx%d, shadow map %d², light size %g\n  --camera %s\n",
                scene.name.c_str(), projection.c_str(), filter.c_str(), gbuffer.width, gbuffer.height,
                s.technique.mapSize(), scene.light().size, cameraArgument(scene.camera).c_str());
    std::printf("  RMSE            %8.4f\n  mean |dV|       %8.4f\n  leak %%          %8.3f  (inside the reference's umbra: %.3f)\n"
                "  over-dark %%     %8.3f  (acne: %.3f %% of the pixels the reference sees fully lit)\n"
                "  penumbra RMSE   %8.4f\n  split approx.   %8.4f  (RMSE of V vs cos-weighted V in the reference)\n"
                "  pixels          %8zu\n",
                m.rmse, m.mae, m.leakPct, m.umbraLeakPct, m.overDarkPct, m.acnePct, m.penumbraRmse, approximationRmse, m.pixels);
    if (cmp.lights.size() > 1) {
      std::printf("  the metrics above combine the lights, each weighted by its unshadowed light at the pixel:\n"
                  "    light  type   RMSE     leak %%  over-dark %%  penumbra RMSE  map\n");
      for (const report::LightComparison& l : cmp.lights) {
        const std::string map = fmt::format("{}² × {}{}", l.map.mapSize, l.map.views,
                                            l.map.mapSize < l.map.requestedMapSize ? fmt::format(" (asked {}²)", l.map.requestedMapSize) : "");
        if (l.castsShadow)
          std::printf("    %5zu  %-5s %7.4f  %8.3f  %11.3f  %13.4f  %s\n", l.index, lightTypeName(l.type), l.metrics.rmse,
                      l.metrics.leakPct, l.metrics.overDarkPct, l.metrics.penumbraRmse, map.c_str());
        else
          std::printf("    %5zu  %-5s casts no shadow\n", l.index, lightTypeName(l.type));
      }
    }
    for (const report::LightComparison& l : cmp.lights)
      if (l.colour)
        std::printf("  colour RMSE     %8.4f  (over RGB; red %.4f, green %.4f, blue %.4f) against light %zu's RGB reference\n",
                    l.colour->rmse, l.colour->channelRmse[0], l.colour->channelRmse[1], l.colour->channelRmse[2], l.index);
    for (const report::LightComparison& l : cmp.lights)
      if (l.map.pages.poolPages > 0)
        std::printf("  pages           light %zu: %d needed, %d drawn, %d resident in the last frame; pool %d pages, %.1f MiB\n", l.index,
                    l.map.pages.needed, l.map.pages.drawn, l.map.pages.resident, l.map.pages.poolPages,
                    static_cast<double>(l.map.pages.poolBytes) / (1024.0 * 1024.0));
    std::printf("  texel density   median %.3f, p95 %.3f, near median %.3f screen px per texel; %.1f%% undersampled\n",
                densityStats.median, densityStats.p95, densityStats.nearMedian, densityStats.undersampledPct);
    if (sequence)
      std::printf("  %zu frames at %g fps from %g s%s: RMSE mean %.4f, worst %.4f at frame %zu; penumbra RMSE mean %.4f; "
                  "flicker %.4f%% of %zu followed points\n",
                  sequence->frames.size(), o->fps, o->timeS, o->walk ? ", the camera walking round its target" : "",
                  sequence->rmseMean, sequence->rmseWorst, sequence->rmseWorstFrame, sequence->penumbraRmseMean,
                  sequence->flicker.pct(), sequence->flicker.followed);
    if (sequence)
      std::printf("  lag             RMSE %.4f on %zu pixels whose reference changed in the last %d frames; %.2f%% off by > %.1f "
                  "(%zu too dark, %zu too bright)\n",
                  sequence->lag.rmse(), sequence->lag.pixels, LagOptions{}.frames, sequence->lag.ghostPct(), LagOptions{}.ghostV,
                  sequence->lag.tooDark, sequence->lag.tooBright);
    if (sequence && sequence->lights.size() > 1)
      for (const report::LightSequence& l : sequence->lights)
        std::printf("    light %zu: flicker %.4f%% of %zu followed points; lag RMSE %.4f on %zu pixels, %.2f%% off\n", l.index,
                    l.flicker.pct(), l.flicker.followed, l.lag.rmse(), l.lag.pixels, l.lag.ghostPct());
    if (mapsCached(renderer.shadows())) std::printf("  %s\n", mapUpdatesSummary(renderer.shadows()).c_str());
    if (shimmer)
      std::printf("  shimmer         %.4f%% of %zu edge points over %d steps\n", shimmer->shimmerPct, shimmer->edgePoints,
                  shimmer->steps);
    std::printf("  times, warm: the median of %d frames after %d warm-up (p10-p90), %s on %s:\n", times.frames,
                kCompareWarmupFrames, times.clock.c_str(), context.info().renderer.c_str());
    for (const report::PassStats& p : times.passes)
      if (p.name != report::kTotalPass)
        std::printf("    %-12s %8.2f ms  (%.2f-%.2f)\n", p.name.c_str(), p.ms.median, p.ms.p10, p.ms.p90);
    std::printf("    %-12s %8.2f ms  (%.2f-%.2f; shadow + prefilter + visibility per frame, as bench's whole cost)\n",
                "whole cost", times.shadowCost.median, times.shadowCost.p10, times.shadowCost.p90);
    std::printf("  reference: %d samples/pixel, %.2f s%s\n", referenceSamples, referenceSeconds, referenceCached ? " (cached)" : "");
    if (horizonPixels > 0)
      std::printf("  left out:       %zu pixels lit by part of a soft light whose centre is below their horizon (in the EXRs, "
                  "not in the metrics)\n",
                  horizonPixels);
    std::printf("  images in %s/\n", o->out.c_str());
    return 0;
  }});
}

}  // namespace penumbra::app
