// penumbra compare: a technique against the ray-traced reference on the same pixels — metrics,
// per-pass times, and images (technique, reference, error heatmap, split-approximation error),
// and the two V's as float images, so that anyone can check the ruler with another renderer.
#include "Commands.h"
#include "Common.h"

#include "platform/Context.h"
#include "metrics/Shimmer.h"
#include "metrics/TexelDensity.h"
#include "report/FrameComparison.h"
#include "report/Sheet.h"

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

/// Every file compare writes into --out, in the order --help names them.
constexpr std::pair<const char*, const char*> kOutputs[] = {
    {"technique.png", "the frame lit with the technique's V"},
    {"reference.png", "the same frame lit with V_ref"},
    {"heatmap.png", "V - V_ref on a grey of V_ref: leaks red, over-darkening blue"},
    {"approximation.png", "where the shadow-map model itself (V averaged outside the lighting integral) is wrong"},
    {"sheet.png", "technique, reference, heatmap and a 4x zoom of its worst region, titled, with the colour legend and the metrics"},
    {"texel-density.png", "screen pixels per shadow-map texel"},
    {"visibility.exr", "the technique's V"},
    {"reference-visibility.exr", "V_ref: the unoccluded fraction of the light"},
    {"reference-visibility-cos.exr", "V_ref weighted by cos(theta): exact over unshadowed shading"},
};

std::string outputsHelp() {
  std::string help = "folder for the outputs:";
  for (const auto& [name, what] : kOutputs) help += fmt::format("\n  {} ({})", name, what);
  return help + "\nEXR files: one float channel V, row 0 = top; V_ref is 0 on geometry that faces away from the light "
                "(or lies outside a spot's cone) and 1 on background";
}

}  // namespace

