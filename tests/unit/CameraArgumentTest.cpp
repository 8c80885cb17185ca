// The --camera argument: what the viewer prints reads back as the same camera, and bad text is a
// usage error naming the argument.
#include <penumbra/Error.h>
#include <penumbra/SceneIO.h>

#include <gtest/gtest.h>
#include <glm/trigonometric.hpp>

using namespace penumbra;

TEST(CameraArgument, RoundTripsExactly) {
  Camera c;
  c.position = {1.0f / 3.0f, -2.5f, 312.0625f};
  c.target = {4.3f, 1e-7f, -305.5f};
  c.fovYRad = 0.8f;
  c.nearM = 0.3f;
  const Camera back = parseCameraArgument(cameraArgument(c), Camera{});
  EXPECT_EQ(back.position, c.position) << cameraArgument(c);
  EXPECT_EQ(back.target, c.target);
  EXPECT_FLOAT_EQ(back.fovYRad, c.fovYRad);
  EXPECT_EQ(back.nearM, Camera{}.nearM) << "near, far and up come from the base camera";
}

TEST(CameraArgument, FieldOfViewIsOptional) {
  Camera base;
  base.fovYRad = 0.5f;
  const Camera c = parseCameraArgument("-1,2,3:0,0.5,0", base);
  EXPECT_EQ(c.position, glm::vec3(-1.0f, 2.0f, 3.0f));
  EXPECT_EQ(c.target, glm::vec3(0.0f, 0.5f, 0.0f));
  EXPECT_EQ(c.fovYRad, 0.5f);
  EXPECT_FLOAT_EQ(parseCameraArgument("-1,2,3:0,0.5,0:30", base).fovYRad, glm::radians(30.0f));
}

TEST(CameraArgument, BadTextIsAUsageError) {
  for (const char* bad : {"", "1,2,3", "1,2:0,0,0", "1,2,3:1,2,3", "0,5,0:0,0,0", "1,2,3:0,0,0:0.5",
                          "1,2,3:0,0,0:200", "inf,1,2:0,0,0", "1,2,3,4:0,0,0", "1,2,3:0,0,0:30:4", "1,,3:0,0,0",
                          "1,2,3 :0,0,0", "1e30,0,0:0,0,0", "0,0,0:0,-2e6,1"}) {
    try {
      parseCameraArgument(bad, Camera{});
      ADD_FAILURE() << "accepted '" << bad << "'";
    } catch (const Error& e) {
      EXPECT_EQ(e.kind(), ErrorKind::Usage) << bad;
      EXPECT_NE(std::string(e.what()).find(std::string("--camera ") + bad), std::string::npos) << e.what();
    }
  }
}
