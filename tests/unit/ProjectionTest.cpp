// Projections on the CPU: the practical split scheme, every projection mapping the visible part
// of the camera frustum into its clip volume (warps included), csm's snapping, and that every
// caster that can shadow a visible receiver lies inside the light's clip volume.
#include "ProjectionSamples.h"
#include "techniques/projections/CascadedProjection.h"
#include "techniques/projections/LightSpace.h"
#include "techniques/projections/LightSpacePerspectiveProjection.h"
#include "techniques/projections/PerspectiveProjection.h"
#include "techniques/projections/TrapezoidalProjection.h"

#include "techniques/Registry.h"
#include <penumbra/SceneIO.h>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include <array>
#include <bit>
#include <cmath>
#include <limits>
#include <random>

using namespace penumbra;
using penumbra::test::visibleSurfaceSamples;

namespace {

constexpr float kAspect = 16.0f / 9.0f;
constexpr int kMapSize = 1024;
constexpr float kClipEps = 1e-3f;  // NDC units (a map of 1024 texels: half a texel)

struct ClipCheck {
  bool inside = true;
  std::string what;
};

// Whether world point p lies in view v's clip volume: w > 0, NDC xy in [-1,1], the clip depth
// and the stored linear depth in [0,1].
ClipCheck insideClip(const ShadowView& v, const glm::vec3& p) {
  const glm::vec4 c = v.clipFromWorld * glm::vec4(p, 1.0f);
  const float depth = glm::dot(v.depthPlane, glm::vec4(p, 1.0f));
  ClipCheck r;
  if (!(c.w > 0.0f)) return {false, "w <= 0"};
  const glm::vec3 ndc = glm::vec3(c) / c.w;
  if (std::abs(ndc.x) > 1.0f + kClipEps || std::abs(ndc.y) > 1.0f + kClipEps) r = {false, "xy outside"};
  if (ndc.z < -kClipEps || ndc.z > 1.0f + kClipEps) r = {false, "clip z outside"};
  if (depth < -kClipEps || depth > 1.0f + kClipEps) r = {false, "linear depth outside"};
  if (!r.inside) r.what += " at ndc (" + std::to_string(ndc.x) + ", " + std::to_string(ndc.y) + ", " + std::to_string(ndc.z) + ") depth " + std::to_string(depth);
  return r;
}

// The body's vertices and random points inside it (convex combinations).
std::vector<glm::vec3> samplesIn(const std::vector<glm::vec3>& body, int count, uint32_t seed) {
  std::vector<glm::vec3> out = body;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (int i = 0; i < count && !body.empty(); ++i) {
    glm::vec3 sum(0.0f);
    float total = 0.0f;
    for (const glm::vec3& p : body) {
      const float w = std::pow(u(rng), 4.0f);  // skewed weights reach near the vertices too
      sum += w * p;
      total += w;
    }
    out.push_back(sum / total);
  }
  return out;
}

Scene sceneWithSun(const std::string& name, const glm::vec3& direction) {
  Scene s = makeBuiltinScene(name);
  s.lights.front().direction = glm::normalize(direction);
  return s;
}

// The camera depth interval each view must cover: csm's slices (with the blend band before each
// split), everything else the whole shadowed range.
std::pair<float, float> viewDepthRange(const LightFrusta& f, size_t i, const Camera& cam, const Scene& scene) {
  const float farM = std::max(shadowFarDistance(cam, scene.extent()), 2.0f * cam.nearM);
  if (f.views.size() == 1) return {cam.nearM, farM};
  const float a = i == 0 ? cam.nearM : f.views[i - 1].splitFarM - f.blendBandM;
  const float b = i + 1 == f.views.size() ? std::min(f.views[i].splitFarM, farM) : f.views[i].splitFarM;
  return {std::max(a, cam.nearM), b};
}

void expectFrustumInsideClip(const Scene& scene, const std::string& projection, const std::string& label) {
  auto p = makeProjection(projection);
  const LightFrusta f = p->computeFrusta(scene.camera, kAspect, scene.light(), scene.extent(), kMapSize);
  ASSERT_FALSE(f.views.empty());
  size_t checked = 0;
  for (size_t i = 0; i < f.views.size(); ++i) {
    const auto [a, b] = viewDepthRange(f, i, scene.camera, scene);
    const std::vector<glm::vec3> body = receiverBody(scene.camera, kAspect, a, b, scene.extent(), scene.light());
    if (body.empty()) continue;  // a cascade slice in front of the scene: nothing to cover
    ++checked;
    int outside = 0;
    std::string first;
    for (const glm::vec3& s : samplesIn(body, 400, 11)) {
      const ClipCheck c = insideClip(f.views[i], s);
      if (!c.inside && outside++ == 0) first = c.what;
    }
    EXPECT_EQ(outside, 0) << label << " " << projection << " view " << i << ": " << first;
  }
  EXPECT_GT(checked, 0u) << label << " " << projection;
}

}  // namespace

TEST(Projection, PracticalSplitsBlendUniformAndLogarithmic) {
  const float n = 0.1f, f = 1000.0f;
  const int count = 4;
  const std::vector<float> uni = practicalSplits(n, f, count, 0.0f);
  const std::vector<float> log = practicalSplits(n, f, count, 1.0f);
  const std::vector<float> mid = practicalSplits(n, f, count, 0.5f);
  ASSERT_EQ(uni.size(), 5u);
  EXPECT_FLOAT_EQ(uni.front(), n);
  EXPECT_FLOAT_EQ(uni.back(), f);
  EXPECT_FLOAT_EQ(log.back(), f);
  for (int i = 1; i <= count; ++i) {
    const size_t k = static_cast<size_t>(i);
    EXPECT_NEAR(uni[k] - uni[k - 1], (f - n) / count, 1e-3f);                      // equal lengths
    EXPECT_NEAR(log[k] / log[k - 1], std::pow(f / n, 1.0f / count), 1e-3f);         // equal ratios
    EXPECT_NEAR(mid[k], 0.5f * (uni[k] + log[k]), 1e-3f * mid[k]);                  // the λ blend
    EXPECT_GT(mid[k], mid[k - 1]);
  }
  EXPECT_NEAR(log[1], 0.1f * std::pow(1e4f, 0.25f), 1e-4f);  // 1 m: n·(f/n)^(1/4)
}

