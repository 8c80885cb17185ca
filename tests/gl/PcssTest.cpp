// pcss against the Embree reference on `pen` (spot light): the penumbra widens away from the
// contact and matches the reference's width; PCSS beats every fixed-radius PCF; on the sun
// (orthographic view) the penumbra follows the angular radius. Also the benchmark note: the
// visibility pass time as the light grows ×8, next to PCF at a fixed radius.
#include "GlFixture.h"
#include "TestGeometry.h"

#include <penumbra/Metrics.h>
#include <penumbra/Reference.h>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

using namespace penumbra;
using namespace penumbra::test;

namespace {

constexpr int kMapSize = 1024;
constexpr int kReferenceSamples = 256;

ReferenceResult traceReference(const Scene& scene, const GBufferData& g) {
  ReferenceTracer tracer(scene);
  ReferenceOptions o;
  o.samples = kReferenceSamples;
  o.progress = false;
  o.useCache = false;
  return tracer.trace(g, scene.light(), o);
}

// --- pen geometry ------------------------------------------------------------------------
// The pencil's tip touches the floor at the origin; its shadow on the floor is the central
// projection of its axis from the light's centre: a ray from the origin along `shadowAxis`.
glm::vec2 penShadowAxis(const Scene& scene) {
  const Object* pencil = nullptr;
  for (const Object& o : scene.objects)
    if (o.name == "pencil") pencil = &o;
  EXPECT_NE(pencil, nullptr);
  const glm::vec3 axis = glm::normalize(glm::vec3(pencil->worldFromObject * glm::vec4(0, 1, 0, 0)));
  const glm::vec3 light = scene.light().position;
  const glm::vec3 p = axis;  // a point of the axis 1 m from the tip
  const glm::vec3 shadow = light + (p - light) * (light.y / (light.y - p.y));
  return glm::normalize(glm::vec2(shadow.x, shadow.z));
}

// The 10 %–90 % width (m) of the penumbra across the shadow at distance alongM from the
// contact: floor pixels within kBandHalfM of that distance are binned by their signed distance
// across the shadow axis, V is averaged per bin, and on each flank the crossings of 0.9 and 0.1
// (linearly interpolated between bins) are found from the outside in. Mean of both flanks;
// NaN if a flank never reaches 0.1 (no umbra to measure against).
double penumbraWidthM(std::span<const float> v, const GBufferData& g, std::span<const uint8_t> mask,
                      glm::vec2 axis, float alongM) {
  constexpr float kBandHalfM = 0.03f, kBinM = 0.001f, kHalfSpanM = 0.09f;
  constexpr double kLitV = 0.9, kDarkV = 0.1;
  const int bins = static_cast<int>(2.0f * kHalfSpanM / kBinM);
  std::vector<double> sum(static_cast<size_t>(bins), 0.0);
  std::vector<int> count(static_cast<size_t>(bins), 0);
  const glm::vec2 across(-axis.y, axis.x);
  for (size_t i = 0; i < v.size(); ++i) {
    const glm::vec4& p = g.position[i];
    if (!mask[i] || !onFloor(p)) continue;
    const glm::vec2 xz(p.x, p.z);
    if (std::abs(glm::dot(xz, axis) - alongM) > kBandHalfM) continue;
    const int b = static_cast<int>(std::floor((glm::dot(xz, across) + kHalfSpanM) / kBinM));
    if (b < 0 || b >= bins) continue;
    sum[static_cast<size_t>(b)] += v[i];
    ++count[static_cast<size_t>(b)];
  }
  std::vector<double> profile;
  for (int b = 0; b < bins; ++b)
    if (count[static_cast<size_t>(b)] > 0) profile.push_back(sum[static_cast<size_t>(b)] / count[static_cast<size_t>(b)]);
  // Bins are contiguous in a camera that covers the band; an empty bin would only merge two.
  auto flank = [&](bool reversed) {
    auto at = [&](size_t k) { return profile[reversed ? profile.size() - 1 - k : k]; };
    auto crossing = [&](double level, size_t from, size_t& k) {
      for (k = from; k < profile.size(); ++k)
        if (at(k) < level) break;
      if (k == 0 || k == profile.size()) return std::numeric_limits<double>::quiet_NaN();
      return static_cast<double>(k - 1) + (at(k - 1) - level) / (at(k - 1) - at(k));
    };
    size_t k90 = 0, k10 = 0;
    const double c90 = crossing(kLitV, 0, k90);
    const double c10 = crossing(kDarkV, k90, k10);
    return (c10 - c90) * kBinM;
  };
  return 0.5 * (flank(false) + flank(true));
}

// A camera looking at the shadow alongM from the contact from the far side of the pencil (so
// the pencil never hides its shadow), about 0.25 m of floor across the image.
Camera cameraOnShadow(glm::vec2 axis, float alongM) {
  const glm::vec3 target(axis.x * alongM, 0.0f, axis.y * alongM);
  Camera c;
  c.target = target;
  c.position = target + glm::vec3(0.0f, 0.7f, -0.4f);
  c.fovYRad = 0.3f;
  c.nearM = 0.05f;
  c.farM = 20.0f;
  return c;
}

}  // namespace

