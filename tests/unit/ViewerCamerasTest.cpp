// The viewer's camera and light controls (src/viewer/Cameras.h): pure maths.
#include "viewer/Cameras.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace penumbra;
using namespace penumbra::viewer;

namespace {
constexpr float kEpsM = 1e-4f;
void expectNear(const glm::vec3& a, const glm::vec3& b, float eps = kEpsM) {
  EXPECT_NEAR(a.x, b.x, eps);
  EXPECT_NEAR(a.y, b.y, eps);
  EXPECT_NEAR(a.z, b.z, eps);
}
}  // namespace

TEST(ViewerCameras, OrbitRoundTripsTheSceneCamera) {
  Camera c;
  c.position = {3.5f, 4.0f, 6.5f};
  c.target = {-0.3f, 0.3f, 0.0f};
  Camera out = c;
  OrbitCamera::fromCamera(c).apply(out);
  expectNear(out.position, c.position);
  expectNear(out.target, c.target);
}

TEST(ViewerCameras, OrbitKeepsDistanceAndClampsPitch) {
  Camera c;
  c.position = {0, 2, 6};
  c.target = {0, 0, 0};
  OrbitCamera o = OrbitCamera::fromCamera(c);
  const float d = o.distanceM;
  o.rotate(1.0f, 10.0f);  // far past the pole
  EXPECT_FLOAT_EQ(o.pitchRad, kPitchLimitRad);
  o.apply(c);
  EXPECT_NEAR(glm::length(c.position - c.target), d, kEpsM);
  o.zoom(1e-9f);
  EXPECT_FLOAT_EQ(o.distanceM, OrbitCamera::kMinDistanceM);
}

TEST(ViewerCameras, OrbitPanMovesTargetInTheViewPlane) {
  Camera c;
  c.position = {0, 0, 5};
  c.target = {0, 0, 0};
  OrbitCamera o = OrbitCamera::fromCamera(c);
  o.pan(0.5f, 0.0f, glm::radians(90.0f));  // half a view height to the right; view height = 10 m
  // Dragging right moves the scene right, i.e. the target left (−X seen from +Z).
  expectNear(o.target, {-5.0f, 0.0f, 0.0f});
}

TEST(ViewerCameras, FlyRoundTripsAndMovesAlongItsAxes) {
  Camera c;
  c.position = {1, 2, 3};
  c.target = {1, 2, -7};
  FlyCamera f = FlyCamera::fromCamera(c);
  Camera out = c;
  f.apply(out);
  expectNear(out.target, c.target);
  f.move({0, 0, 2});  // forward = −Z
  expectNear(f.position, {1, 2, 1});
  f.move({1, 0, 0});  // right = +X when looking down −Z
  expectNear(f.position, {2, 2, 1});
}

TEST(ViewerCameras, SpotLightOrbitsItsAimPointAndKeepsAimingAtIt) {
  Light l;
  l.type = LightType::Spot;
  l.position = {-0.2f, 2.6f, 0.6f};
  l.direction = glm::normalize(glm::vec3(-0.35f, 0.0f, 0.0f) - l.position);
  Aabb bounds;
  bounds.extend(glm::vec3(-4, 0, -4));
  bounds.extend(glm::vec3(4, 1, 4));
  const glm::vec3 aim = lightAimPoint(l, bounds);
  const float dist = glm::length(l.position - aim);
  const glm::vec2 a = lightAngles(l, aim);
  setLightAngles(l, aim, a.x + 0.7f, a.y - 0.2f);
  EXPECT_NEAR(glm::length(l.position - aim), dist, kEpsM);
  expectNear(glm::normalize(aim - l.position), l.direction);
  const glm::vec2 b = lightAngles(l, aim);
  EXPECT_NEAR(b.x, a.x + 0.7f, 1e-4f);
  EXPECT_NEAR(b.y, a.y - 0.2f, 1e-4f);
}

TEST(ViewerCameras, SunElevationStaysAboveTheHorizon) {
  Light sun;
  sun.direction = glm::normalize(glm::vec3(-0.45f, -1.0f, -0.35f));
  setLightAngles(sun, glm::vec3(0), 0.3f, -1.0f);
  EXPECT_NEAR(lightAngles(sun, glm::vec3(0)).y, kMinLightElevationRad, 1e-5f);
  EXPECT_LT(sun.direction.y, 0.0f);  // still shining downward
  EXPECT_NEAR(glm::length(sun.direction), 1.0f, 1e-5f);
}