TEST(Projection, CsmViewsFollowTheSplits) {
  const Scene scene = makeBuiltinScene("city");
  auto p = makeProjection("csm");
  p->setParam("csm.cascades", 4.0f);
  p->setParam("csm.lambda", 0.9f);
  const LightFrusta f = p->computeFrusta(scene.camera, kAspect, scene.light(), scene.extent(), kMapSize);
  ASSERT_EQ(f.views.size(), 4u);
  const float farM = stableFarDistance(shadowFarDistance(scene.camera, scene.extent()));
  const std::vector<float> z = practicalSplits(scene.camera.nearM, farM, 4, 0.9f);
  for (size_t i = 0; i < 4; ++i) EXPECT_FLOAT_EQ(f.views[i].splitFarM, z[i + 1]);
  EXPECT_GT(f.blendBandM, 0.0f);
  EXPECT_LE(f.blendBandM, 0.5f * (z[1] - z[0]));
  // Finer cascades near the camera: each cascade's map covers more ground than the one before.
  for (size_t i = 1; i < 4; ++i) EXPECT_GT(f.views[i].extent.x, 1.5f * f.views[i - 1].extent.x);
}

// The visible part of the frustum (frustum ∩ scene bounds) for the fits that cover it as a
// whole. `uniform` fits each object's box clipped to the frustum instead, so empty space inside
// the scene's bounds may fall outside it; its guarantee is tested on surface points below.
TEST(Projection, EveryProjectionMapsTheVisibleFrustumIntoItsClipVolume) {
  for (const std::string& projection : projectionIds()) {
    // virtual: each level covers only the pixels whose footprint suits its texels (VirtualLevels below).
    if (projection == "uniform" || projection == "virtual") continue;
    expectFrustumInsideClip(makeBuiltinScene("boxes"), projection, "boxes");
    expectFrustumInsideClip(makeBuiltinScene("city"), projection, "city");
    expectFrustumInsideClip(makeBuiltinScene("pen"), projection, "pen (spot)");
    expectFrustumInsideClip(makeBuiltinScene("fence"), projection, "fence");
  }
}

TEST(Projection, WarpsMapTheFrustumIntoTheUnitCubeForEveryLightDirection) {
  Scene city = makeBuiltinScene("city");
  const glm::vec3 fwd = city.camera.forward();
  const glm::vec3 right = glm::normalize(glm::cross(fwd, glm::vec3(0, 1, 0)));
  // Light behind the camera, in front of it, from the side, from above, and grazing.
  const std::vector<std::pair<std::string, glm::vec3>> lights = {
      {"behind", fwd + glm::vec3(0, -0.6f, 0)},   {"in front", -fwd + glm::vec3(0, -0.6f, 0)},
      {"side", right + glm::vec3(0, -0.4f, 0)},   {"overhead", glm::vec3(0.1f, -1.0f, 0.05f)},
      {"low oblique", right + fwd + glm::vec3(0, -0.15f, 0)}};
  for (const auto& [label, dir] : lights) {
    const Scene s = sceneWithSun("city", dir);
    for (const char* projection : {"psm", "tsm", "lispsm", "csm"}) expectFrustumInsideClip(s, projection, "city, sun " + label);
    const Scene b = sceneWithSun("boxes", dir);
    for (const char* projection : {"psm", "tsm", "lispsm"}) expectFrustumInsideClip(b, projection, "boxes, sun " + label);
  }
}

TEST(Projection, PsmAndTsmWarpTheCityAndPsmClassifiesTheLight) {
  const Scene city = makeBuiltinScene("city");
  for (const char* id : {"psm", "tsm", "lispsm"}) {
    auto p = makeProjection(id);
    const LightFrusta f = p->computeFrusta(city.camera, kAspect, city.light(), city.extent(), 2048);
    ASSERT_EQ(f.views.size(), 1u);
    EXPECT_TRUE(f.views[0].warped) << id << " fell back to an unwarped map on the city";
  }
  Camera cam = city.camera;
  Light sun = city.light();
  sun.direction = glm::normalize(cam.forward() + glm::vec3(0, -0.5f, 0));
  EXPECT_EQ(psmLightCase(cam, sun), PsmLightCase::Behind);
  sun.direction = glm::normalize(-cam.forward() + glm::vec3(0, -0.5f, 0));
  EXPECT_EQ(psmLightCase(cam, sun), PsmLightCase::InFront);
  cam.target = cam.position + glm::vec3(0, 0, -1);
  sun.direction = glm::vec3(0, -1, 0);
  EXPECT_EQ(psmLightCase(cam, sun), PsmLightCase::Perpendicular);
}