void addCompareCommand(CLI::App& app, std::vector<Command>& commands) {
  struct Options {
    TechniqueOptions technique;
    int samples = ReferenceOptions{}.samples;  // as bench and the viewer's heatmap
    std::string out = "compare";
    bool json = false, noCache = false;
    int shimmer = 0;
    std::optional<std::uintmax_t> cacheMaxMb;
  };
  auto o = std::make_shared<Options>();
  CLI::App* sub = app.add_subcommand("compare", "render a technique and the ray-traced reference; print the error metrics and pass times");
  addTechniqueOptions(*sub, o->technique);
  sub->add_option("--samples", o->samples, "reference light samples per pixel (soft lights)")
      ->capture_default_str()->check(CLI::Range(1, kMaxReferenceSamples));
  sub->add_option("--out", o->out, outputsHelp())->capture_default_str();
  sub->add_flag("--json", o->json, "print one JSON object on stdout instead of the table");
  sub->add_flag("--no-cache", o->noCache, "recompute the reference even if a cached one exists");
  addCacheCapOption(*sub, o->cacheMaxMb, "after the reference is stored");
  sub->add_option("--shimmer", o->shimmer,
                  "also move the camera by small steps over N frames and report shimmer_pct (world points near shadow edges whose V changes by > 0.1 between frames)")
      ->check(CLI::Range(1, 1000));
  commands.push_back({sub, [o] {
    checkOutputDir("--out", o->out);
    Setup s = makeSetup(o->technique);
    gl::HeadlessContext context({.debug = gl::kDebugBuild, .verbose = o->technique.verbose});
    checkImageFits(context, s.render.width, s.render.height, kCompareHostBytesPerPixel);
    const std::unique_ptr<Renderer> rendererPtr = makeRenderer(context, s);
    Renderer& renderer = *rendererPtr;
    renderer.render(s.render);  // warm-up: the first frame includes shader compilation
    renderer.render(s.render);
    const GBufferData gbuffer = renderer.readGBuffer();
    // Aliasing: screen pixels covered by one shadow-map texel, per pixel.
    const std::vector<float> density = computeTexelDensity(renderer);
    const TexelDensityStats densityStats = texelDensityStats(density, gbuffer, s.scene.camera.position);

    ReferenceOptions ro;
    ro.samples = o->samples;
    ro.useCache = !o->noCache;
    ro.cacheMaxBytes = cacheCapBytes(o->cacheMaxMb);
    ro.progress = !o->json;
    const ReferenceTracer tracer(s.scene);
    const ReferenceResult ref = tracer.trace(gbuffer, s.scene.light(), ro);
    const report::FrameComparison cmp = report::compareFrame(renderer, ref, true);
    const VisibilityMetrics& m = cmp.metrics;
    const double approximationRmse = compareVisibility(ref.visibility, ref.visibilityCosWeighted, ref.litMask).rmse;

    const std::filesystem::path dir(o->out);
    const ColorImage &technique = cmp.technique, &reference = cmp.reference, &heat = cmp.heatmap;
    // The split model's own error in units of V, on the reference's grey, full colour at
    // kApproximationFullScaleV (docs/reference.md).
    constexpr float kApproximationFullScaleV = 0.1f;
    const ColorImage approx = errorHeatmap(ref.visibility, ref.visibilityCosWeighted, ref.litMask, ref.width, ref.height,
                                           nullptr, HeatmapOptions{kApproximationFullScaleV});
    const ColorImage all = report::compareSheet(
        {.technique = &technique, .reference = &reference, .heatmap = &heat, .v = cmp.visibility, .vRef = ref.visibility,
         .mask = ref.litMask, .heatmapFullScaleDeltaV = report::kLabHeatmap.fullScaleDeltaV,
         .techniqueTitle = fmt::format("{} · {} on {}", renderer.filter().id(), renderer.projection().id(), s.scene.name),
         .referenceTitle = fmt::format("reference: Embree, {} light samples per pixel", ref.samplesPerPixel),
         .metrics = {fmt::format("RMSE {:.4f} · mean |ΔV| {:.4f} · penumbra RMSE {:.4f} · leak {:.2f}% (in the umbra "
                                 "{:.2f}%) · over-dark {:.2f}% over {} lit pixels",
                                 m.rmse, m.mae, m.penumbraRmse, m.leakPct, m.umbraLeakPct, m.overDarkPct, m.pixels),
                     fmt::format("{}×{} pixels, shadow map {}², light size {:g} · --camera {}", gbuffer.width,
                                 gbuffer.height, s.render.shadowMapSize, s.scene.light().size,
                                 cameraArgument(s.scene.camera))}});
    const ColorImage densityImage = texelDensityHeatmap(density, gbuffer.width, gbuffer.height);
    for (const auto& [name, img] : {std::pair{"technique.png", &technique}, {"reference.png", &reference},
                                    {"heatmap.png", &heat}, {"approximation.png", &approx}, {"sheet.png", &all},
                                    {"texel-density.png", &densityImage}})
      writePng(dir / name, img->width, img->height, img->rgba);
    for (const auto& [name, v] : {std::pair{"visibility.exr", &cmp.visibility}, {"reference-visibility.exr", &ref.visibility},
                                  {"reference-visibility-cos.exr", &ref.visibilityCosWeighted}})
      writeExr(dir / name, ref.width, ref.height, flipRows<float>(*v, ref.width, ref.height));

    const PassTimings t = renderer.timings();
    std::optional<ShimmerResult> shimmer;
    if (o->shimmer > 0) {
      ShimmerOptions so;
      so.steps = o->shimmer;
      shimmer = measureShimmer(renderer, s.render, so);
    }
    const std::string projection(renderer.projection().id()), filter(renderer.filter().id());
    if (o->json) {
      nlohmann::json j;
      j["scene"] = s.scene.name;
      j["filter"] = filter;
      j["projection"] = projection;
      j["camera"] = cameraArgument(s.scene.camera);  // what --camera takes: the run repeats from it
      j["width"] = gbuffer.width;
      j["height"] = gbuffer.height;
      j["shadow_map"] = s.render.shadowMapSize;
      j["light_size"] = s.scene.light().size;
      j["rmse"] = m.rmse;
      j["mae"] = m.mae;
      j["leak_pct"] = m.leakPct;
      j["overdark_pct"] = m.overDarkPct;
      j["umbra_leak_pct"] = m.umbraLeakPct;
      j["penumbra_rmse"] = m.penumbraRmse;
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
      j["pixels"] = m.pixels;
      j["timings_ms"] = nlohmann::json::object();
      for (const auto& [pass, ms] : t.ms) j["timings_ms"][pass] = ms;
      j["clock"] = t.clock;
      j["gl_renderer"] = context.info().renderer;
      j["reference_seconds"] = ref.traceSeconds;
      j["reference_samples"] = ref.samplesPerPixel;
      j["reference_cached"] = ref.fromCache;
      std::printf("%s\n", j.dump(2).c_str());
      return 0;
    }
    std::printf("scene %s  --projection %s --filter %s  %dx%d, shadow map %d², light size %g\n  --camera %s\n",
                s.scene.name.c_str(), projection.c_str(), filter.c_str(), gbuffer.width, gbuffer.height,
                s.render.shadowMapSize, s.scene.light().size, cameraArgument(s.scene.camera).c_str());
    std::printf("  RMSE            %8.4f\n  mean |dV|       %8.4f\n  leak %%          %8.3f  (inside the reference's umbra: %.3f)\n"
                "  over-dark %%     %8.3f\n"
                "  penumbra RMSE   %8.4f\n  split approx.   %8.4f  (RMSE of V vs cos-weighted V in the reference)\n"
                "  pixels          %8zu\n",
                m.rmse, m.mae, m.leakPct, m.umbraLeakPct, m.overDarkPct, m.penumbraRmse, approximationRmse, m.pixels);
    std::printf("  texel density   median %.3f, p95 %.3f, near median %.3f screen px per texel; %.1f%% undersampled\n",
                densityStats.median, densityStats.p95, densityStats.nearMedian, densityStats.undersampledPct);
    if (shimmer)
      std::printf("  shimmer         %.4f%% of %zu edge points over %d steps\n", shimmer->shimmerPct, shimmer->edgePoints,
                  shimmer->steps);
    std::printf("  times (%s on %s):\n", t.clock.c_str(), context.info().renderer.c_str());
    for (const auto& [pass, ms] : t.ms) std::printf("    %-12s %8.2f ms\n", pass.c_str(), ms);
    std::printf("  reference: %d samples/pixel, %.2f s%s\n  images in %s/\n", ref.samplesPerPixel, ref.traceSeconds,
                ref.fromCache ? " (cached)" : "", o->out.c_str());
    return 0;
  }});
}

}  // namespace penumbra::app
