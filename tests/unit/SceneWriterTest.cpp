// "Save settings" (src/viewer/SceneWriter.h): what the viewer writes loads back as the same
// scene: geometry, camera, light and technique.
#include "viewer/SceneWriter.h"

#include <penumbra/Error.h>
#include "techniques/Registry.h"
#include <penumbra/SceneIO.h>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <unistd.h>

using namespace penumbra;
using namespace penumbra::viewer;

namespace {

constexpr float kEpsM = 2e-3f;  // 7 significant digits on positions of a few metres, and rotations

std::filesystem::path tempFile(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / ("penumbra-scenewriter-" + std::to_string(getpid()));
  std::filesystem::create_directories(dir);
  return dir / name;
}

void expectSameBounds(const Aabb& a, const Aabb& b, const std::string& what) {
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(a.lo[i], b.lo[i], kEpsM) << what;
    EXPECT_NEAR(a.hi[i], b.hi[i], kEpsM) << what;
  }
}

}  // namespace

TEST(SceneWriter, DecomposesTranslateRotateScale) {
  const glm::mat4 m = glm::translate(glm::mat4(1), {1, 2, 3}) * glm::rotate(glm::mat4(1), glm::radians(30.0f), {0, 1, 0}) *
                      glm::rotate(glm::mat4(1), glm::radians(-20.0f), {1, 0, 0}) *
                      glm::rotate(glm::mat4(1), glm::radians(70.0f), {0, 0, 1}) * glm::scale(glm::mat4(1), {2, 0.5f, 1});
  const Trs t = decomposeTransform(m);
  EXPECT_NEAR(t.translate.z, 3.0f, 1e-5f);
  EXPECT_NEAR(t.rotateDeg.x, -20.0f, 1e-3f);
  EXPECT_NEAR(t.rotateDeg.y, 30.0f, 1e-3f);
  EXPECT_NEAR(t.rotateDeg.z, 70.0f, 1e-3f);
  EXPECT_NEAR(t.scale.x, 2.0f, 1e-5f);
  EXPECT_NEAR(t.scale.y, 0.5f, 1e-5f);
  glm::mat4 shear(1.0f);
  shear[1][0] = 0.5f;
  EXPECT_THROW(decomposeTransform(shear), Error);
}

TEST(SceneWriter, EveryBuiltinSceneRoundTrips) {
  for (const std::string& name : builtinSceneNames()) {
    Scene s = makeBuiltinScene(name);
    s.camera.position += glm::vec3(0.5f, 0.25f, 0.0f);  // as moved in the viewer
    s.lights.front().size *= 1.5f;
    Technique technique(projectionIds().back(), filterIds().back());
    technique.setMapSize(1024);
    const std::span<const ParamDesc> filterTable = technique.filterValues().paramDescs();
    const ParamDesc& d = filterTable.empty() ? technique.projectionValues().paramDescs().front() : filterTable.front();
    const float changed = d.isChoice() ? d.max : d.min;  // a non-default value
    technique.set(d.key, changed);

    const auto path = tempFile(name + ".json");
    saveSceneFile(path, s, technique);
    const Scene back = loadSceneFile(path);
    ASSERT_EQ(back.objects.size(), s.objects.size()) << name;
    for (size_t i = 0; i < s.objects.size(); ++i) {
      const Object& a = s.objects[i];
      const Object& b = back.objects[i];
      EXPECT_EQ(a.name, b.name);
      EXPECT_EQ(a.castsShadow, b.castsShadow) << a.name;
      expectSameBounds(s.meshes[a.mesh].bounds().transformed(a.worldFromObject),
                       back.meshes[b.mesh].bounds().transformed(b.worldFromObject), name + ": " + a.name);
      EXPECT_NEAR(glm::length(s.materials[a.material].baseColor - back.materials[b.material].baseColor), 0.0f, 1e-5f);
      EXPECT_NEAR(glm::length(s.materials[a.material].transmittance - back.materials[b.material].transmittance), 0.0f, 1e-5f)
          << name << ": " << a.name;
    }
    EXPECT_NEAR(glm::length(back.camera.position - s.camera.position), 0.0f, kEpsM) << name;
    EXPECT_NEAR(glm::length(back.camera.target - s.camera.target), 0.0f, kEpsM) << name;
    EXPECT_NEAR(back.camera.fovYRad, s.camera.fovYRad, 1e-5f) << name;
    const Light& la = s.lights.front();
    const Light& lb = back.lights.front();
    EXPECT_EQ(la.type, lb.type) << name;
    EXPECT_NEAR(lb.size, la.size, 1e-6f) << name;
    EXPECT_NEAR(glm::length(lb.direction - la.direction), 0.0f, 1e-5f) << name;
    if (la.type == LightType::Spot) {
      EXPECT_NEAR(glm::length(lb.position - la.position), 0.0f, kEpsM) << name;
    }
    EXPECT_EQ(back.shadow.projection, technique.projection());
    EXPECT_EQ(back.shadow.filter, technique.filter());
    EXPECT_EQ(back.shadow.mapSize, 1024);
    bool found = false;
    for (const auto& [key, value] : back.shadow.params)
      if (key == d.key) {
        found = true;
        EXPECT_EQ(value, formatParamValue(d, changed)) << key;
      }
    EXPECT_TRUE(found) << d.key;
  }
}