TEST(Projection, TrapezoidRuleMapsTheFocusPointTo80Percent) {
  const float lambda = 2.0f, delta = 0.3f, m = 0.8f;
  const float eta = trapezoidApexDistance(lambda, delta, m);
  ASSERT_GT(eta, 0.0f);
  // The warp along the centre line: a point at distance a from the apex lands at y = A − B/a.
  const glm::mat4 w = trapezoidWarp({0, -1}, {0, 1}, eta, lambda, -1.0f, 1.0f);
  auto mapY = [&](float s) {  // s: distance past the top edge along u
    const glm::vec4 c = w * glm::vec4(0.0f, -1.0f + eta + s, 0.0f, 1.0f);
    return c.y / c.w;
  };
  EXPECT_NEAR(mapY(0.0f), -1.0f, 1e-5f);
  EXPECT_NEAR(mapY(lambda), 1.0f, 1e-5f);
  EXPECT_NEAR(0.5f * (mapY(delta) + 1.0f), m, 1e-5f);  // 80% of the way across the map
  EXPECT_TRUE(std::isinf(trapezoidApexDistance(lambda, 0.9f * lambda, m)));
}

// Stabilised cascades start at the nearest receiver rounded down to a quarter octave: never
// past the receiver, never before the camera's near plane, and the same for small moves.
TEST(Projection, StableNearDistance) {
  EXPECT_FLOAT_EQ(stableNearDistance(0.05f, 0.1f), 0.1f);
  EXPECT_FLOAT_EQ(stableNearDistance(64.0f, 0.1f), 64.0f);
  for (float d : {0.3f, 1.0f, 7.7f, 68.95f, 500.0f}) {
    const float s = stableNearDistance(d, 0.1f);
    EXPECT_LE(s, d);
    EXPECT_GT(s, d / std::exp2(0.25f) * 0.999f) << d;
    EXPECT_FLOAT_EQ(std::exp2(std::round(std::log2(s) * 4.0f) / 4.0f), s) << "on the ladder";
  }
  EXPECT_EQ(stableNearDistance(68.9f, 0.1f), stableNearDistance(69.0f, 0.1f));
}

// tsm's second centre line aims at the centroid of the receivers' area, which must not lean
// toward where the body's vertices happen to cluster (the near plane's four corners all project
// next to the camera's point).
TEST(Projection, HullAreaCentroid) {
  std::vector<glm::vec2> square = {{0, 0}, {2, 0}, {2, 2}, {0, 2}, {0.5f, 0.5f}, {1.5f, 0.2f}, {2, 2}};
  glm::vec2 c = hullAreaCentroid(square);
  EXPECT_NEAR(c.x, 1.0f, 1e-5f);
  EXPECT_NEAR(c.y, 1.0f, 1e-5f);
  // A triangle with many points crowded at one corner: the area centroid is the corners' mean.
  std::vector<glm::vec2> triangle = {{0, 0}, {3, 0}, {0, 3}};
  for (int i = 1; i <= 20; ++i) triangle.push_back({0.001f * static_cast<float>(i), 0.0005f * static_cast<float>(i)});
  c = hullAreaCentroid(triangle);
  EXPECT_NEAR(c.x, 1.0f, 1e-4f);
  EXPECT_NEAR(c.y, 1.0f, 1e-4f);
  // No area: the points' mean.
  c = hullAreaCentroid({{0, 0}, {1, 1}, {3, 3}});
  EXPECT_NEAR(c.x, 4.0f / 3.0f, 1e-5f);
  EXPECT_NEAR(c.y, 4.0f / 3.0f, 1e-5f);
  c = hullAreaCentroid({{5, -1}});
  EXPECT_NEAR(c.x, 5.0f, 1e-6f);
  EXPECT_NEAR(c.y, -1.0f, 1e-6f);
}

// The trapezoid spends the map on the receivers: its top and base edges touch their region and
// its sides are tangents to it, so the body spans the whole map both ways, less the margins. The
// margin along the centre line once grew with the apex distance: with the apex far away (little
// or no warp, `grazing`) the body filled 5 % of the map's height and shadows came out 11× blockier.
TEST(Projection, TrapezoidFillsTheMap) {
  constexpr float kMinSpanNdc = 1.9f;  // of 2; the margins take 2 · 2 texels of 1024
  for (const char* name : {"grazing", "boxes", "fence", "city"})
  for (const char* id : {"tsm", "lispsm"}) {
    const Scene scene = makeBuiltinScene(name);
    auto p = makeProjection(id);
    const ShadowView v = p->computeFrusta(scene.camera, kAspect, scene.light(), scene.extent(), kMapSize).views.at(0);
    const float farM = std::max(shadowFarDistance(scene.camera, scene.extent()), 2.0f * scene.camera.nearM);
    const std::vector<glm::vec3> body = receiverBody(scene.camera, kAspect, scene.camera.nearM, farM, scene.extent(), scene.light());
    ASSERT_FALSE(body.empty()) << name;
    glm::vec2 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
    for (const glm::vec3& q : body) {
      const glm::vec4 c = v.clipFromWorld * glm::vec4(q, 1.0f);
      ASSERT_GT(c.w, 0.0f) << name;
      lo = glm::min(lo, glm::vec2(c) / c.w);
      hi = glm::max(hi, glm::vec2(c) / c.w);
    }
    std::printf("%-8s %-6s: the receivers span %.3f x %.3f of the map's 2 x 2 (NDC)\n", name, id, hi.x - lo.x, hi.y - lo.y);
    EXPECT_GE(hi.x - lo.x, kMinSpanNdc) << name;
    EXPECT_GE(hi.y - lo.y, kMinSpanNdc) << name;
  }
}

