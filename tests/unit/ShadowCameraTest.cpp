// ShadowCamera::fromMatrices: an engine's view and projection matrices give back the camera the
// light's views are fitted to (position, direction, field of view, aspect, near, far), for GL's
// default depth range, for zero-to-one, for reversed-Z with an infinite far plane, for
// orthographic projections and left-handed (Direct3D-style) views.
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

// An editor's top view or an isometric game: orthographic, its volume's half height recovered,
// and a near plane behind the eye (glm::ortho's near -100) fitted from an eye moved back, with
// the same clip space.
TEST(ShadowCamera, RecoversAnOrthographicCamera) {
  const glm::vec3 eye(0, 20, 0);
  const glm::mat4 view = glm::lookAt(eye, glm::vec3(0), glm::vec3(0, 0, -1));
  const glm::mat4 proj = glm::ortho(-8.0f, 8.0f, -4.5f, 4.5f, 1.0f, 50.0f);
  const ShadowCamera c = ShadowCamera::fromMatrices(view, proj, DepthConvention::NegativeOneToOne);
  EXPECT_TRUE(c.fit.orthographic());
  EXPECT_NEAR(c.fit.orthoHalfHeightM, 4.5f, kTolerance);
  EXPECT_NEAR(c.aspect, 16.0f / 9.0f, kTolerance);
  expectNear(c.fit.position, eye);
  expectNear(c.fit.forward(), glm::vec3(0, -1, 0));
  EXPECT_NEAR(c.fit.nearM, 1.0f, 1e-3f);
  EXPECT_NEAR(c.fit.farM, 50.0f, 1e-2f);
  const ShadowCamera behind = ShadowCamera::fromMatrices(view, glm::ortho(-8.0f, 8.0f, -4.5f, 4.5f, -100.0f, 50.0f),
                                                        DepthConvention::NegativeOneToOne);
  EXPECT_GT(behind.fit.nearM, 0.0f);
  EXPECT_NEAR(behind.fit.farM - behind.fit.nearM, 150.0f, 1e-2f) << "the whole volume, from -100 to 50";
  const glm::mat4 clip = glm::ortho(-8.0f, 8.0f, -4.5f, 4.5f, -100.0f, 50.0f) * view;
  const glm::mat4 same = behind.clipFromView * behind.viewFromWorld;
  for (int i = 0; i < 4; ++i) expectNear(glm::vec3(same[i]), glm::vec3(clip[i]));
}

// Direct3D's convention: a left-handed view looking down +Z and a projection whose w row is
// (0, 0, 1, 0). The camera comes back looking where the engine's camera looks, and the matrices
// turned right-handed still make the engine's clip space.
TEST(ShadowCamera, RecoversALeftHandedCamera) {
  const glm::vec3 eye(3, 4, 5), target(0, 1, -2);
  const glm::mat4 view = glm::lookAtLH(eye, target, glm::vec3(0, 1, 0));
  const glm::mat4 proj = glm::perspectiveLH_ZO(0.9f, 1.5f, 0.2f, 80.0f);
  const ShadowCamera c = ShadowCamera::fromMatrices(view, proj, DepthConvention::ZeroToOne);
  expectNear(c.fit.position, eye);
  expectNear(c.fit.forward(), glm::normalize(target - eye));
  EXPECT_NEAR(c.fit.fovYRad, 0.9f, kTolerance);
  EXPECT_NEAR(c.aspect, 1.5f, kTolerance);
  EXPECT_NEAR(c.fit.nearM, 0.2f, 1e-3f);
  EXPECT_NEAR(c.fit.farM, 80.0f, 0.1f);
  EXPECT_NEAR(c.clipFromView[2][3], -1.0f, kTolerance) << "right-handed inside";
  const glm::mat4 clip = proj * view, same = c.clipFromView * c.viewFromWorld;
  for (int i = 0; i < 4; ++i) expectNear(glm::vec3(same[i]), glm::vec3(clip[i]));
  // An orthographic left-handed one: its volume lies in front along +Z.
  const ShadowCamera o = ShadowCamera::fromMatrices(view, glm::orthoLH_ZO(-2.0f, 2.0f, -1.0f, 1.0f, 0.5f, 30.0f), DepthConvention::ZeroToOne);
  EXPECT_TRUE(o.fit.orthographic());
  expectNear(o.fit.forward(), glm::normalize(target - eye));
  EXPECT_NEAR(o.fit.nearM, 0.5f, 1e-3f);
  EXPECT_NEAR(o.fit.farM, 30.0f, 1e-2f);
}

TEST(ShadowCamera, RefusesWhatIsNoCamera) {
  const glm::mat4 view = glm::lookAt(glm::vec3(0, 2, 6), glm::vec3(0), glm::vec3(0, 1, 0));
  glm::mat4 skewed = glm::perspective(0.8f, 1.0f, 0.1f, 10.0f);
  skewed[0][3] = 0.5f;  // a w row of no projection
  try {
    ShadowCamera::fromMatrices(view, skewed, DepthConvention::NegativeOneToOne);
    FAIL() << "a matrix of no camera was accepted";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Usage);
    EXPECT_NE(std::string(e.what()).find("clipFromView is neither a perspective projection"), std::string::npos) << e.what();
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
