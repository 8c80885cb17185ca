// The aliasing axis measured: texel density (screen pixels per shadow-map texel) on the city for
// each projection at equal texel budgets, the measure itself against a closed form, the shimmer
// of csm with and without stabilisation, PSM with the light behind the camera, and the debug
// views of cascades and texel density.
#include "GlFixture.h"
#include "TestGeometry.h"

#include "comparison/Shimmer.h"
#include "comparison/TexelDensity.h"
#include "techniques/projections/PerspectiveProjection.h"
#include "shared/DensityRamp.h"
#include "shared/Enums.h"

#include <penumbra/ImageIO.h>

#include <fmt/format.h>
#include <glm/gtc/matrix_transform.hpp>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <random>
#include <set>

using namespace penumbra;
using namespace penumbra::test;

namespace {

struct Case {
  std::string projection;
  int mapSize;
  std::vector<std::pair<std::string, std::string>> params;
};

std::unique_ptr<Renderer> makeRenderer(const Scene& scene, const Case& t, const std::string& filter = "hard") {
  return makeTestRenderer(scene, t.projection, filter, t.params, t.mapSize);
}

// Where a test may leave images for a person to look at (unset: nowhere).
std::filesystem::path artifactDir() {
  const char* dir = std::getenv("PENUMBRA_TEST_ARTIFACTS");
  return dir ? std::filesystem::path(dir) : std::filesystem::path();
}

// Texel density on city from another camera, one 1024² map per projection (per cascade for csm).
std::map<std::string, TexelDensityStats> cityDensities(const glm::vec3& position, const glm::vec3& target, float fovDeg,
                                                       int width, int height, const std::vector<std::string>& projections) {
  Scene city = makeBuiltinScene("city");
  city.camera.position = position;
  city.camera.target = target;
  city.camera.fovYRad = glm::radians(fovDeg);
  constexpr int kMap = 1024;
  std::map<std::string, TexelDensityStats> out;
  for (const std::string& projection : projections) {
    auto r = makeRenderer(city, {projection, kMap, {}});
    r->render({.width = width, .height = height});
    const TexelDensityStats& s = out[projection] =
        texelDensityStats(computeTexelDensity(*r), r->readGBuffer(), city.camera.position);
    std::printf("  %-8s median %.3f, near median %.3f screen px per texel\n", projection.c_str(), s.median, s.nearMedian);
  }
  return out;
}

}  // namespace

// The measure against a closed form: a camera looking straight down at a floor under a sun
// straight overhead. A pixel at the image centre spans (2·H·tan(fov/2)/height)² m² of floor, a
// texel (extent/mapSize)², so one texel covers their ratio in pixels.
TEST(Aliasing, TexelDensityMatchesTheClosedFormOnAFlatFloor) {
  Scene s;
  s.name = "floor";
  addObject(s, "floor", makePlane(20.0f, 20.0f), {0.7f, 0.7f, 0.7f});
  addObject(s, "box", makeBox({1.0f, 1.0f, 1.0f}), {0.8f, 0.3f, 0.3f}, glm::translate(glm::mat4(1.0f), {3.0f, 0.5f, 3.0f}));
  Light sun;
  sun.direction = {0.0f, -1.0f, 0.0f};
  s.lights.push_back(sun);
  constexpr float kHeightM = 6.0f;
  s.camera.position = {0.0f, kHeightM, 0.0f};
  s.camera.target = {0.0f, 0.0f, 0.0f};
  s.camera.up = {0.0f, 0.0f, -1.0f};
  s.camera.fovYRad = 0.9f;
  constexpr int kW = 160, kH = 120, kMap = 512;
  auto r = makeRenderer(s, {"uniform", kMap, {}});
  r->render({.width = kW, .height = kH});
  const std::vector<float> d = computeTexelDensity(*r);
  const ShadowView& v = r->frusta().views[0];
  const float pixelM = 2.0f * kHeightM * std::tan(0.5f * s.camera.fovYRad) / static_cast<float>(kH);
  const float texelArea = (v.extent.x / kMap) * (v.extent.y / kMap);
  const float expected = texelArea / (pixelM * pixelM);
  const float measured = d[static_cast<size_t>(kH / 2) * kW + kW / 2];
  EXPECT_NEAR(measured, expected, 0.01f * expected) << "extent " << v.extent.x << " x " << v.extent.y;
  // Double the map: a texel covers a quarter of the pixels.
  setMapSize(*r, 2 * kMap);
  r->render({.width = kW, .height = kH});
  const float finer = computeTexelDensity(*r)[static_cast<size_t>(kH / 2) * kW + kW / 2];
  const ShadowView& v2 = r->frusta().views[0];
  EXPECT_NEAR(finer, (v2.extent.x / (2 * kMap)) * (v2.extent.y / (2 * kMap)) / (pixelM * pixelM), 0.01f * finer);
  // Background pixels carry no value; statistics see only the floor and the box.
  const TexelDensityStats st = texelDensityStats(d, r->readGBuffer(), s.camera.position);
  EXPECT_GT(st.pixels, static_cast<size_t>(kW * kH) / 2);
  EXPECT_NEAR(st.median, expected, 0.1f * expected);
}