TEST(Pcss, PenPenumbraGrowsWithDistanceAndMatchesReference) {
  Scene scene = makeBuiltinScene("pen");
  ASSERT_GT(scene.light().size, 0.0f);
  const glm::vec2 axis = penShadowAxis(scene);
  constexpr float kNearM = 0.45f, kFarM = 0.95f;  // along the shadow from the contact point
  constexpr int kSize = 192;
  double widths[2][2] = {};  // [point][pcss, reference]
  const float along[2] = {kNearM, kFarM};
  for (int k = 0; k < 2; ++k) {
    scene.camera = cameraOnShadow(axis, along[k]);
    const RenderResult r = renderScene(scene, "uniform", "pcss", {}, kSize, kSize, kMapSize);
    const ReferenceResult ref = traceReference(scene, r.gbuffer);
    widths[k][0] = penumbraWidthM(r.visibility, r.gbuffer, ref.litMask, axis, along[k]);
    widths[k][1] = penumbraWidthM(ref.visibility, r.gbuffer, ref.litMask, axis, along[k]);
    std::printf("pen penumbra (10-90%%) %.2f m from the contact: pcss %.1f mm, reference %.1f mm (%+.0f%%)\n", along[k],
                1e3 * widths[k][0], 1e3 * widths[k][1], 100.0 * (widths[k][0] / widths[k][1] - 1.0));
  }
  constexpr double kMinGrowth = 1.3;  // the reference grows ~2x between the points
  for (int m = 0; m < 2; ++m) {
    ASSERT_TRUE(std::isfinite(widths[0][m]) && std::isfinite(widths[1][m])) << "no umbra to measure against";
    EXPECT_GT(widths[1][m], kMinGrowth * widths[0][m]) << (m == 0 ? "pcss" : "reference");
  }
  constexpr double kMaxMismatch = 0.25;
  for (int k = 0; k < 2; ++k) EXPECT_LE(std::abs(widths[k][0] / widths[k][1] - 1.0), kMaxMismatch) << along[k] << " m";
}

TEST(Pcss, BeatsEveryFixedRadiusPcfOnPen) {
  const Scene scene = makeBuiltinScene("pen");
  constexpr int kWidth = 256, kHeight = 144;
  const RenderResult pcss = renderScene(scene, "uniform", "pcss", {}, kWidth, kHeight, kMapSize);
  const ReferenceResult ref = traceReference(scene, pcss.gbuffer);
  const VisibilityMetrics mPcss = compareVisibility(pcss.visibility, ref.visibility, ref.litMask);
  std::printf("pen, %dx%d, map %d, reference %d spp: RMSE over %zu lit pixels (penumbra RMSE over %zu)\n", kWidth, kHeight,
              kMapSize, kReferenceSamples, mPcss.pixels, mPcss.penumbraPixels);
  std::printf("  %-26s %8s %14s\n", "technique", "RMSE", "penumbra RMSE");
  std::printf("  %-26s %8.4f %14.4f\n", "pcss (16 + 32 poisson)", mPcss.rmse, mPcss.penumbraRmse);
  for (const char* kernel : {"poisson", "box"}) {
    for (int radius : {1, 2, 4, 8, 16}) {
      const RenderResult pcf = renderScene(scene, "uniform", "pcf",
                                           {{"pcf.kernel", kernel}, {"pcf.radiusTexels", std::to_string(radius)}, {"pcf.samples", "32"}},
                                           kWidth, kHeight, kMapSize);
      const VisibilityMetrics m = compareVisibility(pcf.visibility, ref.visibility, ref.litMask);
      const std::string name = fmt::format("pcf {} r={}", kernel, radius);
      std::printf("  %-26s %8.4f %14.4f\n", name.c_str(), m.rmse, m.penumbraRmse);
      EXPECT_LT(mPcss.rmse, m.rmse) << name;
    }
  }
}