TEST(Projection, CsmSnappingKeepsTheMatrixForSubTexelMoves) {
  const Scene scene = makeBuiltinScene("city");
  auto p = makeProjection("csm");
  const LightFrusta f0 = p->computeFrusta(scene.camera, kAspect, scene.light(), scene.extent(), kMapSize);
  const glm::mat4 worldFromLight = glm::inverse(f0.views[0].viewFromWorld);
  const glm::vec3 lightX = glm::vec3(worldFromLight[0]), lightZ = glm::vec3(worldFromLight[2]);
  for (size_t v = 0; v < f0.views.size(); ++v) {
    const float texelM = f0.views[v].extent.x / static_cast<float>(kMapSize);
    const float ndcPerTexel = 2.0f / static_cast<float>(kMapSize);
    // Walk one texel along the light's x axis in 64 steps: the snapped matrix may change once
    // (crossing a texel boundary), only in its translation, and then by exactly one texel.
    int changes = 0;
    glm::mat4 previous = f0.views[v].clipFromWorld;
    for (int k = 1; k < 64; ++k) {
      Camera c = scene.camera;
      const glm::vec3 move = lightX * (texelM * static_cast<float>(k) / 64.0f);
      c.position += move;
      c.target += move;
      const glm::mat4 m = p->computeFrusta(c, kAspect, scene.light(), scene.extent(), kMapSize).views[v].clipFromWorld;
      if (m == previous) continue;
      ++changes;
      for (int col = 0; col < 3; ++col) EXPECT_EQ(m[col], previous[col]) << "view " << v << ": rotation/scale changed";
      EXPECT_NEAR(std::abs(m[3].x - previous[3].x) / ndcPerTexel, 1.0f, 1e-2f) << "view " << v;
      EXPECT_NEAR(m[3].y, previous[3].y, 1e-2f * ndcPerTexel) << "view " << v;
      previous = m;
    }
    EXPECT_LE(changes, 1) << "view " << v;
    // Moving along the light's own axis changes nothing at all.
    Camera c = scene.camera;
    c.position += lightZ * (3.7f * texelM);
    c.target += lightZ * (3.7f * texelM);
    EXPECT_EQ(p->computeFrusta(c, kAspect, scene.light(), scene.extent(), kMapSize).views[v].clipFromWorld, f0.views[v].clipFromWorld);
  }
  // Without stabilisation the same sub-texel moves change the matrix nearly every time.
  p->setParam("csm.stabilize", 0.0f);
  const LightFrusta u0 = p->computeFrusta(scene.camera, kAspect, scene.light(), scene.extent(), kMapSize);
  int unstableChanges = 0;
  for (int k = 1; k < 16; ++k) {
    Camera c = scene.camera;
    const glm::vec3 move = lightX * (0.01f * static_cast<float>(k));
    c.position += move;
    c.target += move;
    if (p->computeFrusta(c, kAspect, scene.light(), scene.extent(), kMapSize).views[0].clipFromWorld != u0.views[0].clipFromWorld) ++unstableChanges;
  }
  EXPECT_GE(unstableChanges, 12);
}

namespace {

// World-space triangles (three points each) of the scene's shadow casters.
std::vector<glm::vec3> casterTriangles(const Scene& scene) {
  std::vector<glm::vec3> tri;
  for (const Object& o : scene.objects) {
    if (!o.castsShadow) continue;
    const Mesh& m = scene.meshes[o.mesh];
    for (uint32_t i : m.indices) tri.push_back(glm::vec3(o.worldFromObject * glm::vec4(m.positions[i], 1.0f)));
  }
  return tri;
}

// Every point where a caster triangle crosses the segment from receiver r to the light (the
// points that can shadow r; Möller–Trumbore, every hit).
std::vector<glm::vec3> occluderHits(const std::vector<glm::vec3>& tri, const Light& light, const glm::vec3& r) {
  glm::vec3 dir = -glm::normalize(light.direction);
  float tMax = 1e30f;
  if (light.type == LightType::Spot) {
    tMax = glm::length(light.position - r);
    dir = (light.position - r) / tMax;
  }
  std::vector<glm::vec3> hits;
  for (size_t i = 0; i + 2 < tri.size(); i += 3) {
    const glm::vec3 e1 = tri[i + 1] - tri[i], e2 = tri[i + 2] - tri[i], pv = glm::cross(dir, e2);
    const float det = glm::dot(e1, pv);
    if (std::abs(det) < 1e-12f) continue;
    const glm::vec3 s = r - tri[i];
    const float u = glm::dot(s, pv) / det;
    if (u < 0.0f || u > 1.0f) continue;
    const glm::vec3 q = glm::cross(s, e1);
    const float v = glm::dot(dir, q) / det;
    if (v < 0.0f || u + v > 1.0f) continue;
    const float t = glm::dot(e2, q) / det;
    if (t <= 1e-4f || t >= tMax) continue;
    hits.push_back(r + dir * t);
  }
  return hits;
}

// Every caster-triangle hit between each receiver sample and the light must lie inside the view
// that the receiver is looked up in (csm: its cascade and, in the blend band, the next one).
void expectCastersInsideClip(const Scene& scene, const std::string& projection) {
  auto p = makeProjection(projection);
  const LightFrusta f = p->computeFrusta(scene.camera, kAspect, scene.light(), scene.extent(), kMapSize);
  const std::vector<glm::vec3> tri = casterTriangles(scene);
  const glm::mat4 view = scene.camera.viewFromWorld();
  int hits = 0, outside = 0;
  std::string first;
  for (const glm::vec3& r : visibleSurfaceSamples(scene, kAspect, 1000, 5)) {
    const float depth = -(view * glm::vec4(r, 1.0f)).z;
    std::vector<size_t> views;
    for (size_t i = 0; i < f.views.size(); ++i) {
      const float a = i == 0 ? 0.0f : f.views[i - 1].splitFarM - f.blendBandM;
      const float b = i + 1 == f.views.size() ? 1e30f : f.views[i].splitFarM;
      if (depth >= a && depth <= b) views.push_back(i);
    }
    for (const glm::vec3& hit : occluderHits(tri, scene.light(), r)) {
      ++hits;
      for (size_t vi : views) {
        const ClipCheck c = insideClip(f.views[vi], hit);
        if (!c.inside && outside++ == 0) first = "view " + std::to_string(vi) + ": " + c.what;
      }
    }
  }
  EXPECT_GT(hits, 10) << scene.name << ": the test needs casters between receivers and the light";
  EXPECT_EQ(outside, 0) << scene.name << " " << projection << ": " << first;
}

}  // namespace