// The table: city at 1280×720, equal texel budgets (uniform/psm/tsm/lispsm one 2048² map,
// csm and sdsm four 1024² maps). Near-camera density (median screen pixels per texel within 20 m)
// must drop at least 4× for csm, tsm and lispsm, 2× for psm (whose light direction here, from the
// side and a little behind, favours it); sdsm, with csm's memory, must at least halve csm's.
TEST(Aliasing, CityTexelDensityTable) {
  const Scene city = makeBuiltinScene("city");
  const std::vector<Case> techniques = {
      {"uniform", 2048, {}},
      {"psm", 2048, {}},
      {"tsm", 2048, {}},
      {"lispsm", 2048, {}},
      {"csm", 1024, {{"csm.cascades", "4"}}},
      {"sdsm", 1024, {{"sdsm.cascades", "4"}}},
  };
  std::map<std::string, TexelDensityStats> stats;
  std::printf("\n  projection  map          median        p95   near_median  undersampled_pct\n");
  for (const Case& t : techniques) {
    auto r = makeRenderer(city, t);
    r->render({.width = 1280, .height = 720});
    const std::vector<float> d = computeTexelDensity(*r);
    const TexelDensityStats s = texelDensityStats(d, r->readGBuffer(), city.camera.position);
    stats[t.projection] = s;
    const std::string budget = t.mapSize == 1024 ? "4x1024^2" : "1x2048^2";
    std::printf("  %-10s  %-9s %10.4f %10.3f %12.4f %12.1f\n", t.projection.c_str(), budget.c_str(), s.median, s.p95,
                s.nearMedian, s.undersampledPct);
    RecordProperty(t.projection + "_texel_density_near_median", fmt::format("{:.4f}", s.nearMedian));
    ASSERT_GT(s.nearPixels, 10000u) << t.projection << ": the near set is the lower part of the image";
    if (const std::filesystem::path dir = artifactDir(); !dir.empty()) {
      const ColorImage heat = texelDensityHeatmap(d, 1280, 720);
      writePng(dir / ("city-texel-density-" + t.projection + ".png"), heat.width, heat.height, heat.rgba);
    }
  }
  const double uniform = stats["uniform"].nearMedian;
  EXPECT_GT(stats["uniform"].undersampledPct, 50.0) << "uniform should under-sample most of the city";
  EXPECT_LE(stats["csm"].nearMedian * 4.0, uniform);
  EXPECT_LE(stats["tsm"].nearMedian * 4.0, uniform);
  EXPECT_LE(stats["psm"].nearMedian * 2.0, uniform);
  EXPECT_LE(stats["lispsm"].nearMedian * 4.0, uniform);
  EXPECT_LE(stats["sdsm"].nearMedian * 2.0, stats["csm"].nearMedian);
}

