// The viewer's light edits (src/viewer/LightEdit.h): what `light set N KEY VALUE` does to a
// light, which edits are refused and with what message, and that every light the viewer makes or
// converts is one a scene file can hold. The script's `light` actions: ViewerScriptTest.cpp.
#include "viewer/LightEdit.h"

#include <penumbra/Error.h>

#include <gtest/gtest.h>

#include <string>
#include <vector>

using namespace penumbra;
using namespace penumbra::viewer;

namespace {

const Aabb kBounds{glm::vec3(-2.0f, 0.0f, -2.0f), glm::vec3(2.0f, 1.0f, 2.0f)};

Light set(const Light& l, const std::string& key, const std::vector<std::string>& value) {
  return setLightField(l, key, value, kBounds);
}

// The message of the usage Error that `f` throws ("" when it throws none).
template <class F>
std::string usageMessage(F&& f) {
  try {
    f();
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Usage) << e.what();
    return e.what();
  }
  return "";
}

Light spot() {
  Light l;
  l.type = LightType::Spot;
  l.position = {0.0f, 3.0f, 0.0f};
  l.coneAngleRad = glm::radians(30.0f);
  l.innerConeAngleRad = glm::radians(25.0f);
  return l;
}

}  // namespace

TEST(ViewerLights, SetChangesOneFieldOfTheScenesKeys) {
  Light l = set(spot(), "position", {"1", "2", "3"});
  EXPECT_EQ(l.position, glm::vec3(1.0f, 2.0f, 3.0f));
  l = set(l, "position", {"-1,0.5,4"});
  EXPECT_EQ(l.position, glm::vec3(-1.0f, 0.5f, 4.0f));
  l = set(l, "target", {"-1", "0.5", "0"});
  EXPECT_NEAR(glm::length(l.direction - glm::vec3(0.0f, 0.0f, -1.0f)), 0.0f, 1e-6f);
  l = set(l, "color", {"1,0.5,0.25"});
  EXPECT_EQ(l.color, glm::vec3(1.0f, 0.5f, 0.25f));
  l = set(set(l, "intensity", {"40"}), "size", {"0.1"});
  EXPECT_FLOAT_EQ(l.intensity, 40.0f);
  EXPECT_FLOAT_EQ(l.size, 0.1f);
  l = set(l, "range", {"12"});
  EXPECT_FLOAT_EQ(l.rangeM, 12.0f);
  l = set(l, "castsShadow", {"off"});
  EXPECT_FALSE(l.castsShadow);
  l = set(l, "mapSize", {"512"});
  EXPECT_EQ(l.shadow.mapSize, 512);
  l = set(l, "mapSize", {"0"});
  EXPECT_EQ(l.shadow.mapSize, 0);
  l = set(l, "updates", {"2"});
  EXPECT_EQ(l.shadow.updates, (MapUpdates{MapUpdates::Policy::Budget, 2}));
  l = set(l, "updates", {"invalid"});
  EXPECT_EQ(l.shadow.updates, MapUpdates{MapUpdates::Policy::WhenInvalid});
  l = set(l, "updates", {"default"});
  EXPECT_FALSE(l.shadow.updates);
  // A narrower outer cone narrows the inner one with it; the inner one alone stays inside.
  l = set(l, "outerConeDeg", {"10"});
  EXPECT_NEAR(glm::degrees(l.coneAngleRad), 10.0f, 1e-4f);
  EXPECT_NEAR(glm::degrees(l.innerConeAngleRad), 10.0f, 1e-4f);
  l = set(l, "innerConeDeg", {"4"});
  EXPECT_NEAR(glm::degrees(l.innerConeAngleRad), 4.0f, 1e-4f);
}

TEST(ViewerLights, RefusedEditsSayWhy) {
  Light sun;
  EXPECT_NE(usageMessage([&] { set(sun, "position", {"1", "2", "3"}); }).find("position: the light is a sun"), std::string::npos);
  EXPECT_NE(usageMessage([&] { set(sun, "outerConeDeg", {"20"}); }).find("which has no cone"), std::string::npos);
  EXPECT_NE(usageMessage([&] { set(sun, "size", {"0.9"}); }).find("angular radius"), std::string::npos);
  EXPECT_NE(usageMessage([&] { set(sun, "colour", {"1"}); }).find("unknown light key 'colour'"), std::string::npos);
  EXPECT_NE(usageMessage([&] { set(sun, "direction", {"0", "0", "0"}); }).find("must not be zero"), std::string::npos);
  EXPECT_NE(usageMessage([&] { set(sun, "intensity", {"-1"}); }).find("intensity"), std::string::npos);
  Light point = set(spot(), "type", {"point"});
  EXPECT_NE(usageMessage([&] { set(point, "direction", {"0", "-1", "0"}); }).find("no direction"), std::string::npos);
  const Light s = spot();
  EXPECT_NE(usageMessage([&] { set(s, "innerConeDeg", {"40"}); }).find("inner cone angle"), std::string::npos);
  EXPECT_NE(usageMessage([&] { set(s, "outerConeDeg", {"90"}); }).find("outer cone angle"), std::string::npos);
  EXPECT_NE(usageMessage([&] { set(set(s, "size", {"0.5"}), "range", {"0.2"}); }).find("must exceed the light's size"),
            std::string::npos);
  EXPECT_NE(usageMessage([&] { set(s, "mapSize", {"8"}); }).find("map"), std::string::npos);
  EXPECT_NE(usageMessage([&] { set(s, "updates", {"0"}); }).find("expected every, invalid or a number"), std::string::npos);
  EXPECT_NE(usageMessage([&] { set(s, "castsShadow", {"maybe"}); }).find("on or off"), std::string::npos);
  EXPECT_NE(usageMessage([&] { set(s, "position", {"1", "2"}); }).find("X Y Z or X,Y,Z"), std::string::npos);
  EXPECT_NE(usageMessage([&] { set(s, "type", {"lamp"}); }).find("unknown light type 'lamp'"), std::string::npos);
}

TEST(ViewerLights, NewAndConvertedLightsAreOnesAFileCanHold) {
  Camera camera;
  camera.position = {0.0f, 2.0f, 6.0f};
  for (LightType type : {LightType::Directional, LightType::Spot, LightType::Point})
    for (size_t index = 0; index < 8; ++index) {
      const Light l = makeLight(type, kBounds, camera, index);
      EXPECT_EQ(l.type, type);
      EXPECT_EQ(lightProblem(l), "") << lightLabel(l, index);
      for (LightType to : {LightType::Directional, LightType::Spot, LightType::Point}) {
        Light converted = l;
        changeLightType(converted, to, kBounds);
        EXPECT_EQ(converted.type, to);
        EXPECT_EQ(lightProblem(converted), "") << lightLabel(l, index) << " → " << lightTypeName(to);
      }
    }
  EXPECT_EQ(lightLabel(spot(), 2), "light 2 (spot)");
  EXPECT_EQ(parseLightType("point"), LightType::Point);
  EXPECT_STREQ(cubeFaceName(0), "+X");
  EXPECT_STREQ(cubeFaceName(5), "-Z");
}