TEST(Projection, UniformFrustumHoldsEveryCasterOfAVisibleReceiver) {
  for (const char* name : {"boxes", "fence", "pen", "grazing"}) expectCastersInsideClip(makeBuiltinScene(name), "uniform");
}

TEST(Projection, LargeViewProjectionsHoldEveryCasterOfAVisibleReceiver) {
  for (const char* projection : {"csm", "psm", "tsm", "lispsm"})
    for (const char* name : {"boxes", "fence", "pen"}) expectCastersInsideClip(makeBuiltinScene(name), projection);
}

// A spot light hanging inside the visible region: in PPS it lies inside the body of receivers
// and casters, so no projection from it can hold them all. PSM must notice and fall back to the
// unwarped fit, which still covers the view.
TEST(Projection, PsmFallsBackWhenTheWarpDegenerates) {
  Scene scene = makeBuiltinScene("boxes");
  Light spot;
  spot.type = LightType::Spot;
  spot.position = {0.0f, 0.9f, 0.8f};  // between the boxes, in front of the camera
  spot.direction = glm::normalize(glm::vec3(0.1f, -1.0f, 0.05f));
  spot.coneAngleRad = 1.2f;
  scene.lights = {spot};
  const float farM = shadowFarDistance(scene.camera, scene.extent());
  const std::vector<glm::vec3> body = receiverBody(scene.camera, kAspect, scene.camera.nearM, farM, scene.extent(), spot);
  const std::vector<glm::vec3> casters = casterExtrusion(body, spot, scene.casterBounds());
  ASSERT_FALSE(body.empty());
  EXPECT_TRUE(computePsmWarp(scene.camera, spot, body, casters, scene.bounds(), 1.0f, 0.0f).degenerate);
  auto p = makeProjection("psm");
  const LightFrusta f = p->computeFrusta(scene.camera, kAspect, spot, scene.extent(), kMapSize);
  ASSERT_EQ(f.views.size(), 1u);
  EXPECT_FALSE(f.views[0].warped);
  expectFrustumInsideClip(scene, "psm", "boxes, spot inside the view");
}

namespace {

// What a single light view must hold, measured in that view's light space from the scene
// itself: the visible receivers (surface samples inside the camera frustum) and every caster
// point between one of them and the light.
struct NeededFit {
  glm::vec2 extent{0.0f};  ///< as ShadowView::extent: metres (ortho) or 2·tan(half angle) (perspective)
  float nearM = 1e30f, farM = 0.0f;
};

NeededFit measureNeededFit(const Scene& scene, const ShadowView& v) {
  const std::vector<glm::vec3> tri = casterTriangles(scene);
  NeededFit n;
  Aabb xy;
  float widestTan = 0.0f;
  for (const glm::vec3& r : visibleSurfaceSamples(scene, kAspect, 4000, 17)) {
    const glm::vec3 ls = glm::vec3(v.viewFromWorld * glm::vec4(r, 1.0f));
    xy.extend(ls);
    const float tanR = std::max(std::abs(ls.x), std::abs(ls.y)) / -ls.z;
    if (v.perspective && !(ls.z < 0.0f && tanR <= std::tan(scene.light().coneAngleRad))) continue;  // unlit: no shadow needed
    widestTan = std::max(widestTan, std::max(std::abs(ls.x), std::abs(ls.y)) / -ls.z);
    n.nearM = std::min(n.nearM, -ls.z);
    n.farM = std::max(n.farM, -ls.z);
    for (const glm::vec3& hit : occluderHits(tri, scene.light(), r))
      n.nearM = std::min(n.nearM, -(v.viewFromWorld * glm::vec4(hit, 1.0f)).z);
  }
  n.extent = v.perspective ? glm::vec2(2.0f * widestTan) : glm::vec2(xy.size());
  return n;
}

// A small box and ball on a 60 m ground, seen from close by: a fit to the whole world would be
// tens of times too large.
Scene smallCornerOfALargeWorld() {
  Scene s;
  s.name = "custom: small corner of a large world";
  addObject(s, "ground", makePlane(60.0f, 60.0f), {0.6f, 0.6f, 0.6f});
  addObject(s, "box", makeBox({0.6f, 0.6f, 0.6f}), {0.8f, 0.3f, 0.3f}, glm::translate(glm::mat4(1.0f), {-8.0f, 0.3f, -5.0f}));
  addObject(s, "ball", makeSphere(0.3f), {0.3f, 0.3f, 0.8f}, glm::translate(glm::mat4(1.0f), {-7.0f, 0.3f, -5.5f}));
  Light sun;
  sun.type = LightType::Directional;
  sun.direction = glm::normalize(glm::vec3(0.4f, -1.0f, 0.3f));
  s.lights = {sun};
  s.camera.position = {-7.0f, 4.0f, -3.0f};
  s.camera.target = {-7.5f, 0.3f, -5.2f};
  return s;
}

}  // namespace

