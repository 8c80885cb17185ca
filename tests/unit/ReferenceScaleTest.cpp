// The ruler at every scale (issue 18): far from the origin the reference must give the answers
// it gives near it. Every expected value is computed on the surface itself, without any offset:
// a reference that lifts its rays off the surface by a fraction of the scene's size moves shadow
// edges by that lift / tan(elevation) and fails these tests (the old 1e-4 × scene size moved
// them by 0.1 m at 1 km).
#include "ReferenceKnownAnswers.h"

#include <penumbra/Reference.h>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

namespace penumbra {
namespace {

using namespace penumbra::test;

// Where the far scenes stand: 1 km from the origin, where float32 spacing is 61 µm.
const glm::vec3 kKilometreM{1000.0f, 0.0f, 0.0f};
// A tenth of a millimetre: the most a shadow edge may move on a scene 1 km across.
constexpr double kEdgeToleranceM = 1e-4;

/// A 1 m box standing on a 20 m ground around `centreM`: its top edge x = centre + kEdgeX is the
/// square's edge of ReferenceAnalytic.h, and it meets the ground (contact shadows).
Scene boxOnGround(const glm::vec3& centreM) {
  Scene s;
  addObject(s, "ground", makePlane(20.0f, 20.0f), glm::vec3(0.8f), glm::translate(glm::mat4(1.0f), centreM));
  addObject(s, "box", makeBox(glm::vec3(kOccluderSizeM, kOccluderHeightM, kOccluderSizeM)), glm::vec3(0.8f),
            glm::translate(glm::mat4(1.0f), centreM + glm::vec3(0.0f, 0.5f * kOccluderHeightM, 0.0f)));
  return s;
}

// The soft penumbra of the box's edge, 1 km out, pixel by pixel against the exact cap segment
// (the test near the origin is Reference.SpherePenumbraWidthMatchesSimilarTriangles).
TEST(ReferenceScale, BoxEdgePenumbraOneKilometreOutMatchesTheExactAnswer) {
  const ReferenceTracer tracer(boxOnGround(kKilometreM));
  std::vector<glm::vec3> points;
  // From just outside the box's side (umbra, against the contact) across the penumbra.
  constexpr float kFirstX = 0.502f, kLastX = 1.2f, kStepX = 0.002f;
  for (float x = kFirstX; x <= kLastX + 1e-6f; x += kStepX) points.push_back(kKilometreM + glm::vec3(x, 0.0f, 0.0f));
  const ReferenceResult r = tracer.trace(pointsGBuffer(points), sphereLight(kLightRadiusM, kKilometreM), quiet(1024));
  double worst = 0.0;
  size_t penumbra = 0;
  for (size_t i = 0; i < points.size(); ++i) {
    const double exact = analyticVisibility(glm::dvec3(points[i]) - glm::dvec3(kKilometreM));
    worst = std::max(worst, std::abs(r.visibility[i] - exact));
    penumbra += exact > 0.0 && exact < 1.0;
  }
  std::printf("1 km out: max |V - V_exact| over %zu points (%zu in the penumbra) at 1024 spp: %.4f\n", points.size(),
              penumbra, worst);
  EXPECT_GT(penumbra, 100u);
  EXPECT_LT(worst, 0.02) << "the bound of the same test at the origin";
}

// A hard sun at 42° elevation: the box's top edge casts its shadow's edge at x = 0.5 + h / tan(42°)
// past the box. 0.1 mm inside it the ground is dark, 0.1 mm outside it lit; 0.1 mm from the
// box's foot on the shadow side it is dark (contact), on the sunny side lit.
TEST(ReferenceScale, HardShadowEdgeOneKilometreOutMovesLessThanATenthOfAMillimetre) {
  const ReferenceTracer tracer(boxOnGround(kKilometreM));
  Light sun;
  sun.type = LightType::Directional;
  const float elevationRad = glm::radians(42.0f);
  sun.direction = {std::cos(elevationRad), -std::sin(elevationRad), 0.0f};
  sun.size = 0.0f;
  // Computed from the float direction the tracer reads, in double.
  const double edgeX = kKilometreM.x + kEdgeX + kOccluderHeightM * double(sun.direction.x) / -double(sun.direction.y);
  const float footX = kKilometreM.x + kEdgeX, sunnyFootX = kKilometreM.x - kEdgeX;
  const std::vector<glm::vec3> points = {{static_cast<float>(edgeX - kEdgeToleranceM), 0, 0},
                                         {static_cast<float>(edgeX + kEdgeToleranceM), 0, 0},
                                         {footX + static_cast<float>(kEdgeToleranceM), 0, 0},
                                         {sunnyFootX - static_cast<float>(kEdgeToleranceM), 0, 0}};
  const ReferenceResult r = tracer.trace(pointsGBuffer(points), sun, quiet(1));
  std::printf("1 km out, hard sun at 42 deg: V at the edge -/+ 0.1 mm: %g %g; beside the foot: %g (shadow side) %g (sunny side)\n",
              r.visibility[0], r.visibility[1], r.visibility[2], r.visibility[3]);
  EXPECT_EQ(r.visibility, (std::vector<float>{0.0f, 1.0f, 0.0f, 1.0f}));
}

// --- no acne far out ----------------------------------------------------------------------

// grazingPlaneFarOut's plane, 10 km out, under a sun 1° above it. The points are made as a
// rasteriser makes them: barycentric sums of the float world vertices, rounded in float, many of
// them a hair from a shared edge; the normal is the triangle's, in float.
TEST(ReferenceScale, NoAcneOnAGrazingPlaneTenKilometresOut) {
  const Scene scene = grazingPlaneFarOut(0.0f);
  const Object& plane = scene.objects.front();
  const Mesh& mesh = scene.meshes[plane.mesh];
  std::vector<glm::vec3> world;
  for (const glm::vec3& p : mesh.positions) world.push_back(glm::vec3(plane.worldFromObject * glm::vec4(p, 1.0f)));
  const glm::vec3 up = glm::mat3(plane.worldFromObject) * glm::vec3(0, 1, 0);  // the lit side

  // Barycentric weights: inside, and 1e-3 … 1e-6 of the way from each edge.
  const std::vector<glm::vec3> weights = {{1 / 3.f, 1 / 3.f, 1 / 3.f}, {0.5f, 0.5f - 1e-3f, 1e-3f}, {0.5f - 1e-5f, 1e-5f, 0.5f},
                                          {1e-6f, 0.5f, 0.5f - 1e-6f}, {0.2f, 0.8f - 1e-4f, 1e-4f},  {0.7f, 1e-6f, 0.3f - 1e-6f}};
  GBufferData g;
  for (size_t t = 0; t < mesh.triangleCount(); ++t) {
    const glm::vec3 a = world[mesh.indices[3 * t]], b = world[mesh.indices[3 * t + 1]], c = world[mesh.indices[3 * t + 2]];
    glm::vec3 normal = glm::normalize(glm::cross(b - a, c - a));
    if (glm::dot(normal, up) < 0.0f) normal = -normal;
    for (const glm::vec3& w : weights) {
      g.position.emplace_back(w.x * a + w.y * b + w.z * c, 1.0f);
      g.geoNormal.emplace_back(normal, 0.0f);
      g.normal.emplace_back(normal, 0.0f);
      g.albedo.emplace_back(1.0f);
      g.triangle.emplace_back(1u, static_cast<uint32_t>(t));  // object 0
    }
  }
  g.width = static_cast<int>(g.position.size());
  g.height = 1;

  const ReferenceTracer tracer(scene);
  for (const float sizeRad : {0.0f, 0.005f}) {
    Light sun = scene.light();
    sun.size = sizeRad;
    for (const bool knowsTriangles : {true, false}) {
      GBufferData probe = g;
      if (!knowsTriangles) probe.triangle.clear();
      const ReferenceResult r = tracer.trace(probe, sun, quiet(64));
      size_t lit = 0, acne = 0;
      for (size_t i = 0; i < r.visibility.size(); ++i) {
        lit += r.litMask[i];
        acne += r.litMask[i] && r.visibility[i] < 1.0f;
      }
      std::printf("grazing plane 10 km out, sun 1 deg above it, size %.3f rad, %s triangle ids: %zu of %zu points darkened\n",
                  sizeRad, knowsTriangles ? "with" : "without", acne, lit);
      EXPECT_EQ(lit, r.visibility.size());
      EXPECT_EQ(acne, 0u);
    }
  }
}

}  // namespace
}  // namespace penumbra