// tsm from city's bench, looking down and away from the sun (`--camera 1.5,1.7,310:4.3,0,305.5:40`):
// the view axis leaves the receivers a few metres ahead. A trapezoid built along the axis' image
// opened its sides nearly flat and kept uniform's density (near median 498 against uniform's
// 579 screen px per texel at 384×216); along the receivers' centroid it reads 0.17.
TEST(Aliasing, TsmFollowsTheReceiversWhenTheCameraLooksDown) {
  auto s = cityDensities({1.5f, 1.7f, 310.0f}, {4.3f, 0.0f, 305.5f}, 40.0f, 384, 216, {"uniform", "tsm"});
  ASSERT_GT(s["tsm"].nearPixels, 10000u);
  EXPECT_LE(s["tsm"].nearMedian, 1.0);
  EXPECT_LE(s["tsm"].nearMedian * 16.0, s["uniform"].nearMedian);
}

// An aerial camera, 120 m above city looking down at 45° (`--camera 0,120,330:0,0,250:50`): the
// nearest receiver is 69 m away. csm's splits started at the 0.1 m near plane, so three cascades
// covered air and the last one the whole view (median 2.99 screen px per texel against uniform's
// 0.092); tsm's 20 m focus lay in the air and the 80% rule put the apex on the top edge (7.1).
// Both now measure from the nearest receiver: 0.38 and 1.40 (256×144, 1024² maps).
TEST(Aliasing, AerialCameraStartsAtTheNearestReceiver) {
  auto s = cityDensities({0.0f, 120.0f, 330.0f}, {0.0f, 0.0f, 250.0f}, 50.0f, 256, 144, {"uniform", "csm", "tsm"});
  EXPECT_LE(s["csm"].median, 1.0);
  EXPECT_LE(s["tsm"].median, 2.0);
  EXPECT_LE(s["uniform"].median, 0.2) << "the view is small enough for one map";
}

// Stabilisation: over 50 small camera moves (sub-texel and a few texels, translation and turns)
// fixed world points near shadow edges keep their visibility with csm's snapping, and flicker
// without it.
TEST(Aliasing, CsmStabilisationStopsShimmer) {
  const Scene city = makeBuiltinScene("city");
  ShimmerOptions o;
  o.steps = 50;
  const RenderOptions render{.width = 192, .height = 108};
  double pct[2] = {0.0, 0.0};
  for (int stabilize = 0; stabilize <= 1; ++stabilize) {
    auto r = makeRenderer(city, {"csm", 512, {{"csm.stabilize", stabilize ? "on" : "off"}}});
    const ShimmerResult s = measureShimmer(*r, render, o);
    std::printf("  csm.stabilize=%s: shimmer_pct %.4f over %zu edge points, %d steps of %.4f m texels\n",
                stabilize ? "on" : "off", s.shimmerPct, s.edgePoints, s.steps, s.texelM);
    RecordProperty(stabilize ? "shimmer_pct_on" : "shimmer_pct_off", fmt::format("{:.4f}", s.shimmerPct));
    ASSERT_GT(s.edgePoints, 200u);
    pct[stabilize] = s.shimmerPct;
  }
  EXPECT_LT(pct[1], 0.1);
  EXPECT_GT(pct[0], 0.2);
  EXPECT_GT(pct[0], 10.0 * std::max(pct[1], 0.01));
}