// "Tight": the uniform fit is not much larger than what the scene itself says it must hold (the
// visible receivers and the caster points between them and the light, sampled). The slack covers
// object boxes against their surfaces, the margin texels and sampling; a fit to the whole scene
// (or, before the fit clipped boxes to the frustum itself, to the frustum's bounding box) fails.
TEST(Projection, UniformFitIsTight) {
  constexpr float kExtentSlack = 1.10f;  // ortho metres or spot 2·tan(half angle), per axis
  constexpr float kDepthSlack = 1.40f;   // far − near; a spot's far comes from box corners
  std::vector<Scene> scenes = {makeBuiltinScene("boxes"), makeBuiltinScene("grazing"), makeBuiltinScene("fence"),
                               makeBuiltinScene("pen"), smallCornerOfALargeWorld()};
  for (const Scene& scene : scenes) {
    auto p = makeProjection("uniform");
    const ShadowView v = p->computeFrusta(scene.camera, kAspect, scene.light(), scene.extent(), kMapSize).views.at(0);
    const NeededFit need = measureNeededFit(scene, v);
    ASSERT_GT(need.farM, need.nearM) << scene.name;
    const glm::vec2 extentRatio = v.extent / need.extent;
    const float depthRatio = (v.farM - v.nearM) / (need.farM - need.nearM);
    std::printf("%-38s extent %.3f x %.3f / needed %.3f x %.3f = %.3f x %.3f; depth [%.3f, %.3f] / needed [%.3f, %.3f] = %.3f\n",
                scene.name.c_str(), v.extent.x, v.extent.y, need.extent.x, need.extent.y, extentRatio.x, extentRatio.y,
                v.nearM, v.farM, need.nearM, need.farM, depthRatio);
    EXPECT_LE(extentRatio.x, kExtentSlack) << scene.name;
    EXPECT_LE(extentRatio.y, kExtentSlack) << scene.name;
    EXPECT_LE(depthRatio, kDepthSlack) << scene.name;
    // The measure can fail: a frustum around the whole scene would exceed one of the slacks.
    const Aabb world = scene.bounds().transformed(v.viewFromWorld);
    const float worldDepthRatio = world.size().z / (need.farM - need.nearM);
    const glm::vec2 worldExtentRatio = v.perspective ? glm::vec2(0.0f) : glm::vec2(world.size()) / need.extent;
    EXPECT_TRUE(worldDepthRatio > kDepthSlack || std::max(worldExtentRatio.x, worldExtentRatio.y) > kExtentSlack)
        << scene.name << ": the whole scene is no larger than the fit; pick a scene where tightness matters";
  }
}

// ---- lispsm -------------------------------------------------------------------------------

// Wimmer et al.'s optimum: with the view perpendicular to the light, n_opt = z_n + √(z_n·z_f)
// (P's depth d is the view's, z_f = z_n + d); at any other angle the camera depths of P's planes
// along its axis are z0 and z0 + d·sin γ and n_opt is divided by sin γ; along the light, infinite.
TEST(Projection, LispsmOptimalNearFollowsWimmer) {
  EXPECT_NEAR(lispsmOptimalNear(1.0f, 99.0f, 1.0f), 1.0f + 10.0f, 1e-4f);
  EXPECT_NEAR(lispsmOptimalNear(0.5f, 49.5f, 1.0f), 0.5f + 5.0f, 1e-4f);
  const float s = std::sin(0.3f);
  EXPECT_NEAR(lispsmOptimalNear(2.0f, 40.0f, s), (2.0f + std::sqrt(2.0f * (2.0f + 40.0f * s))) / s, 1e-3f);
  EXPECT_TRUE(std::isinf(lispsmOptimalNear(1.0f, 10.0f, 0.0f)));
  // Monotonic: the closer the view to the light, the farther P's centre (the weaker the warp).
  float previous = 0.0f;
  for (float g : {1.5f, 1.0f, 0.5f, 0.1f, 0.01f}) {
    const float n = lispsmOptimalNear(1.0f, 100.0f, std::sin(g));
    EXPECT_GT(n, previous) << g;
    previous = n;
  }
}

namespace {

// What the lispsm map does along P's axis, measured from its matrix alone: the change of the map's
// coordinate along the axis per metre at P's near plane over that at its far plane. P's perspective
// y = A − B/a (a: distance from P's centre) gives ((n + d) / n)².
struct LispsmMeasure {
  double nearOverFarRate = 0.0;
  double n = 0.0, d = 0.0;  ///< n_opt and d, computed here from the scene as Wimmer et al. define them
  bool warped = false;
};

LispsmMeasure measureLispsm(const Scene& scene, int mapSize = kMapSize) {
  auto p = makeProjection("lispsm");
  const ShadowView v = p->computeFrusta(scene.camera, kAspect, scene.light(), scene.extent(), mapSize).views.at(0);
  LispsmMeasure m;
  m.warped = v.warped;
  const Camera& cam = scene.camera;
  const float farM = std::max(shadowFarDistance(cam, scene.extent()), 2.0f * cam.nearM);
  const std::vector<glm::vec3> body = receiverBody(cam, kAspect, cam.nearM, farM, scene.extent(), scene.light());
  // P's axis in the world: the view direction without its part along the light.
  const glm::vec3 l = glm::normalize(scene.light().direction), fwd = cam.forward();
  const double sinGamma = glm::length(glm::cross(fwd, l));
  const glm::vec3 axis = glm::normalize(fwd - glm::dot(fwd, l) * l);
  double sMin = 1e30, sMax = -1e30, z0 = 1e30;
  for (const glm::vec3& q : body) {
    sMin = std::min(sMin, static_cast<double>(glm::dot(q - cam.position, axis)));
    sMax = std::max(sMax, static_cast<double>(glm::dot(q - cam.position, axis)));
    z0 = std::min(z0, static_cast<double>(glm::dot(q - cam.position, fwd)));
  }
  z0 = std::max(z0, static_cast<double>(cam.nearM));
  m.d = sMax - sMin;
  m.n = (z0 + std::sqrt(z0 * (z0 + m.d * sinGamma))) / sinGamma;
  // The map's coordinate along P's axis: the warp's y (P's axis is the map's y).
  const auto mapY = [&](double s) {
    const glm::dvec4 c = glm::dmat4(v.clipFromWorld) * glm::dvec4(glm::dvec3(cam.position) + glm::dvec3(axis) * s, 1.0);
    return c.y / c.w;
  };
  const double h = 1e-3 * m.d;
  const double rateNear = (mapY(sMin + h) - mapY(sMin - h)) / (2.0 * h);
  const double rateFar = (mapY(sMax + h) - mapY(sMax - h)) / (2.0 * h);
  m.nearOverFarRate = rateNear / rateFar;
  return m;
}

}  // namespace

