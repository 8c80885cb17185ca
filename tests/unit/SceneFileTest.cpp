#include <penumbra/Error.h>
#include <penumbra/SceneIO.h>

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include <sys/resource.h>
#include <unistd.h>

using namespace penumbra;

namespace {

// ctest runs each test in its own process, two at a time: a folder per process keeps one test
// from reading the file another is writing.
std::filesystem::path scratchDir() {
  return std::filesystem::temp_directory_path() / ("penumbra-scene-tests-" + std::to_string(getpid()));
}

std::filesystem::path writeTemp(const std::string& name, const std::string& text) {
  const auto dir = scratchDir();
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

// A camera looking straight down with the default up, a zero up or an up along the view rendered
// an empty or garbage image with exit 0 (the same view through --camera was refused).
TEST(SceneFile, CameraUpMustGiveTheImageAnUp) {
  const std::string objects = R"("lights": [{"type": "sun"}], "objects": [{"shape": "box"}])";
  std::string e = loadError(R"({"camera": {"position": [0, 10, 0], "target": [0, 0, 0]}, )" + objects + "}");
  EXPECT_NE(e.find("camera.up: the view is along the up vector (0, 1, 0)"), std::string::npos) << e;
  EXPECT_NE(e.find("(the default; set camera.up)"), std::string::npos) << e;
  e = loadError(R"({"camera": {"up": [0, 0, 0]}, )" + objects + "}");
  EXPECT_NE(e.find("camera.up: the up vector (0, 0, 0) is zero"), std::string::npos) << e;
  e = loadError(R"({"camera": {"position": [0, 0, 5], "up": [0, 0, 1]}, )" + objects + "}");
  EXPECT_NE(e.find("camera.up: the view is along the up vector (0, 0, 1)"), std::string::npos) << e;
  // Looking straight down works with an up across the view.
  EXPECT_EQ(loadError(R"({"camera": {"position": [0, 10, 0], "up": [0, 0, -1]}, )" + objects + "}"), "");
}

// The glTF path bounds light colours; the scene file did not (1e38 gave a black image).
TEST(SceneFile, LightColourAndAmbientAreBounded) {
  const std::string box = R"("objects": [{"shape": "box"}])";
  std::string e = loadError(R"({"lights": [{"type": "sun", "color": [1e38, 1, 1]}], )" + box + "}");
  EXPECT_NE(e.find("lights[0].color: 1e+38 is outside [0, 1000000]"), std::string::npos) << e;
  e = loadError(R"({"lights": [{"type": "spot", "color": [1, -0.5, 1]}], )" + box + "}");
  EXPECT_NE(e.find("lights[0].color: -0.5 is outside"), std::string::npos) << e;
  e = loadError(R"({"ambient": [0, 1e38, 0], "lights": [{"type": "sun"}], )" + box + "}");
  EXPECT_NE(e.find("ambient: 1e+38 is outside"), std::string::npos) << e;
  EXPECT_EQ(loadError(R"({"ambient": [0, 0, 0], "lights": [{"type": "sun", "color": [1000, 0, 0]}], )" + box + "}"), "");
}

// A file of 30 000 spheres reached 2.26 GB before the limit error: the shapes' totals are now
// checked before any shape is built, so the process barely grows.
TEST(SceneFile, ShapeTotalsFailBeforeAnyShapeIsBuilt) {
  constexpr int kSpheres = 30000;
  constexpr long kMaxGrowthKiB = 200 * 1024;  // the JSON document; one built sphere is 66 KiB, all 30 000 2.2 GiB
  std::string json = R"({"lights": [{"type": "sun"}], "objects": [)";
  for (int i = 0; i < kSpheres; ++i) json += std::string(i ? "," : "") + R"({"shape": "sphere", "radius": 0.25})";
  json += "]}";
  rusage before{}, after{};
  getrusage(RUSAGE_SELF, &before);
  const std::string e = loadError(json);
  getrusage(RUSAGE_SELF, &after);
  EXPECT_NE(e.find("objects: the shapes have 36750000 vertices, more than the limit of 16777216"), std::string::npos) << e;
  EXPECT_LT(after.ru_maxrss - before.ru_maxrss, kMaxGrowthKiB) << "KiB of peak memory growth";
  const std::string many = loadError(R"({"lights": [{"type": "sun"}], "objects": [)" +
                                     [] { std::string s; for (int i = 0; i < 65537; ++i) s += i ? ",{}" : "{}"; return s; }() + "]}");
  EXPECT_NE(many.find("objects: 65537 objects, more than the limit of 65536"), std::string::npos) << many;
}

// A folder, a PNG or a binary file given as a scene: a message that says so, never raw bytes.
TEST(SceneFile, NonSceneInputsSayWhatTheyAre) {
  const auto dir = scratchDir();
  std::filesystem::create_directories(dir / "folder.json");
  auto error = [](const std::string& what) {
    try {
      loadScene(what);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(error((dir / "folder.json").string()).find("folder.json: is a folder, not a scene or model file"), std::string::npos);
  const std::string png = (std::filesystem::path(PENUMBRA_TEST_DATA) / "bad/scene_binary.json").string();
  const std::string e = error(png);
  EXPECT_NE(e.find("not valid JSON: parse error at line 1, column 1"), std::string::npos) << e;
  for (char c : e) EXPECT_TRUE(c >= 0x20 && c < 0x7f) << "a raw byte in the message: " << static_cast<int>(static_cast<unsigned char>(c));
  std::ofstream(dir / "image.png", std::ios::binary) << "\x89PNG\r\n\x1a\n";
  EXPECT_NE(error((dir / "image.png").string()).find("image.png: not a scene file (.json) or a model file (.gltf, .glb, .obj)"),
            std::string::npos);
}