// PSM with the sun behind the camera: the light's post-perspective image converges on a point
// beyond the far plane (the inverted case). Probe pixels deep inside and outside the boxes'
// shadows (a CPU ray cast, robust 4 cm around) must come out shadowed and lit.
TEST(Aliasing, PsmLightBehindCameraProbePixels) {
  Scene scene = makeBuiltinScene("boxes");
  const glm::vec3 fwd = scene.camera.forward();
  scene.lights.front().direction = glm::normalize(glm::vec3(fwd.x, 0.0f, fwd.z) * 0.7f + glm::vec3(0.25f, -1.0f, 0.1f));
  scene.lights.front().size = 0.0f;
  ASSERT_EQ(psmLightCase(scene.camera, scene.light()), PsmLightCase::Behind);
  constexpr int kSize = 256;
  const RenderResult r = renderScene(scene, "psm", "hard", {{"hard.bias", "slope"}}, kSize, kSize, 2048);
  ASSERT_TRUE(r.frusta.views.front().warped) << "psm fell back to an unwarped map";
  CasterTriangles tris(scene);
  std::mt19937 rng(3);
  std::uniform_int_distribution<size_t> pick(0, r.visibility.size() - 1);
  int shadowed = 0, lit = 0, wrong = 0;
  for (int tries = 0; tries < 20000 && (shadowed < 150 || lit < 150); ++tries) {
    const size_t i = pick(rng);
    const glm::vec4 p = r.gbuffer.position[i];
    if (p.w < 0.5f || std::abs(p.y) > 1e-3f) continue;  // floor pixels
    const float occ = tris.robustOcclusion(scene, glm::vec3(p), {0, 1, 0}, 0.04f);
    if (occ == 1.0f && shadowed < 150) {
      ++shadowed;
      wrong += r.visibility[i] > 0.05f ? 1 : 0;
    } else if (occ == 0.0f && lit < 150) {
      ++lit;
      wrong += r.visibility[i] < 0.95f ? 1 : 0;
    }
  }
  EXPECT_GE(shadowed, 50);
  EXPECT_GE(lit, 100);
  EXPECT_EQ(wrong, 0) << "of " << shadowed << " shadowed and " << lit << " lit probes";
}

// The debug views: cascade colours show one region per cascade; the texel-density view shows
// the ramp colour of the measured density (the GLSL view and the CPU heatmap share one ramp).
TEST(Aliasing, CascadeAndTexelDensityDebugViews) {
  const Scene city = makeBuiltinScene("city");
  auto r = makeRenderer(city, {"csm", 512, {}});
  RenderOptions o{.width = 192, .height = 108};
  o.debugView = PN_VIEW_CASCADES;
  r->render(o);
  const ColorImage cascades = r->readColor();
  // Dominant channel of each pixel in the lower half: cascade 0 is red, cascade 1 green.
  std::set<int> dominant;
  for (int y = cascades.height / 2; y < cascades.height; ++y)
    for (int x = 0; x < cascades.width; ++x) {
      const uint8_t* c = &cascades.rgba[(static_cast<size_t>(y) * static_cast<size_t>(cascades.width) + static_cast<size_t>(x)) * 4];
      if (c[0] > c[1] + 40 && c[0] > c[2] + 40) dominant.insert(0);
      if (c[1] > c[0] + 40 && c[1] > c[2] + 40) dominant.insert(1);
    }
  EXPECT_EQ(dominant.size(), 2u) << "the ground near the camera spans the first two cascades";
  if (const std::filesystem::path dir = artifactDir(); !dir.empty()) writePng(dir / "city-cascades.png", cascades.width, cascades.height, cascades.rgba);

  o.debugView = PN_VIEW_TEXEL_DENSITY;
  float density[2] = {0.0f, 0.0f};
  int k = 0;
  for (const char* projection : {"csm", "uniform"}) {
    auto q = makeRenderer(city, {projection, 512, {}});
    q->render(o);
    const ColorImage heat = q->readColor();
    const std::vector<float> d = computeTexelDensity(*q);
    // A ground pixel near the bottom centre (row 1 from the bottom, GL order).
    const int x = heat.width / 2, y = 1;
    const float value = d[static_cast<size_t>(y) * static_cast<size_t>(heat.width) + static_cast<size_t>(x)];
    ASSERT_GT(value, 0.0f) << projection;
    density[k++] = value;
    const uint8_t* c = &heat.rgba[(static_cast<size_t>(heat.height - 1 - y) * static_cast<size_t>(heat.width) + static_cast<size_t>(x)) * 4];
    const glm::vec4 ramp = gpu::densityRampColor(std::log2(value));
    // colour = shade · ramp: compare chromaticity (each channel over the largest).
    const glm::vec3 got = glm::vec3(c[0], c[1], c[2]) / static_cast<float>(std::max({c[0], c[1], c[2]}));
    const glm::vec3 want = glm::vec3(ramp) / std::max({ramp.x, ramp.y, ramp.z});
    EXPECT_LT(glm::length(got - want), 0.05f) << projection << " density " << value;
  }
  EXPECT_GT(density[1], 8.0f * density[0]) << "uniform's texels near the camera are far larger than csm's";
}
