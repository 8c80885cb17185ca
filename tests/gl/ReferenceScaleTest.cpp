// The ruler at every scale (issue 18), on real G-buffers: the rasteriser's positions lie within
// the tolerance the reference assumes and name the triangle Embree numbers the same way; the same
// caster on a 10 m and on a 2 km ground has the same truth; a plane 10 km out under a grazing sun
// has no acne in the truth. No expected value involves a ray offset.
#include "GlFixture.h"
#include "ReferenceKnownAnswers.h"

#include <penumbra/Reference.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

using namespace penumbra;
using namespace penumbra::test;

namespace {

constexpr int kSize = 256;
constexpr int kMapSize = 1024;  // the technique's map: only the G-buffer is used here
constexpr int kSoftSamples = 64;
constexpr float kNoiseDeltaV = 0.1f;  // the bound on |ΔV| between the two grounds
// A pixel's interpolated position lies inside its triangle up to rounding: barycentrics down to
// this (in double, from the float vertices) count as inside. Measured on llvmpipe: −0.0022 (a
// 35 m triangle of city seen edge-on, 8 cm); a wrong triangle id is off by far more.
constexpr double kInsideBarycentric = -0.01;

float floatSpacing(float x) { return std::nextafter(x, std::numeric_limits<float>::infinity()) - x; }

struct PositionError {
  double worstUlps = 0.0;  // distance to the triangle's plane over the float spacing of its magnitude
  size_t pixels = 0, outside = 0;
};

/// Every covered pixel against the triangle its G-buffer names, in double from the float scene:
/// its distance to the triangle's plane, in float spacings of the largest magnitude it was made
/// from (ReferenceTracer's rule), and whether it lies inside the triangle.
PositionError positionError(const Scene& scene, const GBufferData& g) {
  PositionError e;
  for (size_t i = 0; i < g.position.size(); ++i) {
    if (!g.covered(i)) continue;
    EXPECT_GT(g.triangle[i].x, 0u) << "covered pixel " << i << " names no triangle";
    if (g.triangle[i].x == 0) continue;
    const Object& object = scene.objects[g.triangle[i].x - 1];
    const Mesh& mesh = scene.meshes[object.mesh];
    const glm::dmat4 worldFromObject(object.worldFromObject);
    glm::dvec3 v[3];
    float magnitude = 0.0f;
    for (int k = 0; k < 3; ++k) {
      const glm::vec3 local = mesh.positions[mesh.indices[3 * g.triangle[i].y + static_cast<uint32_t>(k)]];
      v[k] = glm::dvec3(worldFromObject * glm::dvec4(glm::dvec3(local), 1.0));
      glm::mat4 absolute;
      for (int c = 0; c < 4; ++c) absolute[c] = glm::abs(object.worldFromObject[c]);
      const glm::vec4 terms = absolute * glm::vec4(glm::abs(local), 1.0f);
      magnitude = std::max({magnitude, terms.x, terms.y, terms.z});
    }
    const glm::dvec3 p(g.position[i]);
    magnitude = std::max({magnitude, std::abs(g.position[i].x), std::abs(g.position[i].y), std::abs(g.position[i].z)});
    const glm::dvec3 cross = glm::cross(v[1] - v[0], v[2] - v[0]);
    const glm::dvec3 n = glm::normalize(cross);
    e.worstUlps = std::max(e.worstUlps, std::abs(glm::dot(p - v[0], n)) / floatSpacing(magnitude));
    // Barycentrics of p's projection: signed areas over the whole.
    const double area = glm::dot(cross, n);
    bool inside = true;
    for (int k = 0; k < 3; ++k)
      inside &= glm::dot(glm::cross(v[(k + 1) % 3] - p, v[(k + 2) % 3] - p), n) / area >= kInsideBarycentric;
    e.outside += !inside;
    ++e.pixels;
  }
  return e;
}

Scene loadTestScene(const std::string& name) { return loadScene(std::string(PENUMBRA_TEST_DATA) + "/scenes/" + name); }

}  // namespace

// The assumption behind kPositionToleranceUlps, measured on this machine's rasteriser, and the
// triangle ids checked against Embree's numbering (a pixel lies inside the triangle it names).
TEST(ReferenceScale, GBufferPositionsLieWithinTheToleranceOfTheirTriangle) {
  for (const Scene& scene : {grazingPlaneFarOut(0.0f), loadTestScene("box-on-2km-ground.json"), makeBuiltinScene("city")}) {
    const RenderResult r = renderScene(scene, "uniform", "hard", {}, kSize, kSize, kMapSize);
    const PositionError e = positionError(scene, r.gbuffer);
    std::printf("%s: %zu pixels, farthest %.2f float spacings off their triangle's plane (tolerance %.0f); %zu outside it\n",
                scene.name.c_str(), e.pixels, e.worstUlps, kPositionToleranceUlps, e.outside);
    EXPECT_GT(e.pixels, static_cast<size_t>(kSize * kSize / 4)) << scene.name;
    EXPECT_LE(e.worstUlps, kPositionToleranceUlps) << scene.name;
    EXPECT_EQ(e.outside, 0u) << scene.name << ": the G-buffer's triangle ids do not name the triangles drawn";
  }
}