// The visibility pass is compiled for its frame (FrameContext::frameDefines): a spot light's
// psm and tsm views are perspective AND warped, and the penumbra and texel sizes need both. When
// the two facts were one "kind", warped spot views were sized as a sun's: pcss on pen with psm read
// RMSE 0.0271 against uniform's 0.0049 (now 0.0061, tsm 0.0055). Every projection stays within 2x
// of the uniform map's error.
TEST(Pcss, SpotLightWarpedViewsAreSizedAsPerspective) {
  const Scene scene = makeBuiltinScene("pen");
  constexpr int kWidth = 256, kHeight = 144;
  constexpr double kMaxRatio = 2.0;
  const RenderResult uniform = renderScene(scene, "uniform", "pcss", {}, kWidth, kHeight, kMapSize);
  const ReferenceResult ref = traceReference(scene, uniform.gbuffer);
  const double base = compareVisibility(uniform.visibility, ref.visibility, ref.litMask).rmse;
  for (const char* projection : {"psm", "tsm", "csm"}) {
    const RenderResult r = renderScene(scene, projection, "pcss", {}, kWidth, kHeight, kMapSize);
    const double rmse = compareVisibility(r.visibility, ref.visibility, ref.litMask).rmse;
    std::printf("pen pcss %-7s RMSE %.4f (uniform %.4f)\n", projection, rmse, base);
    EXPECT_LE(rmse, kMaxRatio * base) << projection;
  }
}

// The uniform fit ends `pen`'s spot map inside the visible floor, and that floor deepens toward
// the map's far edge. Kernel taps past the edge read the edge texel (clamp to edge) and used to be
// compared with the receiver's plane continued past the edge: a false blocker, i.e. a grey line
// along the edge (pcf box r=16: V = 0.52 on 249 pixels) and a blocker-search hit with a 0 m
// penumbra (pcss). Taps are now kept inside the map. vssm and msm-soft had the same line from
// their SAT boxes (clipped on one side, so no longer centred on the receiver: 9 and 14 pixels,
// V down to 0.97 and 0.75); their boxes now shrink about the receiver, which is itself moved onto
// the outermost texel centres along its plane. Floor far from the pencil's shadow is lit.
TEST(MapEdge, NoFalseShadowOnTheLitFloor) {
  const Scene scene = makeBuiltinScene("pen");
  constexpr int kWidth = 256, kHeight = 144;
  constexpr float kClearM = 0.3f;  // from the shadow's axis: far beyond any kernel or penumbra here
  const glm::vec2 axis = penShadowAxis(scene);
  for (const auto& [filter, params] : std::vector<std::pair<std::string, Params>>{
           {"pcf", {{"pcf.kernel", "box"}, {"pcf.radiusTexels", "16"}}},
           {"pcf", {{"pcf.kernel", "poisson"}, {"pcf.radiusTexels", "16"}}},
           {"pcf", {{"pcf.kernel", "poisson"}, {"pcf.radiusTexels", "16"}, {"pcf.hardwareCompare", "on"}}},
           {"pcss", {}},
           {"pcss", {{"pcss.pattern", "box"}}},
           {"vssm", {}},
           {"msm-soft", {}}}) {
    const RenderResult r = renderScene(scene, "uniform", filter, params, kWidth, kHeight, kMapSize);
    size_t floor = 0, dark = 0;
    float darkest = 1.0f;
    for (size_t i = 0; i < r.visibility.size(); ++i) {
      const glm::vec4& p = r.gbuffer.position[i];
      if (!onFloor(p)) continue;
      const glm::vec2 xz(p.x, p.z);
      const float along = glm::dot(xz, axis);
      const float fromAxisM = along > 0.0f ? std::abs(glm::dot(xz, glm::vec2(-axis.y, axis.x))) : glm::length(xz);
      if (fromAxisM < kClearM) continue;
      ++floor;
      if (r.visibility[i] < 0.99f) ++dark;
      darkest = std::min(darkest, r.visibility[i]);
    }
    std::string name = filter;
    for (const auto& [key, value] : params) name += fmt::format(" {}={}", key, value);
    std::printf("pen %s: %zu of %zu floor pixels clear of the shadow below V=0.99 (darkest %.3f)\n", name.c_str(), dark,
                floor, darkest);
    EXPECT_GT(floor, 10000u);
    EXPECT_EQ(dark, 0u) << name;
  }
}

