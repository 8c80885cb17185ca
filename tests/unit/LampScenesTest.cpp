// Lights as engines have them, without GL: the built-in scenes lit by lamps (`room`, `night`)
// hold the lights their sweeps and tests rely on, and a glTF file's KHR_lights_punctual point and
// spot lights arrive as they were written (tests/data/models/lamps.gltf).
#include <penumbra/SceneIO.h>

#include <glm/gtc/constants.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>

using namespace penumbra;

namespace {

size_t countOf(const Scene& s, size_t first, LightType type) {
  return static_cast<size_t>(std::count_if(s.lights.begin(), s.lights.begin() + static_cast<std::ptrdiff_t>(first),
                                           [&](const Light& l) { return l.type == type; }));
}

}  // namespace

// room: light 0 is a point lamp with a sphere (soft shadows), light 1 a spot with both cones.
TEST(LampScenes, RoomHasAPointLampAndASpot) {
  const Scene room = makeBuiltinScene("room");
  ASSERT_EQ(room.lights.size(), 2u);
  const Light& lamp = room.lights[0];
  EXPECT_EQ(lamp.type, LightType::Point);
  EXPECT_GT(lamp.size, 0.0f);
  EXPECT_GT(lamp.rangeM, lamp.size);
  const Light& spot = room.lights[1];
  EXPECT_EQ(spot.type, LightType::Spot);
  EXPECT_GT(spot.innerConeAngleRad, 0.0f);
  EXPECT_LT(spot.innerConeAngleRad, spot.coneAngleRad);
  EXPECT_GT(spot.rangeM, spot.size);
  for (const Light& l : room.lights) EXPECT_TRUE(l.castsShadow);
}

// night: 8 lights, each prefix the light-count sweep takes (1, 2, 4, 8) mixes point and spot
// lamps, and every lamp has a range (the far ones fade).
TEST(LampScenes, NightsFirstLightsAreMeaningfulSubsets) {
  const Scene night = makeBuiltinScene("night");
  ASSERT_EQ(night.lights.size(), 8u);
  EXPECT_GE(countOf(night, 8, LightType::Point), 3u);
  EXPECT_GE(countOf(night, 8, LightType::Spot), 3u);
  for (size_t n : {2u, 4u, 8u}) {
    EXPECT_EQ(countOf(night, n, LightType::Point), n / 2) << "the first " << n << " lights";
    EXPECT_EQ(countOf(night, n, LightType::Spot), n / 2) << "the first " << n << " lights";
  }
  // Ordered from the camera outward: each lamp is no nearer than the one before.
  float previousM = 0.0f;
  for (const Light& l : night.lights) {
    EXPECT_GT(l.rangeM, 0.0f);
    EXPECT_TRUE(l.castsShadow);
    const float distanceM = glm::distance(l.position, night.camera.position);
    EXPECT_GE(distanceM, previousM);
    previousM = distanceM;
  }
}

// KHR_lights_punctual: the point light stays a point light at its node's position with its sphere
// (extras.size), range and colour; the spot keeps its inner and outer cone angles and its range,
// and shines down its node's -Z.
TEST(LampScenes, GltfPointAndSpotLightsImportAsWritten) {
  const Scene s = loadScene((std::filesystem::path(PENUMBRA_TEST_DATA) / "models/lamps.gltf").string());
  ASSERT_EQ(s.lights.size(), 2u);
  const Light& lamp = s.lights[0];
  EXPECT_EQ(lamp.type, LightType::Point);
  EXPECT_EQ(lamp.position, glm::vec3(0.5f, 1.6f, 0.0f));
  EXPECT_FLOAT_EQ(lamp.size, 0.05f);
  EXPECT_FLOAT_EQ(lamp.rangeM, 8.0f);
  EXPECT_FLOAT_EQ(lamp.intensity, 3.0f);
  EXPECT_EQ(lamp.color, glm::vec3(1.0f, 0.85f, 0.65f));
  const Light& spot = s.lights[1];
  EXPECT_EQ(spot.type, LightType::Spot);
  EXPECT_EQ(spot.position, glm::vec3(-2.0f, 3.0f, 0.0f));
  EXPECT_NEAR(spot.direction.y, -1.0f, 1e-6f);
  EXPECT_NEAR(spot.innerConeAngleRad, 0.3f, 1e-6f);
  EXPECT_NEAR(spot.coneAngleRad, 0.6f, 1e-6f);
  EXPECT_FLOAT_EQ(spot.rangeM, 10.0f);
  EXPECT_FLOAT_EQ(spot.intensity, 6.0f);
}