struct TruthDifference {
  size_t pixels = 0, differing = 0, shadowedA = 0, shadowedB = 0;
  float worst = 0.0f;
};

/// Over the pixels both results light: how many differ by more than kNoiseDeltaV, and the shadows.
TruthDifference compareTruths(const ReferenceResult& a, const ReferenceResult& b) {
  TruthDifference d;
  for (size_t i = 0; i < a.visibility.size(); ++i) {
    if (!a.litMask[i] || !b.litMask[i]) continue;
    ++d.pixels;
    const float delta = std::abs(a.visibility[i] - b.visibility[i]);
    d.worst = std::max(d.worst, delta);
    d.differing += delta > kNoiseDeltaV;
    d.shadowedA += a.visibility[i] < 0.5f;
    d.shadowedB += b.visibility[i] < 0.5f;
  }
  return d;
}

// The same 0.3 m box, camera and sun on a 10 m and on a 2 km ground: the truth must not see the
// ground's size. The lifted origin of old (1e-4 × scene size: 0.14 m on the 2 km ground) cut the
// box's shadow there by half. First the same G-buffer (the 10 m render's: same objects, same
// triangle numbering) traced in both scenes, so only the reference can differ; then each scene's
// own render, whose ground positions differ by the rounding of a 2 km triangle's interpolation
// (~2e-5 m), which flips a hard edge's pixels but must not move the shadow.
TEST(ReferenceScale, SameCasterOnA10mAndA2kmGroundHasTheSameTruth) {
  const Scene small = loadTestScene("box-on-10m-ground.json"), large = loadTestScene("box-on-2km-ground.json");
  ASSERT_EQ(small.objects.size(), large.objects.size());
  const RenderResult rs = renderScene(small, "uniform", "hard", {}, kSize, kSize, kMapSize);
  const RenderResult rl = renderScene(large, "uniform", "hard", {}, kSize, kSize, kMapSize);
  const ReferenceTracer smallTracer(small), largeTracer(large);
  // A hard edge's pixels whose two renders straddle it, out of the shadow's: a few per thousand.
  constexpr double kMaxEdgeFlipFraction = 0.005;
  for (const float sizeRad : {0.0f, small.light().size}) {
    Light light = small.light();
    light.size = sizeRad;
    ASSERT_EQ(large.light().direction, light.direction);
    const ReferenceResult a = smallTracer.trace(rs.gbuffer, light, quiet(kSoftSamples));
    const TruthDifference same = compareTruths(a, largeTracer.trace(rs.gbuffer, light, quiet(kSoftSamples)));
    const TruthDifference own = compareTruths(a, largeTracer.trace(rl.gbuffer, light, quiet(kSoftSamples)));
    std::printf("box on 10 m vs 2 km ground, sun size %.3f rad, same G-buffer: %zu pixels, shadowed %zu vs %zu, max |dV| %.4f, "
                "%zu over %.1f; own renders: shadowed %zu vs %zu, %zu over %.1f\n",
                sizeRad, same.pixels, same.shadowedA, same.shadowedB, same.worst, same.differing, kNoiseDeltaV,
                own.shadowedA, own.shadowedB, own.differing, kNoiseDeltaV);
    EXPECT_GT(same.pixels, static_cast<size_t>(kSize * kSize / 2));
    EXPECT_GT(same.shadowedA, 1000u) << "the box's shadow must be in view";
    EXPECT_LT(same.shadowedA, same.pixels / 10) << "a 0.3 m box shades a few percent of the view, not all of it";
    EXPECT_EQ(same.differing, 0u);
    if (sizeRad > 0.0f) EXPECT_EQ(own.differing, 0u);
    else EXPECT_LE(static_cast<double>(own.differing), kMaxEdgeFlipFraction * static_cast<double>(own.shadowedA));
  }
}

// A tilted plane of many triangles, 10 km out, the sun 1° above it (hard, then the real sun's
// size): nothing else casts, so every pixel that faces the sun has V_ref = 1.
TEST(ReferenceScale, NoAcneInTheTruthOnAGrazingPlaneTenKilometresOut) {
  for (const float sizeRad : {0.0f, 0.005f}) {
    const Scene scene = grazingPlaneFarOut(sizeRad);
    const RenderResult r = renderScene(scene, "uniform", "hard", {}, kSize, kSize, kMapSize);
    const ReferenceResult ref = ReferenceTracer(scene).trace(r.gbuffer, scene.light(), quiet(kSoftSamples));
    size_t lit = 0, acne = 0;
    for (size_t i = 0; i < ref.visibility.size(); ++i) {
      lit += ref.litMask[i];
      acne += ref.litMask[i] && ref.visibility[i] < 1.0f;
    }
    std::printf("grazing plane 10 km out, sun 1 deg above it, size %.3f rad: %zu of %zu lit pixels darkened in the truth\n",
                sizeRad, acne, lit);
    EXPECT_GT(lit, static_cast<size_t>(kSize * kSize / 2));
    EXPECT_EQ(acne, 0u);
  }
}