// The map itself carries Wimmer et al.'s warp parameter: along P's axis its texels grow from the
// near plane to the far plane by ((n_opt + d) / n_opt)², n_opt from the camera/light angle.
TEST(Projection, LispsmWarpsWithTheOptimalNear) {
  for (const char* name : {"city", "boxes", "fence", "grazing"}) {
    const LispsmMeasure m = measureLispsm(makeBuiltinScene(name));
    ASSERT_TRUE(m.warped) << name;
    const double expected = std::pow((m.n + m.d) / m.n, 2.0);
    std::printf("%-8s lispsm: n_opt %.2f m, d %.2f m: texels grow x%.3f along P's axis (expected x%.3f)\n", name, m.n, m.d,
                m.nearOverFarRate, expected);
    EXPECT_NEAR(m.nearOverFarRate / expected, 1.0, 0.01) << name;
  }
}

// View and light along one line (the sun straight behind the camera, or straight ahead): no
// warp helps, n_opt is infinite and lispsm is `uniform`'s unwarped fit. Approaching that line, the
// warp weakens continuously toward it (n_opt grows as 1/sin γ: slowly, x1.6 at 10⁻⁴ rad on city).
TEST(Projection, LispsmFallsBackToUniformAlongTheView) {
  const Scene city = makeBuiltinScene("city");
  const glm::vec3 fwd = city.camera.forward();
  for (const glm::vec3& dir : {fwd, -fwd}) {
    const Scene s = sceneWithSun("city", dir);
    auto p = makeProjection("lispsm");
    const ShadowView v = p->computeFrusta(s.camera, kAspect, s.light(), s.extent(), kMapSize).views.at(0);
    EXPECT_FALSE(v.warped) << "sun along " << (dir == fwd ? "the view" : "the view, toward the camera");
    expectFrustumInsideClip(s, "lispsm", "city, sun along the view");
  }
  const glm::vec3 right = glm::normalize(glm::cross(fwd, glm::vec3(0, 1, 0)));
  double previous = 1e30;
  for (float angle : {0.5f, 0.1f, 0.01f, 1e-3f, 1e-4f, 1e-5f}) {
    const Scene s = sceneWithSun("city", std::cos(angle) * fwd + std::sin(angle) * right);
    const LispsmMeasure m = measureLispsm(s);
    ASSERT_TRUE(m.warped) << angle;
    std::printf("sun %.4f rad from the view: texels grow x%.3f along P's axis\n", angle, m.nearOverFarRate);
    EXPECT_LT(m.nearOverFarRate, previous) << angle;
    previous = m.nearOverFarRate;
  }
  EXPECT_LT(previous, 1.1);  // 10⁻⁵ rad from the view: all but uniform
}

// virtual's clipmap: levels twice as wide as the one before, each around the camera with its corner
// on its page grid, all with the light's rotation and one depth plane; the last level holds every
// receiver the camera sees (a pixel beyond a level reads a coarser one).
TEST(Projection, VirtualLevelsDoubleAroundTheCameraOnTheirPageGrids) {
  const Scene city = makeBuiltinScene("city");
  auto p = makeProjection("virtual");
  const LightFrusta f = p->computeFrusta(city.camera, kAspect, city.light(), city.extent(), kMapSize);
  const int pagesPerSide = p->paramInt("virtual.virtualSize") / p->paramInt("virtual.pageSize");
  ASSERT_EQ(f.views.size(), static_cast<size_t>(p->paramInt("virtual.levels")));
  for (size_t i = 0; i < f.views.size(); ++i) {
    const ShadowView& v = f.views[i];
    EXPECT_FLOAT_EQ(v.extent.x, p->param("virtual.firstLevelM") * std::exp2(static_cast<float>(i)));
    EXPECT_EQ(v.viewFromWorld, f.views[0].viewFromWorld);
    EXPECT_EQ(v.depthPlane, f.views[0].depthPlane);
    const glm::vec4 camera = v.clipFromWorld * glm::vec4(city.camera.position, 1.0f);
    EXPECT_LT(std::abs(camera.x), 1.0f) << "level " << i;
    EXPECT_LT(std::abs(camera.y), 1.0f) << "level " << i;
    // The corner (clip −1) lies on the page grid: a whole number of pages from the light-space origin.
    const double pageM = static_cast<double>(v.extent.x) / pagesPerSide;
    const double corner = -(static_cast<double>(v.clipFromWorld[3].x) + 1.0) * 0.5 * v.extent.x;
    EXPECT_NEAR(corner / pageM, std::round(corner / pageM), 1e-3) << "level " << i;
  }
  const std::vector<glm::vec3> body = receiverBody(city.camera, kAspect, city.camera.nearM, city.camera.farM, city.extent(), city.light());
  ASSERT_FALSE(body.empty());
  for (const glm::vec3& s : samplesIn(body, 400, 11)) EXPECT_TRUE(insideClip(f.views.back(), s).inside);
}

