// second-depth: no acne on a grazing-lit plane with no bias at all, correct shadows for spot
// and sun lights, and an open mesh that renders (and still casts) instead of crashing.
#include "GlFixture.h"
#include "TestGeometry.h"

#include "gl/Objects.h"

#include <penumbra/Reference.h>

#include <glm/gtc/matrix_transform.hpp>

#include <cstdio>
#include <map>
#include <random>

using namespace penumbra;
using namespace penumbra::test;

namespace {

constexpr int kSize = 256, kMapSize = 1024;
constexpr float kAcneV = 0.5f;       // an unoccluded pixel darker than this is acne

// Makes the floor a shadow caster (it may or may not be one in the built-in scene). On `grazing`
// the floor is a closed slab, so its texels take the midpoint of two layers; on `pen` and `boxes`
// it is an open plane, so its texels exercise second-depth's single-layer fallback.
void floorCasts(Scene& scene) {
  for (Object& o : scene.objects)
    if (o.name == "floor") o.castsShadow = true;
}

// Unoccluded floor pixels, by the Embree reference: V_ref = 1 at the pixel and at four points
// jitterM around it on the floor (so aliased shadow edges, which are not acne, are left out).
std::vector<uint8_t> unoccludedFloor(const Scene& scene, const GBufferData& g, float jitterM) {
  ReferenceTracer tracer(scene);
  ReferenceOptions options;
  options.progress = false;
  options.useCache = false;
  std::vector<uint8_t> mask(g.position.size(), 0);
  for (size_t i = 0; i < mask.size(); ++i) mask[i] = onFloor(g.position[i]) ? 1 : 0;
  const glm::vec3 offsets[] = {{0, 0, 0}, {jitterM, 0, 0}, {-jitterM, 0, 0}, {0, 0, jitterM}, {0, 0, -jitterM}};
  for (const glm::vec3& off : offsets) {
    GBufferData moved = g;
    for (size_t i = 0; i < mask.size(); ++i)
      if (mask[i]) moved.position[i] += glm::vec4(off, 0.0f);
    const ReferenceResult ref = tracer.trace(moved, scene.light(), options);
    for (size_t i = 0; i < mask.size(); ++i)
      if (!ref.litMask[i] || ref.visibility[i] < 1.0f) mask[i] = 0;
  }
  return mask;
}

double acneFraction(const RenderResult& r, const std::vector<uint8_t>& unoccluded) {
  size_t n = 0, acne = 0;
  for (size_t i = 0; i < unoccluded.size(); ++i) {
    if (!unoccluded[i]) continue;
    ++n;
    acne += r.visibility[i] < kAcneV;
  }
  EXPECT_GT(n, 5000u) << "the camera must see unoccluded floor";
  return static_cast<double>(acne) / static_cast<double>(std::max<size_t>(n, 1));
}

}  // namespace

TEST(SecondDepth, GrazingPlaneHasNoAcneWithoutBias) {
  Scene scene = makeBuiltinScene("grazing");
  floorCasts(scene);
  const RenderResult second = renderScene(scene, "uniform", "second-depth", {}, kSize, kSize, kMapSize);
  // The contrast: one layer, compared without bias, on the same pixels.
  const RenderResult hard = renderScene(scene, "uniform", "hard", {{"hard.bias", "none"}}, kSize, kSize, kMapSize);
  constexpr float kJitterM = 0.05f;
  const std::vector<uint8_t> unoccluded = unoccludedFloor(scene, second.gbuffer, kJitterM);
  const double acneSecond = acneFraction(second, unoccluded), acneHard = acneFraction(hard, unoccluded);
  std::printf("grazing acne on unoccluded floor (Embree reference, %.2f m margin): second-depth %.3f%%, hard bias=none %.2f%%\n",
              kJitterM, 100.0 * acneSecond, 100.0 * acneHard);
  EXPECT_LE(acneSecond, 0.005);
  EXPECT_GE(acneHard, 0.2) << "the measure must see acne where there is some";
}

namespace {

// Floor pixels robustly in (occlusion 1) or out of (0) the hard shadow must read V = 0 / 1.
void checkProbes(const std::string& sceneName, float jitterM) {
  Scene scene = makeBuiltinScene(sceneName);
  floorCasts(scene);
  const RenderResult r = renderScene(scene, "uniform", "second-depth", {{"light.size", "0"}}, kSize, kSize, kMapSize);
  CasterTriangles tris(scene);
  std::mt19937 rng(11);
  std::uniform_int_distribution<size_t> pick(0, r.visibility.size() - 1);
  constexpr size_t kPerKind = 100;
  constexpr int kTries = 40000;
  size_t shadowed = 0, lit = 0, wrong = 0;
  for (int t = 0; t < kTries && (shadowed < kPerKind || lit < kPerKind); ++t) {
    const size_t i = pick(rng);
    if (!onFloor(r.gbuffer.position[i])) continue;
    const float occ = tris.robustOcclusion(scene, glm::vec3(r.gbuffer.position[i]), {0, 1, 0}, jitterM);
    if (occ == 1.0f && shadowed < kPerKind) {
      ++shadowed;
      wrong += r.visibility[i] > 0.0f;
    } else if (occ == 0.0f && lit < kPerKind) {
      ++lit;
      wrong += r.visibility[i] < 1.0f;
    }
  }
  std::printf("second-depth on %s: %zu shadowed + %zu lit probes, %zu wrong\n", sceneName.c_str(), shadowed, lit, wrong);
  EXPECT_GT(shadowed, 5u);
  EXPECT_GT(lit, 50u);
  EXPECT_EQ(wrong, 0u);
}

}  // namespace

