// ShadowCamera::fromMatrices: an engine's view and projection matrices give back the camera the
// light's views are fitted to (position, direction, field of view, aspect, near, far), for GL's
// default depth range, for zero-to-one, for reversed-Z with an infinite far plane.
#include <penumbra/Error.h>
#include <penumbra/Shadows.h>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

using namespace penumbra;

namespace {

constexpr float kTolerance = 1e-4f;

void expectNear(const glm::vec3& a, const glm::vec3& b) {
  EXPECT_NEAR(a.x, b.x, kTolerance);
  EXPECT_NEAR(a.y, b.y, kTolerance);
  EXPECT_NEAR(a.z, b.z, kTolerance);
}

}  // namespace

TEST(ShadowCamera, RecoversTheCameraFromGlStyleMatrices) {
  const glm::vec3 eye(3, 4, 5), target(0, 1, -2);
  const glm::mat4 view = glm::lookAt(eye, target, glm::vec3(0, 1, 0));
  const glm::mat4 proj = glm::perspective(0.9f, 16.0f / 9.0f, 0.25f, 300.0f);
  const ShadowCamera c = ShadowCamera::fromMatrices(view, proj, DepthConvention::NegativeOneToOne);
  expectNear(c.fit.position, eye);
  expectNear(c.fit.forward(), glm::normalize(target - eye));
  EXPECT_NEAR(c.fit.fovYRad, 0.9f, kTolerance);
  EXPECT_NEAR(c.aspect, 16.0f / 9.0f, kTolerance);
  EXPECT_NEAR(c.fit.nearM, 0.25f, 1e-3f);
  EXPECT_NEAR(c.fit.farM, 300.0f, 0.5f);
}

TEST(ShadowCamera, ZeroToOneAndReversedInfiniteFar) {
  const glm::mat4 view = glm::lookAt(glm::vec3(0, 2, 6), glm::vec3(0), glm::vec3(0, 1, 0));
  const ShadowCamera zo = ShadowCamera::fromMatrices(view, glm::perspectiveZO(0.8f, 2.0f, 0.1f, 50.0f), DepthConvention::ZeroToOne);
  EXPECT_NEAR(zo.fit.nearM, 0.1f, 1e-4f);
  EXPECT_NEAR(zo.fit.farM, 50.0f, 0.05f);
  // Penumbra's own camera: reversed-Z, infinite far. The far plane becomes one beyond any coordinate.
  Camera own;
  own.nearM = 0.05f;
  const ShadowCamera rev = ShadowCamera::fromMatrices(own.viewFromWorld(), own.clipFromView(1.5f), DepthConvention::ZeroToOne);
  EXPECT_NEAR(rev.fit.nearM, 0.05f, 1e-5f);
  EXPECT_GE(rev.fit.farM, kMaxCoordinateM);
  expectNear(rev.fit.position, own.position);
  EXPECT_NEAR(rev.fit.fovYRad, own.fovYRad, kTolerance);
  EXPECT_NEAR(rev.aspect, 1.5f, kTolerance);
}

TEST(ShadowCamera, RefusesAnOrthographicProjection) {
  const glm::mat4 view = glm::lookAt(glm::vec3(0, 2, 6), glm::vec3(0), glm::vec3(0, 1, 0));
  try {
    ShadowCamera::fromMatrices(view, glm::ortho(-1.0f, 1.0f, -1.0f, 1.0f, 0.1f, 10.0f), DepthConvention::NegativeOneToOne);
    FAIL() << "an orthographic projection was taken for a perspective one";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Usage);
    EXPECT_NE(std::string(e.what()).find("not a perspective projection"), std::string::npos) << e.what();
  }
}

TEST(ShadowCamera, FromCameraKeepsItExactly) {
  Camera cam;
  cam.position = {1, 2, 3};
  const ShadowCamera c = ShadowCamera::fromCamera(cam, 1.25f);
  EXPECT_EQ(c.fit.position, cam.position);
  EXPECT_EQ(c.aspect, 1.25f);
  EXPECT_EQ(c.clipFromView, cam.clipFromView(1.25f));
  EXPECT_EQ(c.viewFromWorld, cam.viewFromWorld());
}