TEST(Pcss, SunPenumbraFollowsTheAngularRadius) {
  // An orthographic view: the penumbra widens with the sun's angular radius as the reference's.
  const Scene scene = makeBuiltinScene("grazing");  // a long shadow: its penumbra widens along it
  constexpr int kWidth = 256, kHeight = 144;
  auto penumbraPixels = [](std::span<const float> v, std::span<const uint8_t> mask) {
    size_t n = 0;
    for (size_t i = 0; i < v.size(); ++i) n += mask[i] && v[i] > kPenumbraLowV && v[i] < kPenumbraHighV;
    return static_cast<double>(n);
  };
  double counts[2][2] = {};  // [size][pcss, reference]
  const float sizes[2] = {0.005f, 0.02f};
  for (int k = 0; k < 2; ++k) {
    Scene s = scene;
    s.lights.front().size = sizes[k];
    const RenderResult pcss = renderScene(s, "uniform", "pcss", {}, kWidth, kHeight, kMapSize);
    const ReferenceResult ref = traceReference(s, pcss.gbuffer);
    const RenderResult hard = renderScene(s, "uniform", "hard", {}, kWidth, kHeight, kMapSize);
    const VisibilityMetrics mPcss = compareVisibility(pcss.visibility, ref.visibility, ref.litMask);
    const VisibilityMetrics mHard = compareVisibility(hard.visibility, ref.visibility, ref.litMask);
    // Cascades: each view has its own extent and depth range; the same code must hold.
    const RenderResult csm = renderScene(s, "csm", "pcss", {}, kWidth, kHeight, kMapSize);
    const VisibilityMetrics mCsm = compareVisibility(csm.visibility, ref.visibility, ref.litMask);
    std::printf("grazing, sun %.3f rad, csm (%zu views): RMSE pcss %.4f\n", sizes[k], csm.frusta.views.size(), mCsm.rmse);
    EXPECT_GT(csm.frusta.views.size(), 1u);
    EXPECT_LT(mCsm.rmse, mHard.rmse);
    counts[k][0] = penumbraPixels(pcss.visibility, ref.litMask);
    counts[k][1] = penumbraPixels(ref.visibility, ref.litMask);
    std::printf("grazing, sun %.3f rad: penumbra pixels pcss %.0f, reference %.0f; RMSE pcss %.4f, hard %.4f\n", sizes[k],
                counts[k][0], counts[k][1], mPcss.rmse, mHard.rmse);
    EXPECT_LT(mPcss.rmse, mHard.rmse);
  }
  constexpr double kMinGrowth = 1.3;
  EXPECT_GT(counts[1][0], kMinGrowth * counts[0][0]);
  EXPECT_GT(counts[1][1], kMinGrowth * counts[0][1]);
}

// Benchmark note, not a performance test: the numbers are printed; only their validity is
// asserted. Compare them as ratios within one run.
TEST(PcssBenchmark, VisibilityTimeAsTheLightGrows) {
  Scene scene = makeBuiltinScene("pen");
  glContext();
  Renderer renderer;
  RenderOptions o;
  o.width = 256;
  o.height = 144;
  constexpr int kWarmup = 2, kFrames = 15;
  auto minVisibilityMs = [&](const std::string& filter, const std::vector<std::pair<std::string, std::string>>& params,
                                float lightSize) {
    scene.lights.front().size = lightSize;
    Technique technique("uniform", filter);
    technique.setMapSize(kMapSize);
    applySettings(params, scene, technique);
    renderer.setScene(scene);
    renderer.setTechnique(technique);
    for (int i = 0; i < kWarmup; ++i) renderer.render(o);  // includes the shaders' JIT compile
    std::vector<double> ms;
    for (int i = 0; i < kFrames; ++i) {
      renderer.render(o);
      ms.push_back(renderer.timings().get("visibility"));
    }
    // The minimum: the least disturbed by other work on a shared CPU (llvmpipe runs on it).
    return *std::min_element(ms.begin(), ms.end());
  };
  std::printf("visibility pass, pen %dx%d, map %d, minimum of %d frames after %d warm-up; clock %s on %s\n", o.width,
              o.height, kMapSize, kFrames, kWarmup, "(below)", glContext().info().renderer.c_str());
  const double pcfMs = minVisibilityMs("pcf", {{"pcf.radiusTexels", "4"}, {"pcf.samples", "32"}}, 0.12f);
  std::printf("  %-32s %8.3f ms (%s)\n", "pcf poisson r=4, 32 taps", pcfMs, renderer.timings().clock.c_str());
  EXPECT_GT(pcfMs, 0.0);
  for (float size : {0.03f, 0.06f, 0.12f, 0.24f}) {
    const double pcssMs = minVisibilityMs("pcss", {}, size);
    const std::string name = fmt::format("pcss light.size={:.2f} m", size);
    std::printf("  %-32s %8.3f ms (x%.2f of pcf)\n", name.c_str(), pcssMs, pcssMs / pcfMs);
    EXPECT_GT(pcssMs, 0.0);
  }
}