TEST(SecondDepth, SpotLightProbes) { checkProbes("pen", 0.01f); }

TEST(SecondDepth, SunLightProbes) { checkProbes("boxes", 0.04f); }

TEST(SecondDepth, OpenMeshRendersAndStillCasts) {
  // A single-sided square (no second layer anywhere) over a floor (another open mesh).
  Scene scene;
  scene.name = "open sheet";
  addObject(scene, "floor", makePlane(6.0f, 6.0f), glm::vec3(0.7f));
  constexpr float kSheetHeightM = 1.0f, kSheetSizeM = 1.0f;
  const glm::mat4 sheetFromObject = glm::translate(glm::mat4(1.0f), {0.0f, kSheetHeightM, 0.0f}) *
                                    glm::rotate(glm::mat4(1.0f), 0.3f, {1, 0, 0});
  addObject(scene, "sheet", makePlane(kSheetSizeM, kSheetSizeM), {0.8f, 0.3f, 0.2f}, sheetFromObject);
  Light sun;
  sun.type = LightType::Directional;
  sun.direction = glm::normalize(glm::vec3(0.2f, -1.0f, 0.1f));
  scene.lights.push_back(sun);
  scene.camera.position = {0.0f, 4.0f, 4.0f};
  scene.camera.target = {0.0f, 0.3f, 0.0f};
  const RenderResult r = renderScene(scene, "uniform", "second-depth", {}, kSize, kSize, kMapSize);
  CasterTriangles tris(scene);
  size_t under = 0, underLit = 0, open = 0, openDark = 0, sheet = 0, sheetDark = 0;
  constexpr float kJitterM = 0.05f;
  for (size_t i = 0; i < r.visibility.size(); ++i) {
    const glm::vec4& p = r.gbuffer.position[i];
    if (p.w < 0.5f) continue;
    if (!onFloor(p)) {  // the sheet's lit side: its own single layer must not shadow it
      const glm::vec3 n(r.gbuffer.geoNormal[i]);
      if (glm::dot(n, -sun.direction) > 0.0f) {
        ++sheet;
        sheetDark += r.visibility[i] < kAcneV;
      }
      continue;
    }
    const float occ = tris.robustOcclusion(scene, glm::vec3(p), {0, 1, 0}, kJitterM);
    if (occ == 1.0f) { ++under; underLit += r.visibility[i] > 0.0f; }
    if (occ == 0.0f) { ++open; openDark += r.visibility[i] < kAcneV; }
  }
  std::printf("open sheet: %zu floor pixels under it (%zu lit), %zu open floor (%zu dark), %zu sheet (%zu dark)\n", under,
              underLit, open, openDark, sheet, sheetDark);
  EXPECT_GT(under, 500u);
  EXPECT_EQ(underLit, 0u);
  EXPECT_GT(open, 5000u);
  EXPECT_LE(static_cast<double>(openDark), 0.005 * static_cast<double>(open));
  EXPECT_GT(sheet, 500u);
  EXPECT_LE(static_cast<double>(sheetDark), 0.005 * static_cast<double>(sheet));
}

TEST(SecondDepth, MapStoresTheMidpointOfTwoPeeledLayers) {
  Scene scene = makeBuiltinScene("boxes");  // closed boxes and spheres: two layers where they are
  floorCasts(scene);
  const std::unique_ptr<Renderer> owned = makeTestRenderer(scene, "uniform", "second-depth", {}, 512);
  Renderer& renderer = *owned;
  RenderOptions o;
  o.width = o.height = 64;
  renderer.render(o);
  std::map<std::string, std::vector<float>> maps;
  for (const DebugImage& d : filterOf(renderer.shadows()).debugImages()) {
    std::vector<float>& m = maps[d.name];
    m.resize(static_cast<size_t>(d.texture->width()) * static_cast<size_t>(d.texture->height()));
    const bool depth = d.name != "shadow-map";  // the midpoint: a colour texture
    d.texture->read(depth ? GL_DEPTH_COMPONENT : GL_RED, GL_FLOAT, m.data(), m.size() * sizeof(float));
  }
  ASSERT_EQ(maps.size(), 3u);
  const std::vector<float>&first = maps["first-layer"], &second = maps["second-layer"], &mid = maps["shadow-map"];
  constexpr float kPeelEpsilonDepth = 1e-5f;  // passes/depth_peel.frag.glsl
  constexpr float kTolerance = 1e-6f;
  size_t twoLayers = 0, oneLayer = 0, bad = 0;
  for (size_t i = 0; i < first.size(); ++i) {
    if (first[i] >= 1.0f) continue;
    if (second[i] < 1.0f) {
      ++twoLayers;
      bad += second[i] <= first[i] + kPeelEpsilonDepth || std::abs(mid[i] - 0.5f * (first[i] + second[i])) > kTolerance;
    } else {
      ++oneLayer;  // the floor alone: first layer plus its own one-texel slope, never less
      bad += mid[i] < first[i] || mid[i] > 1.0f;
    }
  }
  std::printf("second-depth map: %zu texels with two layers, %zu with one, %zu inconsistent\n", twoLayers, oneLayer, bad);
  EXPECT_GT(twoLayers, 1000u);
  EXPECT_GT(oneLayer, 10000u);
  EXPECT_EQ(bad, 0u);
}