TEST(SceneWriter, FileScenesKeepTheirObjectsAsWritten) {
  const auto src = tempFile("source.json");
  std::ofstream(src) << R"({"name": "mine", "lights": [{"type": "sun", "direction": [0, -1, 0.2], "size": 0.01}],
    "objects": [{"name": "floor", "shape": "plane", "size": [4, 4]},
                {"name": "ball", "shape": "sphere", "radius": 0.3, "translate": [0, 1, 0]}]})";
  Scene s = loadSceneFile(src);
  s.lights.front().size = 0.04f;
  const Technique technique = Technique("uniform", "hard").setMapSize(512);
  const std::string text = sceneFileText(s, technique);
  EXPECT_NE(text.find("\"radius\": 0.3"), std::string::npos) << text;  // the original object, not a re-derived one
  EXPECT_NE(text.find("\"size\": 0.04"), std::string::npos) << text;
  const auto out = tempFile("saved.json");
  saveSceneFile(out, s, technique);
  EXPECT_NEAR(loadSceneFile(out).light().size, 0.04f, 1e-7f);
}

TEST(SceneWriter, MeshesWithoutAFileFormAreRefusedByName) {
  Scene s = makeBuiltinScene("boxes");
  s.meshes[s.objects[1].mesh].name = "teapot";
  try {
    sceneFileText(s, Technique("uniform", "hard"));
    ADD_FAILURE() << "expected an Error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("teapot"), std::string::npos) << e.what();
  }
}

// Several lights of every type, each field away from its default: what the viewer saves loads
// back light by light.
TEST(SceneWriter, EveryLightFieldOfSeveralLightsRoundTrips) {
  Scene s = makeBuiltinScene("boxes");
  Light sun;
  sun.direction = glm::normalize(glm::vec3(0.3f, -1.0f, 0.2f));
  sun.size = 0.02f;
  sun.color = {1.0f, 0.9f, 0.8f};
  sun.intensity = 2.5f;
  sun.castsShadow = false;
  Light spot;
  spot.type = LightType::Spot;
  spot.position = {1.0f, 4.0f, -2.0f};
  spot.direction = glm::normalize(glm::vec3(-0.2f, -1.0f, 0.4f));
  spot.coneAngleRad = glm::radians(35.0f);
  spot.innerConeAngleRad = glm::radians(20.0f);
  spot.rangeM = 15.0f;
  spot.size = 0.15f;
  spot.intensity = 60.0f;
  spot.shadow.mapSize = 512;
  spot.shadow.params = {{"pcf.radiusTexels", "2"}};
  spot.shadow.updates = MapUpdates{MapUpdates::Policy::Budget, 2};
  Light point;
  point.type = LightType::Point;
  point.position = {-1.5f, 2.0f, 0.5f};
  point.size = 0.05f;
  point.rangeM = 8.0f;
  point.color = {0.7f, 0.85f, 1.0f};
  point.intensity = 25.0f;
  point.shadow.mapSize = 256;
  point.shadow.updates = MapUpdates{MapUpdates::Policy::WhenInvalid};
  point.shadow.projection = "uniform";  // its own technique's ids
  point.shadow.filter = "pcss";
  s.lights = {sun, spot, point};
  const auto path = tempFile("lights.json");
  saveSceneFile(path, s, Technique("uniform", "pcf").setMapSize(1024));
  const Scene back = loadSceneFile(path);
  ASSERT_EQ(back.lights.size(), s.lights.size());
  for (size_t i = 0; i < s.lights.size(); ++i) {
    const Light& a = s.lights[i];
    const Light& b = back.lights[i];
    const std::string which = "light " + std::to_string(i);
    EXPECT_EQ(b.type, a.type) << which;
    if (a.type != LightType::Point) {
      EXPECT_NEAR(glm::length(b.direction - a.direction), 0.0f, 1e-5f) << which;
    }
    if (isPositional(a)) {
      EXPECT_NEAR(glm::length(b.position - a.position), 0.0f, kEpsM) << which;
      EXPECT_NEAR(b.rangeM, a.rangeM, 1e-5f) << which;
    }
    if (a.type == LightType::Spot) {
      EXPECT_NEAR(b.coneAngleRad, a.coneAngleRad, 1e-5f) << which;
      EXPECT_NEAR(b.innerConeAngleRad, a.innerConeAngleRad, 1e-5f) << which;
    }
    EXPECT_NEAR(b.size, a.size, 1e-6f) << which;
    EXPECT_NEAR(glm::length(b.color - a.color), 0.0f, 1e-6f) << which;
    EXPECT_NEAR(b.intensity, a.intensity, 1e-5f) << which;
    EXPECT_EQ(b.castsShadow, a.castsShadow) << which;
    EXPECT_EQ(b.shadow.mapSize, a.shadow.mapSize) << which;
    EXPECT_EQ(b.shadow.projection, a.shadow.projection) << which;
    EXPECT_EQ(b.shadow.filter, a.shadow.filter) << which;
    EXPECT_EQ(b.shadow.params, a.shadow.params) << which;
    EXPECT_EQ(b.shadow.updates, a.shadow.updates) << which;
  }
}