// virtual's spot: mips of one perspective view from the light (level l: the view over the corner
// [0, 2^-l]² of its square, i.e. uv_l = 2^-l · uv_0), as many as halve the view down to one page;
// level 0 holds every point of the scene inside the light's cone, and a camera that moves leaves
// the levels as they are (pages stay valid).
TEST(Projection, VirtualSpotLevelsAreMipsOfOneViewThatStaysWhenTheCameraMoves) {
  const Scene pen = makeBuiltinScene("pen");
  auto p = makeProjection("virtual");
  const LightFrusta f = p->computeFrusta(pen.camera, kAspect, pen.light(), pen.extent(), kMapSize);
  const int pagesPerSide = p->paramInt("virtual.virtualSize") / p->paramInt("virtual.pageSize");
  ASSERT_EQ(f.views.size(), static_cast<size_t>(std::countr_zero(static_cast<unsigned>(pagesPerSide)) + 1));
  Camera moved = pen.camera;
  moved.position += glm::vec3(0.7f, 0.2f, -0.4f);
  const LightFrusta g = p->computeFrusta(moved, kAspect, pen.light(), pen.extent(), kMapSize);
  const auto uv = [](const ShadowView& v, const glm::vec3& w) {
    const glm::vec4 c = v.clipFromWorld * glm::vec4(w, 1.0f);
    return glm::vec2(c) / c.w * 0.5f + 0.5f;
  };
  int inCone = 0;
  const std::array<glm::vec3, 8> corners = pen.extent().bounds().corners();
  for (const glm::vec3& s : samplesIn(std::vector<glm::vec3>(corners.begin(), corners.end()), 400, 5)) {
    const glm::vec3 d = glm::normalize(s - pen.light().position);
    if (glm::dot(d, pen.light().direction) < std::cos(pen.light().coneAngleRad)) continue;
    ++inCone;
    const glm::vec2 uv0 = uv(f.views[0], s);
    EXPECT_TRUE(insideClip(f.views[0], s).inside);
    for (size_t l = 0; l < f.views.size(); ++l) {
      EXPECT_TRUE(f.views[l].perspective);
      EXPECT_EQ(f.views[l].depthPlane, f.views[0].depthPlane);
      const glm::vec2 uvL = uv(f.views[l], s);
      EXPECT_NEAR(uvL.x, uv0.x * std::exp2(-static_cast<float>(l)), 1e-5f) << "level " << l;
      EXPECT_NEAR(uvL.y, uv0.y * std::exp2(-static_cast<float>(l)), 1e-5f) << "level " << l;
      EXPECT_EQ(g.views[l].clipFromWorld, f.views[l].clipFromWorld) << "level " << l;
    }
  }
  EXPECT_GT(inCone, 50);
}

// A point light under virtual: its six cube faces (+X, −X, +Y, −Y, +Z, −Z, the shaders' cubeFace
// order), each in mips as a spot's view, face after face. A point of the scene lies in the face of
// its dominant direction from the light, at uv_l = 2^-l uv_0 in that face's level l, and the
// faces stay while the camera moves.
TEST(Projection, VirtualPointLightIsSixFacesInMipsThatStayWhenTheCameraMoves) {
  const Scene room = makeBuiltinScene("room");
  ASSERT_EQ(room.light().type, LightType::Point);
  auto p = makeProjection("virtual");
  EXPECT_EQ(p->incompatibility(room.light()), "");
  const LightFrusta f = p->computeFrusta(room.camera, kAspect, room.light(), room.extent(), kMapSize);
  const int pagesPerSide = p->paramInt("virtual.virtualSize") / p->paramInt("virtual.pageSize");
  const size_t levels = static_cast<size_t>(std::countr_zero(static_cast<unsigned>(pagesPerSide)) + 1);
  ASSERT_EQ(f.views.size(), 6 * levels);
  Camera moved = room.camera;
  moved.position += glm::vec3(-0.7f, 0.2f, -0.4f);
  const LightFrusta g = p->computeFrusta(moved, kAspect, room.light(), room.extent(), kMapSize);
  const auto uv = [](const ShadowView& v, const glm::vec3& w) {
    const glm::vec4 c = v.clipFromWorld * glm::vec4(w, 1.0f);
    return glm::vec2(c) / c.w * 0.5f + 0.5f;
  };
  std::array<int, 6> perFace{};
  const std::array<glm::vec3, 8> corners = room.extent().bounds().corners();
  for (const glm::vec3& s : samplesIn(std::vector<glm::vec3>(corners.begin(), corners.end()), 600, 7)) {
    const glm::vec3 d = s - room.light().position, a = glm::abs(d);
    if (glm::length(d) < 0.2f) continue;
    const int face = a.x >= a.y && a.x >= a.z ? (d.x > 0.0f ? 0 : 1) : a.y >= a.z ? (d.y > 0.0f ? 2 : 3) : (d.z > 0.0f ? 4 : 5);
    ++perFace[static_cast<size_t>(face)];
    const ShadowView& base = f.views[static_cast<size_t>(face) * levels];
    EXPECT_TRUE(insideClip(base, s).inside) << "face " << face;
    const glm::vec2 uv0 = uv(base, s);
    for (size_t l = 0; l < levels; ++l) {
      const size_t view = static_cast<size_t>(face) * levels + l;
      EXPECT_TRUE(f.views[view].perspective);
      EXPECT_EQ(f.views[view].depthPlane, base.depthPlane);
      const glm::vec2 uvL = uv(f.views[view], s);
      EXPECT_NEAR(uvL.x, uv0.x * std::exp2(-static_cast<float>(l)), 1e-5f) << "face " << face << " level " << l;
      EXPECT_NEAR(uvL.y, uv0.y * std::exp2(-static_cast<float>(l)), 1e-5f) << "face " << face << " level " << l;
      EXPECT_EQ(g.views[view].clipFromWorld, f.views[view].clipFromWorld) << "face " << face << " level " << l;
    }
  }
  for (int face = 0; face < 6; ++face) EXPECT_GT(perFace[static_cast<size_t>(face)], 10) << "face " << face;
}
