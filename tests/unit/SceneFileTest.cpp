#include <penumbra/Error.h>
#include <penumbra/SceneIO.h>

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

using namespace penumbra;

namespace {

std::filesystem::path writeTemp(const std::string& name, const std::string& text) {
  const auto dir = std::filesystem::temp_directory_path() / "penumbra-scene-tests";
  std::filesystem::create_directories(dir);
  const auto path = dir / name;
  std::ofstream(path) << text;
  return path;
}

std::string loadError(const std::string& json) {
  const auto path = writeTemp("t.json", json);
  try {
    loadSceneFile(path);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

const char* kGood = R"({
  "name": "tiny",
  "camera": {"position": [0, 2, 5], "target": [0, 0, 0], "fovYDeg": 50},
  "lights": [{"type": "sun", "direction": [-0.3, -1, -0.2], "size": 0.01}],
  "objects": [
    {"name": "floor", "shape": "plane", "size": [10, 10], "castsShadow": false},
    {"name": "box", "shape": "box", "size": [1, 1, 1], "translate": [0, 0.5, 0], "color": [0.8, 0.2, 0.2]}
  ],
  "shadow": {"filter": "hard", "mapSize": 1024, "params": {"hard.bias": "slope", "hard.slopeBias": 1.5}}
})";

}  // namespace

TEST(SceneFile, LoadsAGoodFile) {
  const Scene s = loadSceneFile(writeTemp("good.json", kGood));
  EXPECT_EQ(s.name, "tiny");
  EXPECT_EQ(s.objects.size(), 2u);
  EXPECT_FALSE(s.objects[0].castsShadow);
  EXPECT_EQ(s.shadow.mapSize, 1024);
  ASSERT_EQ(s.shadow.params.size(), 2u);
  EXPECT_EQ(s.shadow.params[0].first, "hard.bias");
  EXPECT_EQ(s.shadow.params[0].second, "slope");
}

TEST(SceneFile, ErrorsNameTheFileAndTheField) {
  std::string e = loadError(R"({"lights": [{"type": "sun"}], "objects": [{"shape": "box", "colour": [1,0,0]}]})");
  EXPECT_NE(e.find("t.json"), std::string::npos) << e;
  EXPECT_NE(e.find("objects[0].colour: unknown key"), std::string::npos) << e;

  e = loadError(R"({"lights": [{"type": "sun"}], "objects": [{"shape": "box", "size": [1, 2]}]})");
  EXPECT_NE(e.find("objects[0].size"), std::string::npos) << e;

  e = loadError(R"({"lights": [{"type": "laser"}], "objects": [{"shape": "box"}]})");
  EXPECT_NE(e.find("lights[0].type"), std::string::npos) << e;

  e = loadError(R"({"lights": [{"type": "sun"}], "objects": [{"shape": "teapot"}]})");
  EXPECT_NE(e.find("objects[0].shape"), std::string::npos) << e;

  e = loadError(R"({"camera": {"fovYDeg": 500}, "lights": [{"type": "sun"}], "objects": [{"shape": "box"}]})");
  EXPECT_NE(e.find("camera.fovYDeg"), std::string::npos) << e;

  e = loadError(R"({"objects": [{"shape": "box"}]})");
  EXPECT_NE(e.find("lights"), std::string::npos) << e;

  e = loadError(R"({"lights": [{"type": "sun"}], "objects": [{"shape": "box"}], )");
  EXPECT_NE(e.find("not valid JSON"), std::string::npos) << e;
}

TEST(SceneFile, MissingFileNamesIt) {
  try {
    loadSceneFile("/nonexistent/dir/scene.json");
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/dir/scene.json"), std::string::npos);
  }
}

TEST(SceneFile, BuiltinScenesAreValid) {
  for (const std::string& name : builtinSceneNames()) {
    const Scene s = makeBuiltinScene(name);
    EXPECT_NO_THROW(s.validate()) << name;
    EXPECT_GT(s.triangleCount(), 10u) << name;
  }
}
