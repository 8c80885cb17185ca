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

std::string loadError(const std::string& json, const LoadOptions& options = {}) {
  const auto path = writeTemp("t.json", json);
  try {
    loadSceneFile(path, options);
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

// A file of 30 000 spheres reached 2.26 GB before the limit error: the memory the shapes will take
// is now estimated before any shape is built, so the process barely grows (the limit here is
// 256 MiB, as --max-memory 256M would set it: 36.75 M vertices need about 2.3 GiB).
TEST(SceneFile, ShapeTotalsFailBeforeAnyShapeIsBuilt) {
  constexpr int kSpheres = 30000;
  constexpr long kMaxGrowthKiB = 200 * 1024;  // the JSON document; one built sphere is 66 KiB, all 30 000 2.2 GiB
  std::string json = R"({"lights": [{"type": "sun"}], "objects": [)";
  for (int i = 0; i < kSpheres; ++i) json += std::string(i ? "," : "") + R"({"shape": "sphere", "radius": 0.25})";
  json += "]}";
  rusage before{}, after{};
  getrusage(RUSAGE_SELF, &before);
  LoadOptions limit;
  limit.maxMemoryBytes = uint64_t(256) << 20;
  const std::string e = loadError(json, limit);
  getrusage(RUSAGE_SELF, &after);
  EXPECT_NE(e.find("triangles and about 36750000 vertices need about"), std::string::npos) << e;
  EXPECT_NE(e.find("more than the --max-memory limit of 256 MiB"), std::string::npos) << e;
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

// Every check of a light entry (SceneFile.cpp readLight, docs/scenes.md): the message names the
// light and the field.
TEST(SceneFile, BadLightEntriesNameTheField) {
  struct Case {
    const char* light;
    const char* message;
  };
  const Case cases[] = {
      {R"({"type": "area"})", "lights[1].type: unknown light type 'area' (sun, spot or point)"},
      {R"({"type": 3})", "lights[1].type: expected a string"},
      {R"({"type": "sun", "direction": [0, 0, 0]})", "lights[1].direction: must not be zero"},
      {R"({"type": "sun", "direction": [0, -1]})", "lights[1].direction: expected an array of 3 numbers"},
      {R"({"type": "sun", "size": 0.6})", "lights[1].size: 0.6 is outside [0, 0.5]"},
      {R"({"type": "sun", "position": [0, 1, 0]})", "lights[1].position: unknown key"},
      {R"({"type": "sun", "range": 5})", "lights[1].range: unknown key"},
      {R"({"type": "point", "direction": [0, -1, 0]})", "lights[1].direction: unknown key"},
      {R"({"type": "point", "outerConeDeg": 30})", "lights[1].outerConeDeg: unknown key"},
      {R"({"type": "point", "position": [0, 1e39, 0]})", "lights[1].position: expected an array of 3 numbers"},
      {R"({"type": "point", "position": [0, "up", 0]})", "lights[1].position: expected an array of 3 numbers"},
      {R"({"type": "point", "position": [2e6, 1, 0]})", "lights[1].position: 2000000 is outside [-1000000, 1000000]"},
      {R"({"type": "point", "size": -0.1})", "lights[1].size: -0.1 is outside [0, 100]"},
      {R"({"type": "point", "size": 150})", "lights[1].size: 150 is outside [0, 100]"},
      {R"({"type": "point", "range": -2})", "lights[1].range: -2 is outside [0, 1000000]"},
      {R"({"type": "point", "size": 0.5, "range": 0.5})", "lights[1].range: 0.5 m must exceed the light's size 0.5 m"},
      {R"({"type": "spot", "size": 0.1, "range": 0.05})", "lights[1].range: 0.05 m must exceed the light's size 0.1 m"},
      {R"({"type": "spot", "position": [0, 3, 0], "target": [0, 3, 0]})", "lights[1].target: equals the position"},
      {R"({"type": "spot", "direction": [1, 0, 0], "target": [0, 0, 0]})", "lights[1].target: give target or direction, not both"},
      {R"({"type": "spot", "outerConeDeg": 90})", "lights[1].outerConeDeg: 90 is outside [1, 80.2"},
      {R"({"type": "spot", "outerConeDeg": 0.5})", "lights[1].outerConeDeg: 0.5 is outside [1, 80.2"},
      {R"({"type": "spot", "coneAngleDeg": 120})", "lights[1].coneAngleDeg: 120 is outside [1, 80.2"},
      {R"({"type": "spot", "coneAngleDeg": 30, "outerConeDeg": 30})", "lights[1].coneAngleDeg: give outerConeDeg or coneAngleDeg, not both"},
      {R"({"type": "spot", "innerConeDeg": 40, "outerConeDeg": 30})", "lights[1].innerConeDeg: 40 is outside [0, 30]"},
      {R"({"type": "spot", "innerConeDeg": -5})", "lights[1].innerConeDeg: -5 is outside [0, "},
      {R"({"type": "spot", "castsShadow": "yes"})", "lights[1].castsShadow: expected true or false"},
      {R"({"type": "spot", "intensity": -1})", "lights[1].intensity: -1 is outside [0, 1000000]"},
      {R"({"type": "point", "shadow": {"mapSize": 8}})", "lights[1].shadow.mapSize: 8 is outside [16, 16384]"},
      {R"({"type": "point", "shadow": {"mapSize": 32768}})", "lights[1].shadow.mapSize: 32768 is outside [16, 16384]"},
      {R"({"type": "point", "shadow": {"mapSize": 1000.5}})", "lights[1].shadow.mapSize: 1000.5 is not a whole number"},
      {R"({"type": "point", "shadow": {"technique": "pcf"}})", "lights[1].shadow.technique: unknown key"},
      {R"({"type": "point", "shadow": {"filter": 3}})", "lights[1].shadow.filter: expected"},
      {R"({"type": "point", "shadow": {"updates": 0}})", "lights[1].shadow.updates: 0 is outside [1, 1000000]"},
      {R"({"type": "point", "shadow": {"updates": 2.5}})", "lights[1].shadow.updates: 2.5 is not a whole number"},
      {R"({"type": "point", "shadow": {"updates": "0"}})", "lights[1].shadow.updates: map updates '0': expected every, invalid or a number"},
      {R"({"type": "point", "shadow": {"updates": "sometimes"}})", "lights[1].shadow.updates: map updates 'sometimes': expected"},
      // As a string the number has the number's bound.
      {R"({"type": "point", "shadow": {"updates": "99999999"}})", "lights[1].shadow.updates: map updates '99999999': expected every, invalid or a number of maps per frame in [1, 1000000]"},
      {R"({"type": "point", "shadow": {"updates": true}})", "lights[1].shadow.updates: expected \"every\", \"invalid\" or a number"},
      {R"({"type": "point", "shadow": {"params": {"pcf.radiusTexels": [2]}}})",
       "lights[1].shadow.params.pcf.radiusTexels: expected a number or a name"},
      {R"({"type": "point", "shadow": 512})", "lights[1].shadow: expected an object"},
      {R"({"type": "point", "radius": 0.1})", "lights[1].radius: unknown key"},
      {R"("point")", "lights[1]: expected an object"},
  };
  // The bad entry is the second light: the message must say which one.
  const std::string good = R"({"type": "sun"})", box = R"("objects": [{"shape": "box"}])";
  for (const Case& c : cases) {
    const std::string e = loadError(R"({"lights": [)" + good + ", " + c.light + "], " + box + "}");
    EXPECT_NE(e.find(c.message), std::string::npos) << c.light << " gave: " << e;
    EXPECT_EQ(e.find('\n'), std::string::npos) << "one line: " << e;
  }
}

// Each light has its own maps and visibility layer: a file with more than kMaxLights is refused
// by name (it reached Shadows::render, which exited 2 without naming the file).
TEST(SceneFile, TooManyLightsAreRefusedByName) {
  std::string lights;
  for (size_t i = 0; i <= kMaxLights; ++i) lights += std::string(i ? ", " : "") + R"({"type": "point", "position": [0, 2, 0]})";
  const std::string e = loadError(R"({"lights": [)" + lights + R"(], "objects": [{"shape": "box"}]})");
  EXPECT_NE(e.find("t.json: lights: 17 lights, more than the limit of 16"), std::string::npos) << e;
}

// Every light key read back: a point light, a spot with both cones and a range, the overrides.
TEST(SceneFile, LightsKeepEveryKey) {
  const Scene s = loadSceneFile(writeTemp("lights.json", R"({"lights": [
      {"type": "point", "position": [1, 2, 3], "size": 0.05, "range": 6, "color": [1, 0.8, 0.6], "intensity": 3,
       "shadow": {"mapSize": 256, "params": {"pcf.radiusTexels": 2, "pcf.kernel": "poisson"}, "updates": "invalid"}},
      {"type": "spot", "position": [0, 3, 0], "target": [0, 0, 0], "innerConeDeg": 20, "outerConeDeg": 35, "size": 0.04,
       "range": 8, "castsShadow": false},
      {"type": "spot", "position": [0, 3, 0], "direction": [0, -2, 0], "coneAngleDeg": 30, "shadow": {"updates": 3}},
      {"type": "sun", "direction": [0, -3, 0], "size": 0.01}],
    "objects": [{"shape": "box"}]})"));
  ASSERT_EQ(s.lights.size(), 4u);
  const Light& point = s.lights[0];
  EXPECT_EQ(point.type, LightType::Point);
  EXPECT_EQ(point.position, glm::vec3(1, 2, 3));
  EXPECT_FLOAT_EQ(point.size, 0.05f);
  EXPECT_FLOAT_EQ(point.rangeM, 6.0f);
  EXPECT_EQ(point.color, glm::vec3(1, 0.8f, 0.6f));
  EXPECT_FLOAT_EQ(point.intensity, 3.0f);
  EXPECT_TRUE(point.castsShadow);
  EXPECT_EQ(point.shadow.mapSize, 256);
  // nlohmann::json keeps an object's keys sorted: the params come in name order, not the file's.
  using Param = std::pair<std::string, std::string>;
  EXPECT_EQ(point.shadow.params, (std::vector<Param>{{"pcf.kernel", "poisson"}, {"pcf.radiusTexels", "2"}}));
  const Light& spot = s.lights[1];
  EXPECT_EQ(spot.type, LightType::Spot);
  EXPECT_NEAR(spot.direction.y, -1.0f, 1e-6f);
  EXPECT_NEAR(spot.innerConeAngleRad, glm::radians(20.0f), 1e-6f);
  EXPECT_NEAR(spot.coneAngleRad, glm::radians(35.0f), 1e-6f);
  EXPECT_FLOAT_EQ(spot.rangeM, 8.0f);
  EXPECT_FALSE(spot.castsShadow);
  EXPECT_EQ(spot.shadow.mapSize, 0) << "no override: the scene's size";
  EXPECT_EQ(point.shadow.updates, MapUpdates{MapUpdates::Policy::WhenInvalid});
  EXPECT_FALSE(spot.shadow.updates) << "no override: --map-updates";
  EXPECT_EQ(s.lights[2].shadow.updates, (MapUpdates{MapUpdates::Policy::Budget, 3}));
  // coneAngleDeg, the older name of the outer angle; without innerConeDeg the light fades over
  // the cone's last 5 degrees.
  EXPECT_NEAR(s.lights[2].coneAngleRad, glm::radians(30.0f), 1e-6f);
  EXPECT_NEAR(s.lights[2].innerConeAngleRad, glm::radians(25.0f), 1e-6f);
  EXPECT_EQ(s.lights[2].direction, glm::vec3(0, -1, 0));
  EXPECT_EQ(s.lights[3].type, LightType::Directional);
  EXPECT_FLOAT_EQ(s.lights[3].size, 0.01f);
}

// An object's transmittance makes it a translucent caster: the share of light of each colour
// that passes through it. Out of [0, 1], or beside a model file (which brings its own materials),
// it is refused by name.
TEST(SceneFile, TransmittanceMakesATranslucentCaster) {
  const Scene s = loadSceneFile(writeTemp("glass.json", R"({"lights": [{"type": "sun"}], "objects": [
    {"shape": "box"},
    {"shape": "plane", "color": [0.9, 0.3, 0.2], "transmittance": [0.9, 0.3, 0.2], "translate": [0, 1, 0]}]})"));
  EXPECT_FALSE(s.materials[s.objects[0].material].translucent());
  EXPECT_EQ(s.materials[s.objects[1].material].transmittance, glm::vec3(0.9f, 0.3f, 0.2f));
  EXPECT_TRUE(s.materials[s.objects[1].material].translucent());
  std::string e = loadError(R"({"lights": [{"type": "sun"}], "objects": [{"shape": "box", "transmittance": [0.5, 1.2, 0]}]})");
  EXPECT_NE(e.find("objects[0].transmittance: each component must be in [0, 1]"), std::string::npos) << e;
  e = loadError(R"({"lights": [{"type": "sun"}], "objects": [{"file": "m.obj", "transmittance": [0.5, 0.5, 0.5]}]})");
  EXPECT_NE(e.find("objects[0].transmittance"), std::string::npos) << e;
  EXPECT_TRUE(makeBuiltinScene("glass").materials[makeBuiltinScene("glass").objects[1].material].translucent())
      << "the glass scene's panes are translucent";
}
