// The reference against analytic answers (ReferenceKnownAnswers.h): a square occluder over a plane
// under a spherical light, where every pixel has an exact answer (no GL; G-buffers are
// synthesised). The answers are taken on the surface itself: the reference must not lift rays.
#include "ReferenceKnownAnswers.h"

#include <penumbra/Error.h>
#include <penumbra/Files.h>
#include <penumbra/Reference.h>
#include <penumbra/SceneIO.h>

#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <unistd.h>
#include <vector>

namespace penumbra {
namespace {

using namespace penumbra::test;

Scene squareOverPlane() {
  Scene s;
  s.name = "square-over-plane";
  addObject(s, "ground", makePlane(20.0f, 20.0f), glm::vec3(0.8f));
  addObject(s, "square", makePlane(kOccluderSizeM, kOccluderSizeM), glm::vec3(0.8f),
            glm::translate(glm::mat4(1.0f), {0.0f, kOccluderHeightM, 0.0f}));
  return s;
}

/// Offset t in [0, 1] from a uniform disk's centre where a straight edge hides 10% of it:
/// (acos t − t·√(1 − t²)) / π = 0.1. The 10%–90% span is this fraction of the full 0–1 width.
double diskTenPercentOffset() {
  double lo = 0.0, hi = 1.0;
  for (int i = 0; i < 60; ++i) {
    const double t = 0.5 * (lo + hi);
    ((std::acos(t) - t * std::sqrt(1.0 - t * t)) / glm::pi<double>() > 0.1 ? lo : hi) = t;
  }
  return lo;
}

/// First x where the (rising) profile reaches `level`, linearly interpolated.
double crossing(const std::vector<float>& xs, const std::vector<float>& v, float level) {
  for (size_t i = 1; i < v.size(); ++i)
    if (v[i] >= level && v[i - 1] < level)
      return xs[i - 1] + (xs[i] - xs[i - 1]) * (level - v[i - 1]) / (v[i] - v[i - 1]);
  ADD_FAILURE() << "the profile never crosses " << level;
  return 0.0;
}

// Ground points from the umbra's centre across the edge's penumbra into full light.
constexpr float kLineStartX = 0.0f, kLineEndX = 1.2f, kLineStepX = 0.002f;

std::vector<float> lineXs() {
  std::vector<float> xs;
  for (float x = kLineStartX; x <= kLineEndX + 1e-6f; x += kLineStepX) xs.push_back(x);
  return xs;
}

GBufferData lineGBuffer(const std::vector<float>& xs) {
  std::vector<glm::vec3> points;
  for (float x : xs) points.push_back({x, 0.0f, 0.0f});
  return pointsGBuffer(points);
}

TEST(Reference, SpherePenumbraWidthMatchesSimilarTriangles) {
  const ReferenceTracer tracer(squareOverPlane());
  const std::vector<float> xs = lineXs();
  const ReferenceResult r = tracer.trace(lineGBuffer(xs), sphereLight(), quiet(1024));
  // Similar triangles through the edge: the light's diameter 2R seen from height H, projected
  // past the edge at height h onto the ground, gives the full (0 → 1) width 2R·h/(H − h). For a
  // uniform disk cut by a straight edge the 10%→90% span is diskTenPercentOffset() of it.
  const double fullWidth = 2.0 * kLightRadiusM * kOccluderHeightM / (kLightHeightM - kOccluderHeightM);
  const double expected = diskTenPercentOffset() * fullWidth;
  const double measured = crossing(xs, r.visibility, 0.9f) - crossing(xs, r.visibility, 0.1f);
  std::printf("sphere light: 10-90%% penumbra width %.4f m, similar triangles %.4f m (%.1f%%)\n", measured,
              expected, 100.0 * (measured - expected) / expected);
  EXPECT_NEAR(measured, expected, 0.1 * expected);

  // And pixel by pixel against the exact cap-segment answer.
  double worst = 0.0;
  for (size_t i = 0; i < xs.size(); ++i)
    worst = std::max(worst, std::abs(r.visibility[i] - analyticVisibility({xs[i], 0.0, 0.0})));
  std::printf("sphere light: max |V - V_exact| over %zu points at 1024 spp: %.4f\n", xs.size(), worst);
  EXPECT_LT(worst, 0.02);
}

TEST(Reference, UmbraCentreIsDarkAndFarFieldIsLit) {
  const ReferenceTracer tracer(squareOverPlane());
  const ReferenceResult r = tracer.trace(pointsGBuffer({{0, 0, 0}, {0.1f, 0, -0.1f}, {3, 0, 0}, {-2, 0, 2.5f}}),
                                         sphereLight(), quiet(256));
  ASSERT_EQ(r.visibility.size(), 4u);
  EXPECT_EQ(r.litMask, (std::vector<uint8_t>{1, 1, 1, 1}));
  EXPECT_EQ(r.visibility[0], 0.0f);  // every one of 256 rays blocked
  EXPECT_EQ(r.visibility[1], 0.0f);
  EXPECT_EQ(r.visibility[2], 1.0f);  // no ray blocked
  EXPECT_EQ(r.visibility[3], 1.0f);
  EXPECT_EQ(r.samplesPerPixel, 256);
}

TEST(Reference, ErrorFallsRoughlyAsInverseSqrtOfSamples) {
  const ReferenceTracer tracer(squareOverPlane());
  const std::vector<float> xs = lineXs();
  const GBufferData g = lineGBuffer(xs);
  std::vector<double> exact;
  for (float x : xs) exact.push_back(analyticVisibility({x, 0.0, 0.0}));
  // Each penumbra pixel has its own random stream, so the RMS over ~130 of them is a stable
  // estimate of one pixel's error.
  const auto rmsError = [&](int samples) {
    const ReferenceResult r = tracer.trace(g, sphereLight(), quiet(samples, 7));
    double sum = 0.0;
    int count = 0;
    for (size_t i = 0; i < xs.size(); ++i) {
      if (exact[i] <= 0.0 || exact[i] >= 1.0) continue;
      sum += (r.visibility[i] - exact[i]) * (r.visibility[i] - exact[i]);
      ++count;
    }
    EXPECT_GT(count, 100);
    return std::sqrt(sum / count);
  };
  const double e16 = rmsError(16), e64 = rmsError(64), e256 = rmsError(256);
  const double slope = std::log(e16 / e256) / std::log(16.0);
  std::printf("RMS error vs exact: N=16 %.5f, N=64 %.5f, N=256 %.5f; ratios %.2f %.2f; error ~ N^-%.2f\n", e16, e64,
              e256, e16 / e64, e64 / e256, slope);
  // 1/√N gives 2 per 4× samples. Stratification can do better on an edge (N^-3/4: 2.8); a bias
  // or a broken stratification would flatten the ratio toward 1.
  EXPECT_GT(e16 / e64, 1.5);
  EXPECT_LT(e16 / e64, 3.5);
  EXPECT_GT(e64 / e256, 1.5);
  EXPECT_LT(e64 / e256, 3.5);
  EXPECT_GT(slope, 0.4);
  EXPECT_LT(slope, 1.0);
}

TEST(Reference, SunPenumbraWidthMatchesSimilarTriangles) {
  Light sun;
  sun.type = LightType::Directional;
  sun.direction = {0.0f, -1.0f, 0.0f};
  sun.size = 0.05f;  // angular radius, rad
  const ReferenceTracer tracer(squareOverPlane());
  const std::vector<float> xs = lineXs();
  const ReferenceResult r = tracer.trace(lineGBuffer(xs), sun, quiet(1024));
  // Straight down: the edge's shadow is at x = 0.5, and the sun's disk of angular radius α
  // spreads it over 2·h·tan α.
  const double expected = diskTenPercentOffset() * 2.0 * kOccluderHeightM * std::tan(sun.size);
  const double x10 = crossing(xs, r.visibility, 0.1f), x90 = crossing(xs, r.visibility, 0.9f);
  std::printf("sun: 10-90%% penumbra width %.4f m, similar triangles %.4f m\n", x90 - x10, expected);
  EXPECT_NEAR(x90 - x10, expected, 0.1 * expected);
  EXPECT_NEAR(0.5 * (x10 + x90), kEdgeX, 0.005);  // centred on the geometric shadow edge
}

TEST(Reference, HardLightsTraceOneSharpRay) {
  const ReferenceTracer tracer(squareOverPlane());
  // The edge's hard shadow falls at x = kEdgeX · H / (H − h) = 0.667 m.
  const ReferenceResult spot = tracer.trace(pointsGBuffer({{0.65f, 0, 0}, {0.685f, 0, 0}}), sphereLight(0.0f), quiet(256));
  EXPECT_EQ(spot.samplesPerPixel, 1);
  EXPECT_EQ(spot.visibility, (std::vector<float>{0.0f, 1.0f}));
  Light sun;
  sun.type = LightType::Directional;
  sun.direction = glm::normalize(glm::vec3(1.0f, -1.0f, 0.0f));  // 45°: the shadow shifts by h
  const ReferenceResult hard = tracer.trace(pointsGBuffer({{1.49f, 0, 0}, {1.51f, 0, 0}}), sun, quiet(256));
  EXPECT_EQ(hard.visibility, (std::vector<float>{0.0f, 1.0f}));
  // Lit hard pixels: no split error by construction, and Lambert with E = intensity · cos.
  EXPECT_EQ(hard.approximationError[1], glm::vec3(0.0f));
  EXPECT_NEAR(hard.shadingExact[1].x, sun.intensity * std::cos(glm::quarter_pi<float>()) / glm::pi<float>(), 1e-5f);
}

TEST(Reference, MaskKeepsOnlyPixelsThatFaceTheLightInsideTheCone) {
  const ReferenceTracer tracer(squareOverPlane());
  Light spot = sphereLight();
  spot.coneAngleRad = 0.6f;
  GBufferData g = pointsGBuffer({{2, 0, 0}, {4, 0, 0}, {2, 0, 0}, {2, 0, 0}});
  g.geoNormal[2] = {0, -1, 0, 0};  // faces away from the light
  g.position[3].w = 0.0f;          // background
  // (4, 0, 0) is atan(4/4) = 0.785 rad off the spot axis: outside a 0.6 rad cone.
  const ReferenceResult r = tracer.trace(g, spot, quiet(64));
  EXPECT_EQ(r.litMask, (std::vector<uint8_t>{1, 0, 0, 0}));
  EXPECT_EQ(r.visibility, (std::vector<float>{1.0f, 0.0f, 0.0f, 1.0f}));
  EXPECT_EQ(r.shadingExact[1], glm::vec3(0.0f));
}

/// Irradiance over radiance of a uniform sphere (or the sun's disk) of angular radius α whose
/// centre is at cos θ from a surface's normal, the part below the surface's horizon left out:
/// π sin²α cos θ while the whole light is above the horizon, else the closed form of the cap cut
/// by the horizon plane (Snyder 1996, "Area light sources for real-time graphics").
double horizonCutIrradiance(double cosTheta, double sinAlpha) {
  const double sin2 = sinAlpha * sinAlpha;
  if (cosTheta * cosTheta > sin2) return glm::pi<double>() * sin2 * std::max(cosTheta, 0.0);
  const double sinTheta = std::sqrt(1.0 - cosTheta * cosTheta);
  const double x = std::sqrt(1.0 / sin2 - 1.0);
  const double y = -x * cosTheta / sinTheta;
  const double s = sinTheta * std::sqrt(1.0 - y * y);
  return (cosTheta * std::acos(y) - x * s) * sin2 + std::atan(s / x);
}

// A sphere light whose centre lies below a receiver's horizon still lights it by the part above
// (the shadow side of a ball, a box top beside a lower lamp): the reference traces that part,
// keeps the pixel out of litMask (the metrics') and counts it.
TEST(Reference, SphereLightPartlyAboveTheHorizonLightsTheReceiver) {
  const float distanceM = 2.0f, radiusM = 1.0f;  // sin α = 1/2: 30°
  Scene s;
  addObject(s, "far", makePlane(1.0f, 1.0f), glm::vec3(0.8f), glm::translate(glm::mat4(1.0f), {50.0f, 0.0f, 50.0f}));
  Light light;
  light.type = LightType::Point;
  light.intensity = 5.0f;
  light.size = radiusM;
  const ReferenceTracer tracer(s);
  // The centre 15° below the horizon of the points' plane (y = 0, normal +Y): the light's upper
  // 15° rise above it. At 35° below, none of it does.
  const auto lightAt = [&](double elevationRad) {
    Light l = light;
    l.position = glm::vec3(std::cos(elevationRad), std::sin(elevationRad), 0.0) * distanceM;
    return l;
  };
  const double radiance = light.intensity / (glm::pi<double>() * radiusM * radiusM);
  const double brdf = 1.0 / glm::pi<double>();  // pointsGBuffer's albedo is 1
  for (const double degrees : {-15.0, -5.0}) {
    const double elevation = glm::radians(degrees);
    const ReferenceResult r = tracer.trace(pointsGBuffer({{0, 0, 0}}), lightAt(elevation), quiet(4096));
    const double expected = brdf * radiance * horizonCutIrradiance(std::sin(elevation), 0.5);
    std::printf("sphere centre %.0f deg below the horizon: shading %.5f, closed form %.5f (%.2f%%)\n", -degrees,
                r.shadingExact[0].x, expected, 100.0 * (r.shadingExact[0].x - expected) / expected);
    EXPECT_EQ(r.litMask[0], 0);
    EXPECT_EQ(r.horizonPixels, 1u);
    EXPECT_EQ(r.visibility[0], 1.0f);  // nothing hides the part above the horizon
    EXPECT_EQ(r.visibilityCosWeighted[0], 1.0f);
    EXPECT_NEAR(r.shadingExact[0].x, expected, 0.02 * expected);
  }
  const ReferenceResult below = tracer.trace(pointsGBuffer({{0, 0, 0}}), lightAt(glm::radians(-35.0)), quiet(256));
  EXPECT_EQ(below.horizonPixels, 0u);
  EXPECT_EQ(below.visibility[0], 0.0f);
  EXPECT_EQ(below.shadingExact[0], glm::vec3(0.0f));
  // A wall between the receiver and the light hides the part above the horizon: no light, not counted.
  addObject(s, "wall", makePlane(4.0f, 4.0f), glm::vec3(0.8f),
            glm::rotate(glm::translate(glm::mat4(1.0f), {0.3f, 0.0f, 0.0f}), glm::half_pi<float>(), glm::vec3(0, 0, 1)));
  const ReferenceResult covered = ReferenceTracer(s).trace(pointsGBuffer({{0, 0, 0}}), lightAt(glm::radians(-15.0)), quiet(256));
  EXPECT_EQ(covered.visibility[0], 0.0f);
  EXPECT_EQ(covered.horizonPixels, 0u);
  // The sun too: 0.1 rad wide, its centre 0.05 rad below the horizon.
  Light sun;
  sun.type = LightType::Directional;
  sun.size = 0.1f;
  sun.direction = -glm::vec3(std::cos(-0.05f), std::sin(-0.05f), 0.0f);
  const ReferenceResult low = tracer.trace(pointsGBuffer({{0, 0, 0}}), sun, quiet(4096));
  const double sunRadiance = sun.intensity / (glm::pi<double>() * std::sin(0.1) * std::sin(0.1));
  const double sunExpected = brdf * sunRadiance * horizonCutIrradiance(std::sin(-0.05), std::sin(0.1));
  EXPECT_EQ(low.horizonPixels, 1u);
  EXPECT_NEAR(low.shadingExact[0].x, sunExpected, 0.03 * sunExpected);
}

TEST(Reference, SameSeedRepeatsExactlyAndAnotherSeedDoesNot) {
  const ReferenceTracer tracer(squareOverPlane());
  const GBufferData g = lineGBuffer(lineXs());
  const ReferenceResult a = tracer.trace(g, sphereLight(), quiet(16, 1));
  const ReferenceResult b = tracer.trace(g, sphereLight(), quiet(16, 1));
  const ReferenceResult c = tracer.trace(g, sphereLight(), quiet(16, 2));
  EXPECT_EQ(a.visibility, b.visibility);
  EXPECT_EQ(a.shadingExact, b.shadingExact);
  EXPECT_NE(a.visibility, c.visibility);
}

// The split approximation against a closed form. A point at the origin (normal +Y) sees a
// sphere light of angular radius α = 30° centred 45° above its horizon; a horizontal occluder
// whose edge lies in the plane y = x (through the point and the light's centre) hides exactly
// the upper half of the light. V = 1/2, but the hidden half is the one nearer the normal, so the
// exact cosine-weighted visibility is 1/2 − (α − sin 2α / 2) / (π sin²α) = 0.3847 and the
// split model is too bright by 0.1153 of the unshadowed shading.
TEST(Reference, SplitApproximationErrorMatchesClosedForm) {
  const float distanceM = 2.0f, radiusM = 1.0f;  // sin α = 1/2
  Scene s;
  // x in [-3, 0.3] at y = 0.3: its edge (0.3, 0.3, z) lies in the plane y = x, and it is nearer
  // than the light's surface (1 m away) along every ray it blocks.
  addObject(s, "occluder", makePlane(3.3f, 6.0f), glm::vec3(0.8f),
            glm::translate(glm::mat4(1.0f), {-1.35f, 0.3f, 0.0f}));
  Light light;  // a point light: no cone, no falloff
  light.type = LightType::Point;
  light.position = glm::vec3(std::sqrt(2.0f), std::sqrt(2.0f), 0.0f) * (distanceM / 2.0f);
  light.intensity = 5.0f;
  light.size = radiusM;
  // A second point, (10, 0, 0), sees the whole light (its rays pass y = 0.3 at x > 3).
  const ReferenceResult r = ReferenceTracer(s).trace(pointsGBuffer({{0, 0, 0}, {10, 0, 0}}), light, quiet(1024));
  const double alpha = glm::pi<double>() / 6.0;
  const double cosWeighted = 0.5 - (alpha - 0.5 * std::sin(2.0 * alpha)) / (glm::pi<double>() * std::sin(alpha) * std::sin(alpha));
  const float unshadowed = light.intensity * std::cos(glm::quarter_pi<float>()) / (distanceM * distanceM) / glm::pi<float>();
  std::printf("split: V %.4f (exact 0.5), cos-weighted V %.4f (exact %.4f), split error %.4f of unshadowed\n",
              r.visibility[0], r.visibilityCosWeighted[0], cosWeighted, r.approximationError[0].x / unshadowed);
  EXPECT_NEAR(r.visibility[0], 0.5, 0.01);
  EXPECT_NEAR(r.visibilityCosWeighted[0], cosWeighted, 0.01);
  EXPECT_NEAR(r.shadingSplit[0].x, 0.5 * unshadowed, 0.01 * unshadowed);
  EXPECT_NEAR(r.shadingExact[0].x, cosWeighted * unshadowed, 0.01 * unshadowed);
  EXPECT_NEAR(r.approximationError[0].x / unshadowed, 0.5 - cosWeighted, 0.01);
  // Unoccluded: no split error at all, and a uniform sphere fully above the horizon lights like
  // a point of the same intensity, E = I cos θ / d².
  const glm::vec3 toLight = light.position - glm::vec3(10, 0, 0);
  const float expected = light.intensity * (toLight.y / glm::length(toLight)) / glm::dot(toLight, toLight) / glm::pi<float>();
  EXPECT_EQ(r.visibility[1], 1.0f);
  EXPECT_EQ(r.approximationError[1], glm::vec3(0.0f));
  EXPECT_NEAR(r.shadingExact[1].x, expected, 0.005 * expected);
}

TEST(Reference, AlphaMaskedCastersLetLightThroughTheirHoles) {
  Scene s = squareOverPlane();
  // 2×2 alpha checkerboard: holes at texels (0, 0) and (1, 1). makePlane's uv is (x + ½, ½ − z)
  // and uv row 0 is the image's top row, so the holes are over (−¼, ¼) and (¼, −¼).
  s.images.push_back({2, 2, {255, 255, 255, 0, 255, 255, 255, 255, 255, 255, 255, 255, 255, 255, 255, 0}});
  Material& square = s.materials[s.objects[1].material];
  square.baseColorTexture = 0;
  Light sun;
  sun.type = LightType::Directional;
  const GBufferData g = pointsGBuffer({{-0.25f, 0, 0.25f}, {0.25f, 0, 0.25f}, {-0.25f, 0, -0.25f}, {0.25f, 0, -0.25f}});
  EXPECT_EQ(ReferenceTracer(s).trace(g, sun, quiet(1)).visibility, (std::vector<float>{0, 0, 0, 0}));
  square.alphaMask = true;
  EXPECT_EQ(ReferenceTracer(s).trace(g, sun, quiet(1)).visibility, (std::vector<float>{1, 0, 0, 1}));
}

// Light through translucent casters: each ray keeps the product of the transmittances it
// crosses, in whatever order Embree finds them; an opaque caster stops it; a closed glass box is
// crossed twice; the scalar V is the mean of the channels. The tinted pane's red/green ratio under
// it is the pane's own.
TEST(Reference, TranslucentCastersTintTheLightByTheProductOfTheirTransmittances) {
  const glm::vec3 tint(0.85f, 0.45f, 0.3f), green(0.2f, 0.85f, 0.25f);
  Scene s;
  addObject(s, "ground", makePlane(40.0f, 40.0f), glm::vec3(0.8f));
  const auto glass = [&](const char* name, Mesh mesh, const glm::vec3& t, const glm::vec3& at) {
    const uint32_t o = addObject(s, name, std::move(mesh), t, glm::translate(glm::mat4(1.0f), at));
    s.materials[s.objects[o].material].transmittance = t;
  };
  glass("tinted pane", makePlane(2.0f, 2.0f), tint, {0.0f, 1.0f, 0.0f});     // x in [-1, 1]
  glass("green pane", makePlane(2.0f, 2.0f), green, {1.5f, 2.0f, 0.0f});     // x in [0.5, 2.5]
  glass("glass box", makeBox({1.0f, 1.0f, 1.0f}), tint, {6.0f, 1.5f, 0.0f});  // two faces on a vertical ray
  addObject(s, "opaque lid", makePlane(0.5f, 0.5f), glm::vec3(0.5f), glm::translate(glm::mat4(1.0f), {-0.75f, 3.0f, 0.0f}));
  Light sun;
  sun.type = LightType::Directional;
  sun.direction = {0.0f, -1.0f, 0.0f};
  // Under the tinted pane only, under both panes, under the green one only, in the open, under
  // the glass box, under the opaque lid over the tinted pane.
  // (Off the boxes' and planes' diagonals: a ray exactly through an edge two triangles of one
  // surface share meets both.)
  const GBufferData g =
      pointsGBuffer({{-0.25f, 0, 0.1f}, {0.75f, 0, 0.1f}, {2.2f, 0, 0.1f}, {4.0f, 0, 0.1f}, {6.2f, 0, 0.1f}, {-0.75f, 0, 0.1f}});
  const ReferenceTracer tracer(s);
  const ReferenceResult hard = tracer.trace(g, sun, quiet(1));
  const std::vector<glm::vec3> expected = {tint, tint * green, green, glm::vec3(1.0f), tint * tint, glm::vec3(0.0f)};
  ASSERT_EQ(hard.visibilityRgb.size(), expected.size());
  for (size_t i = 0; i < expected.size(); ++i) {
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(hard.visibilityRgb[i][c], expected[i][c], 1e-6f) << "point " << i;
    EXPECT_NEAR(hard.visibility[i], (expected[i].x + expected[i].y + expected[i].z) / 3.0f, 1e-6f) << "point " << i;
  }
  // A soft sun: every sample under the middle of the tinted pane passes it alone.
  sun.size = 0.02f;
  const ReferenceResult soft = tracer.trace(g, sun, quiet(256));
  const glm::vec3 under = soft.visibilityRgb[0];
  std::printf("translucent: V_rgb under the tinted pane (%.4f, %.4f, %.4f), red/green %.4f (pane %.4f)\n", under.x,
              under.y, under.z, under.x / under.y, tint.x / tint.y);
  EXPECT_NEAR(under.x, tint.x, 1e-5f);
  EXPECT_NEAR(under.y, tint.y, 1e-5f);
  EXPECT_NEAR(under.x / under.y, tint.x / tint.y, 1e-4f);
  EXPECT_NEAR(soft.shadingExact[0].y / soft.shadingExact[3].y, tint.y, 1e-3f) << "the shading carries the colour";
  // The RGB arrays survive the cache.
  ReferenceOptions cached = quiet(64);
  cached.useCache = true;
  cached.cacheDir = std::filesystem::temp_directory_path() / fmt::format("penumbra-ref-colour-{}", getpid());
  std::filesystem::remove_all(cached.cacheDir);
  const ReferenceResult first = tracer.trace(g, sun, cached), again = tracer.trace(g, sun, cached);
  EXPECT_TRUE(again.fromCache);
  EXPECT_EQ(again.visibilityRgb, first.visibilityRgb);
  EXPECT_EQ(again.visibilityCosWeightedRgb, first.visibilityCosWeightedRgb);
  std::filesystem::remove_all(cached.cacheDir);
}

// An opaque scene's truth does not move: on every built-in scene without translucent casters,
// ground points traced with the colour machinery engaged (a translucent square where no ray goes,
// below the ground) give V, cos-weighted V and shading bit for bit as the opaque path, and their RGB
// V is V in every channel; the opaque scene itself has no RGB arrays.
TEST(Reference, OpaqueBuiltinScenesAreBitIdenticalThroughTheColourPath) {
  for (const std::string& name : builtinSceneNames()) {
    const Scene opaque = makeBuiltinScene(name);
    if (std::any_of(opaque.materials.begin(), opaque.materials.end(), [](const Material& m) { return m.translucent(); }))
      continue;
    Scene engaged = opaque;
    const uint32_t o = addObject(engaged, "unseen glass", makePlane(1.0f, 1.0f), glm::vec3(0.5f),
                                 glm::translate(glm::mat4(1.0f), {0.0f, -50.0f, 0.0f}));
    engaged.materials[engaged.objects[o].material].transmittance = glm::vec3(0.5f, 0.6f, 0.7f);
    // A 40 × 40 grid of ground points over 24 m around the camera's target (city: 240 m).
    const float half = name == "city" ? 120.0f : 12.0f;
    std::vector<glm::vec3> points;
    for (int z = 0; z < 40; ++z)
      for (int x = 0; x < 40; ++x)
        points.push_back(glm::vec3(opaque.camera.target.x, 0.0f, opaque.camera.target.z) +
                         glm::vec3(-half + 2.0f * half * (x + 0.5f) / 40.0f, 0.0f, -half + 2.0f * half * (z + 0.5f) / 40.0f));
    const GBufferData g = pointsGBuffer(points);
    for (const Light& light : {opaque.lights.front(), opaque.lights.back()}) {
      const ReferenceResult a = ReferenceTracer(opaque).trace(g, light, quiet(16));
      const ReferenceResult b = ReferenceTracer(engaged).trace(g, light, quiet(16));
      EXPECT_TRUE(a.visibilityRgb.empty()) << name;
      ASSERT_EQ(b.visibilityRgb.size(), a.visibility.size()) << name;
      EXPECT_EQ(a.litMask, b.litMask) << name;
      EXPECT_EQ(a.visibility, b.visibility) << name;
      EXPECT_EQ(a.visibilityCosWeighted, b.visibilityCosWeighted) << name;
      EXPECT_EQ(a.shadingExact, b.shadingExact) << name;
      EXPECT_EQ(a.shadingSplit, b.shadingSplit) << name;
      size_t shadowed = 0;
      for (size_t i = 0; i < a.visibility.size(); ++i) {
        EXPECT_EQ(b.visibilityRgb[i], glm::vec3(a.visibility[i])) << name << " point " << i;
        EXPECT_EQ(b.visibilityCosWeightedRgb[i], glm::vec3(a.visibilityCosWeighted[i])) << name << " point " << i;
        shadowed += a.litMask[i] && a.visibility[i] < 1.0f;
      }
      std::printf("%s: %zu of %zu ground points shadowed, identical through the colour path\n", name.c_str(), shadowed,
                  points.size());
    }
  }
}

TEST(Reference, RejectsInconsistentInputs) {
  const ReferenceTracer tracer(squareOverPlane());
  GBufferData g = pointsGBuffer({{0, 0, 0}});
  EXPECT_THROW(tracer.trace(g, sphereLight(), quiet(0)), Error);
  Light negative = sphereLight();
  negative.size = -1.0f;
  EXPECT_THROW(tracer.trace(g, negative, quiet(16)), Error);
  g.albedo.clear();
  EXPECT_THROW(tracer.trace(g, sphereLight(), quiet(16)), Error);
  // A covered pixel that shows a triangle the scene does not have: a G-buffer of another scene.
  GBufferData foreign = pointsGBuffer({{0, 0, 0}});
  foreign.triangle.assign(1, glm::uvec2(3, 0));  // object 2; the scene has two
  EXPECT_THROW(tracer.trace(foreign, sphereLight(), quiet(16)), Error);
  foreign.triangle.assign(1, glm::uvec2(1, 2));  // the ground's third triangle; it has two
  EXPECT_THROW(tracer.trace(foreign, sphereLight(), quiet(16)), Error);
}

// --- cache and timing on a small synthetic scene ------------------------------------------

/// Boxes and spheres on a ground plane under a soft spot light, and a G-buffer that looks
/// straight down at the ground: n × n points over [−halfM, halfM]².
Scene boxesAndSpheres() {
  Scene s;
  addObject(s, "ground", makePlane(20.0f, 20.0f), glm::vec3(0.8f));
  for (int i = 0; i < 6; ++i) {
    const float x = -3.5f + 1.4f * static_cast<float>(i), height = 0.4f + 0.3f * static_cast<float>(i);
    addObject(s, "box", makeBox({0.6f, height, 0.6f}), glm::vec3(0.7f),
              glm::translate(glm::mat4(1.0f), {x, 0.5f * height, -1.5f}));
    addObject(s, "sphere", makeSphere(0.35f), glm::vec3(0.6f), glm::translate(glm::mat4(1.0f), {x, 1.0f, 1.5f}));
  }
  return s;
}

Light benchLight() {
  Light l = sphereLight(0.3f);
  l.position = {1.0f, 6.0f, 0.5f};
  return l;
}

GBufferData groundGrid(int n, float halfM) {
  std::vector<glm::vec3> points;
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x)
      points.push_back({-halfM + 2.0f * halfM * (static_cast<float>(x) + 0.5f) / static_cast<float>(n), 0.0f,
                        -halfM + 2.0f * halfM * (static_cast<float>(y) + 0.5f) / static_cast<float>(n)});
  GBufferData g = pointsGBuffer(points);
  g.width = g.height = n;
  return g;
}

std::filesystem::path freshTempDir(const std::string& name) {
  const auto dir = std::filesystem::path(testing::TempDir()) / (name + "-" + std::to_string(getpid()));
  std::filesystem::remove_all(dir);
  return dir;
}

size_t filesIn(const std::filesystem::path& dir) {
  return static_cast<size_t>(std::distance(std::filesystem::directory_iterator(dir), {}));
}

void expectSameData(const ReferenceResult& a, const ReferenceResult& b) {
  EXPECT_EQ(a.width, b.width);
  EXPECT_EQ(a.height, b.height);
  EXPECT_EQ(a.litMask, b.litMask);
  EXPECT_EQ(a.visibility, b.visibility);
  EXPECT_EQ(a.visibilityCosWeighted, b.visibilityCosWeighted);
  EXPECT_EQ(a.shadingExact, b.shadingExact);
  EXPECT_EQ(a.shadingSplit, b.shadingSplit);
  EXPECT_EQ(a.approximationError, b.approximationError);
}

TEST(ReferenceCache, SecondCallReadsIdenticalDataFastAndInputsChangeTheKey) {
  const std::filesystem::path dir = freshTempDir("penumbra-reference-cache");
  // 256 samples a pixel, as compare's references use: the load does not depend on the sample
  // count, the trace does. At 64 samples the trace took 0.010-0.020 s and the load 0.004-0.014 s
  // (the high ends on a CI machine running two tests at once), too close to tell a slow reader
  // from a busy machine. The first load in a process is what a compare run pays (later loads in
  // the same process reuse the allocator's pages and take 0.0006 s).
  ReferenceOptions options = quiet(256);
  options.useCache = true;
  options.cacheDir = dir;
  const ReferenceTracer tracer(boxesAndSpheres());
  const GBufferData g = groundGrid(128, 5.0f);

  const ReferenceResult first = tracer.trace(g, benchLight(), options);
  EXPECT_FALSE(first.fromCache);
  EXPECT_EQ(filesIn(dir), 1u);  // the result, no temporary left behind
  const ReferenceResult second = tracer.trace(g, benchLight(), options);
  EXPECT_TRUE(second.fromCache);
  expectSameData(first, second);
  EXPECT_EQ(second.traceSeconds, first.traceSeconds);
  std::printf("cache: trace %.3f s, cached load %.4f s\n", first.traceSeconds, second.seconds);
  EXPECT_LT(second.seconds, 0.25 * first.traceSeconds);

  Light moved = benchLight();
  moved.position.x += 0.01f;
  EXPECT_NE(tracer.cacheKey(g, moved, options), first.cacheKey);
  Light bigger = benchLight();
  bigger.size *= 1.01f;
  EXPECT_NE(tracer.cacheKey(g, bigger, options), first.cacheKey);
  EXPECT_NE(tracer.cacheKey(g, benchLight(), quiet(257)), first.cacheKey);
  EXPECT_NE(tracer.cacheKey(g, benchLight(), quiet(256, 1)), first.cacheKey);
  GBufferData nudged = g;
  nudged.position[5].y += 1e-4f;
  EXPECT_NE(tracer.cacheKey(nudged, benchLight(), options), first.cacheKey);
  EXPECT_EQ(tracer.cacheKey(g, sphereLight(0.0f), quiet(64, 1)), tracer.cacheKey(g, sphereLight(0.0f), quiet(16, 2)))
      << "a hard light ignores samples and seed, so they must not split its cache";
  const ReferenceResult other = tracer.trace(g, moved, options);
  EXPECT_FALSE(other.fromCache);
  EXPECT_EQ(filesIn(dir), 2u);

  // A damaged file is ignored and replaced: one flipped byte in the payload, then a truncation.
  const std::filesystem::path file = dir / fmt::format("reference-{:016x}.bin", first.cacheKey);
  ASSERT_TRUE(std::filesystem::exists(file));
  {
    std::fstream f(file, std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(static_cast<std::streamoff>(std::filesystem::file_size(file) / 2));
    f.put('\x5a');
  }
  const ReferenceResult repaired = tracer.trace(g, benchLight(), options);
  EXPECT_FALSE(repaired.fromCache);
  expectSameData(first, repaired);
  // The header's and the record's fields are checked too: a flipped byte in the kind (offset 8),
  // the key (32), the sample count (96: after the 48-byte header and six block sizes) or the
  // trace time (112); the latter two once reported 191 samples or 3286 s.
  for (const std::streamoff offset : {8, 32, 96, 112}) {
    {
      std::fstream f(file, std::ios::in | std::ios::out | std::ios::binary);
      f.seekp(offset + 1);
      f.put('\x5a');
    }
    const ReferenceResult again = tracer.trace(g, benchLight(), options);
    EXPECT_FALSE(again.fromCache) << "a flipped byte at " << offset;
    EXPECT_EQ(again.samplesPerPixel, first.samplesPerPixel);
  }
  std::filesystem::resize_file(file, std::filesystem::file_size(file) - 7);
  EXPECT_FALSE(tracer.trace(g, benchLight(), options).fromCache);
  EXPECT_TRUE(tracer.trace(g, benchLight(), options).fromCache);
  std::filesystem::remove_all(dir);
}

// A cache that cannot be written costs the cache, not the result: a file in the folder's place,
// and a folder in the entry's place (it can be neither read nor replaced). The result is whole
// and the same as without a cache; cacheWarning says where and why.
TEST(ReferenceCache, AnUnwritableCacheGivesTheResultAndAWarning) {
  const std::filesystem::path dir = freshTempDir("penumbra-reference-cache-unwritable");
  std::filesystem::create_directories(dir);
  const ReferenceTracer tracer(boxesAndSpheres());
  const GBufferData g = groundGrid(32, 5.0f);
  const ReferenceResult plain = tracer.trace(g, benchLight(), quiet(16));
  ReferenceOptions options = quiet(16);
  options.useCache = true;

  options.cacheDir = dir / "file";
  std::ofstream(options.cacheDir) << "a file";
  const ReferenceResult noFolder = tracer.trace(g, benchLight(), options);
  expectSameData(plain, noFolder);
  EXPECT_EQ(noFolder.cacheWarning, "reference cache: the cache folder " + options.cacheDir.string() + " is a file, not a folder");

  options.cacheDir = dir / "folder";
  const std::filesystem::path entry = options.cacheDir / fmt::format("reference-{:016x}.bin", tracer.cacheKey(g, benchLight(), options));
  std::filesystem::create_directories(entry / "inside");
  const ReferenceResult noEntry = tracer.trace(g, benchLight(), options);
  expectSameData(plain, noEntry);
  EXPECT_EQ(noEntry.cacheWarning, "reference cache: " + entry.string() + ": is a folder, not a file");
  EXPECT_EQ(filesIn(options.cacheDir), 1u) << "no temporary file is left";

  std::filesystem::remove_all(entry);
  const ReferenceResult stored = tracer.trace(g, benchLight(), options);
  EXPECT_TRUE(stored.cacheWarning.empty()) << stored.cacheWarning;
  EXPECT_TRUE(tracer.trace(g, benchLight(), options).fromCache);
  std::filesystem::remove_all(dir);
}

TEST(ReferenceCache, DefaultDirectoryFollowsTheEnvironment) {
  const auto saved = [](const char* name) {
    const char* v = std::getenv(name);
    return v ? std::optional<std::string>(v) : std::nullopt;
  };
  const auto restore = [](const char* name, const std::optional<std::string>& v) {
    if (v) setenv(name, v->c_str(), 1); else unsetenv(name);
  };
  const auto cache = saved("PENUMBRA_CACHE"), xdg = saved("XDG_CACHE_HOME"), home = saved("HOME");
  setenv("PENUMBRA_CACHE", "/tmp/pn-cache", 1);
  setenv("XDG_CACHE_HOME", "/tmp/xdg", 1);
  setenv("HOME", "/tmp/home", 1);
  EXPECT_EQ(defaultCacheDir(), std::filesystem::path("/tmp/pn-cache"));
  unsetenv("PENUMBRA_CACHE");
  EXPECT_EQ(defaultCacheDir(), std::filesystem::path("/tmp/xdg/penumbra"));
  unsetenv("XDG_CACHE_HOME");
  EXPECT_EQ(defaultCacheDir(), std::filesystem::path("/tmp/home/.cache/penumbra"));
  restore("PENUMBRA_CACHE", cache);
  restore("XDG_CACHE_HOME", xdg);
  restore("HOME", home);
}

// The benchmark figure (not a pass/fail time): 256×256 pixels at 64 samples. It asserts
// only that the scene has umbra, penumbra and lit pixels, so the time is for real work.
TEST(ReferenceTiming, Image256x256At64Samples) {
  const ReferenceTracer tracer(boxesAndSpheres());
  const ReferenceResult r = tracer.trace(groundGrid(256, 5.0f), benchLight(), quiet(64));
  size_t umbra = 0, penumbra = 0, lit = 0;
  for (float v : r.visibility) (v == 0.0f ? umbra : v == 1.0f ? lit : penumbra) += 1;
  std::printf("timing: reference 256x256 at 64 spp: %.3f s wall (%zu umbra, %zu penumbra, %zu lit pixels)\n",
              r.traceSeconds, umbra, penumbra, lit);
  RecordProperty("reference_seconds_256x256_64spp", std::to_string(r.traceSeconds));
  EXPECT_GT(umbra, 1000u);
  EXPECT_GT(penumbra, 1000u);
  EXPECT_GT(lit, 10000u);
}

}  // namespace
}  // namespace penumbra
