// Animation without GL: keys between keys (linear, slerp, step), the scene file's animation
// blocks and their errors, glTF TRS channels moving their node (and its children), and the
// animated built-ins whose pose at time 0 is the still scene.
#include "sceneio/loaders/GltfLoader.h"

#include <penumbra/Animation.h>
#include <penumbra/Error.h>
#include <penumbra/SceneIO.h>

#include <fmt/format.h>
#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include <unistd.h>

using namespace penumbra;
namespace fs = std::filesystem;

namespace {

std::string errorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

// A scene file in a fresh temporary folder.
fs::path writeScene(const std::string& name, const std::string& json) {
  const fs::path dir = fs::temp_directory_path() / fmt::format("penumbra-animation-{}", getpid());
  fs::create_directories(dir);
  const fs::path p = dir / name;
  std::ofstream(p) << json;
  return p;
}

std::string sceneWith(const std::string& objectAnimation, const std::string& lightExtra = "", const std::string& cameraExtra = "") {
  return fmt::format(R"({{
    "camera": {{"position": [0, 3, 8], "target": [0, 0, 0] {}}},
    "lights": [{{"type": "sun", "direction": [0, -1, 0] {}}}],
    "objects": [{{"shape": "plane", "size": [10, 10]}},
                {{"name": "ball", "shape": "sphere", "radius": 0.5, "translate": [0, 1, 0] {}}}]}})",
                     cameraExtra, lightExtra, objectAnimation);
}

glm::vec3 origin(const Scene& s, size_t object) { return glm::vec3(s.objects[object].worldFromObject[3]); }

}  // namespace

TEST(Animation, KeyedObjectIsWhereTheKeysSayBetweenKeys) {
  Scene s = loadSceneFile(writeScene("keys.json", sceneWith(R"(, "animation": {"keys": [
      {"timeS": 0, "translate": [0, 1, 0], "rotateDeg": [0, 0, 0]},
      {"timeS": 2, "translate": [4, 1, 0], "rotateDeg": [0, 90, 0]},
      {"timeS": 3, "translate": [4, 1, -2]}]})")));
  ASSERT_EQ(s.animation.objects.size(), 1u);
  EXPECT_FLOAT_EQ(s.animation.durationS(), 3.0f);
  poseScene(s, 0.5f);  // a quarter of the way to the second key
  EXPECT_NEAR(glm::length(origin(s, 1) - glm::vec3(1, 1, 0)), 0.0f, 1e-5f);
  // Slerp: a quarter of 90° about +Y turns local +X to (cos 22.5°, 0, -sin 22.5°).
  const glm::vec3 x = glm::vec3(s.objects[1].worldFromObject * glm::vec4(1, 0, 0, 0));
  EXPECT_NEAR(x.x, std::cos(glm::radians(22.5f)), 1e-5f);
  EXPECT_NEAR(x.z, -std::sin(glm::radians(22.5f)), 1e-5f);
  poseScene(s, 2.5f);  // translation keyed at 3 s, rotation holds its last key (2 s)
  EXPECT_NEAR(glm::length(origin(s, 1) - glm::vec3(4, 1, -1)), 0.0f, 1e-5f);
  poseScene(s, 10.0f);  // after the last key: the last key
  EXPECT_NEAR(glm::length(origin(s, 1) - glm::vec3(4, 1, -2)), 0.0f, 1e-5f);
  poseScene(s, -1.0f);  // before the first: the first
  EXPECT_NEAR(glm::length(origin(s, 1) - glm::vec3(0, 1, 0)), 0.0f, 1e-5f);
  EXPECT_EQ(s.objects[0].worldFromObject, glm::mat4(1.0f)) << "the floor is not animated";
}

TEST(Animation, StepKeysHoldUntilTheNextKey) {
  Scene s = loadSceneFile(writeScene("step.json", sceneWith(R"(, "animation": {"interpolation": "step", "keys": [
      {"timeS": 0, "translate": [0, 1, 0]}, {"timeS": 1, "translate": [2, 1, 0]}]})")));
  poseScene(s, 0.99f);
  EXPECT_NEAR(origin(s, 1).x, 0.0f, 1e-6f);
  poseScene(s, 1.0f);
  EXPECT_NEAR(origin(s, 1).x, 2.0f, 1e-6f);
}

TEST(Animation, SunPathLightAndCameraKeys) {
  Scene s = loadSceneFile(writeScene("sun.json", sceneWith("",
      R"(, "sunPath": {"keys": [{"timeS": 0, "azimuthDeg": 0, "elevationDeg": 30}, {"timeS": 1, "azimuthDeg": 90, "elevationDeg": 30}]})",
      R"(, "animation": {"keys": [{"timeS": 0, "position": [0, 3, 8]}, {"timeS": 4, "position": [0, 3, 4], "target": [0, 0, -4]}]})")));
  poseScene(s, 0.5f);
  const glm::vec3 toSun = -s.lights[0].direction;
  EXPECT_NEAR(glm::degrees(std::asin(toSun.y)), 30.0f, 1e-3f);
  EXPECT_NEAR(glm::degrees(std::atan2(toSun.x, toSun.z)), 45.0f, 1e-3f);
  poseScene(s, 2.0f);
  EXPECT_NEAR(s.camera.position.z, 6.0f, 1e-5f);
  EXPECT_NEAR(s.camera.target.z, -4.0f, 1e-5f) << "one target key: held";
  // A spot swinging about its hook.
  Scene lamp = loadSceneFile(writeScene("lamp.json", R"({
    "lights": [{"type": "spot", "position": [0, 2, 0], "direction": [0, -1, 0],
                "animation": {"pivot": [0, 3, 0], "keys": [{"timeS": 0, "rotateDeg": [0, 0, 0]}, {"timeS": 1, "rotateDeg": [0, 0, 90]}]}}],
    "objects": [{"shape": "plane"}]})"));
  poseScene(lamp, 1.0f);
  EXPECT_NEAR(glm::length(lamp.lights[0].position - glm::vec3(1, 3, 0)), 0.0f, 1e-5f);
  EXPECT_NEAR(glm::length(lamp.lights[0].direction - glm::vec3(1, 0, 0)), 0.0f, 1e-5f);
}

TEST(Animation, BadBlocksNameTheField) {
  const auto load = [](const std::string& json) { return errorOf([&] { loadSceneFile(writeScene("bad.json", json)); }); };
  EXPECT_NE(load(sceneWith(R"(, "animation": {"keys": [{"timeS": 1, "translate": [0, 0, 0]}, {"timeS": 1, "translate": [1, 0, 0]}]})"))
                .find("objects[1].animation.keys[1].timeS: 1 s must be after the previous key's 1 s"),
            std::string::npos);
  EXPECT_NE(load(sceneWith(R"(, "animation": {"keys": [{"timeS": 0, "spin": 3}]})")).find("objects[1].animation.keys[0].spin: unknown key"),
            std::string::npos);
  EXPECT_NE(load(sceneWith(R"(, "animation": {"interpolation": "cubic", "keys": [{"timeS": 0}]})"))
                .find("objects[1].animation.interpolation: expected \"linear\" or \"step\""),
            std::string::npos);
  EXPECT_NE(load(sceneWith(R"(, "animation": {"keys": []})")).find("objects[1].animation.keys: expected a non-empty array"),
            std::string::npos);
  EXPECT_NE(load(sceneWith("", R"(, "sunPath": {"keys": [{"timeS": 0, "azimuthDeg": 0}]})"))
                .find("lights[0].sunPath.keys[0].elevationDeg: missing"),
            std::string::npos);
  // A sun is a direction: keys that would move it, or a pivot to swing it about, change nothing.
  EXPECT_NE(load(sceneWith("", R"(, "animation": {"keys": [{"timeS": 0, "rotateDeg": [0, 0, 0]}, {"timeS": 1, "translate": [5, 0, 0]}]})"))
                .find("lights[0].animation.keys[1].translate: a sun has no position"),
            std::string::npos);
  EXPECT_NE(load(sceneWith("", R"(, "animation": {"pivot": [0, 3, 0], "keys": [{"timeS": 0, "rotateDeg": [0, 0, 30]}]})"))
                .find("lights[0].animation.pivot: a sun has no position"),
            std::string::npos);
}

// "dynamic": absent = animated; true marks a still object dynamic; false on an animated object
// is an error naming the object and the field.
TEST(Animation, DynamicFlagParsesAndAnimatedObjectsCannotBeStatic) {
  const std::string keys = R"("animation": {"keys": [{"timeS": 0, "translate": [0, 1, 0]}, {"timeS": 1, "translate": [1, 1, 0]}]})";
  const Scene still = loadSceneFile(writeScene("still.json", sceneWith("")));
  EXPECT_FALSE(still.objects[1].dynamic);
  const Scene declared = loadSceneFile(writeScene("declared.json", sceneWith(R"(, "dynamic": true)")));
  EXPECT_TRUE(declared.objects[1].dynamic);
  EXPECT_FALSE(declared.objects[0].dynamic);
  const Scene animated = loadSceneFile(writeScene("animated.json", sceneWith(", " + keys)));
  EXPECT_TRUE(animated.animation.movingObjects(animated.objects.size())[1]);
  const Scene both = loadSceneFile(writeScene("both.json", sceneWith(", \"dynamic\": true, " + keys)));
  EXPECT_TRUE(both.objects[1].dynamic);
  const auto load = [](const std::string& json) { return errorOf([&] { loadSceneFile(writeScene("bad.json", json)); }); };
  EXPECT_NE(load(sceneWith(", \"dynamic\": false, " + keys)).find("objects[1].dynamic: 'ball' is animated, so it cannot be static"),
            std::string::npos);
  EXPECT_NE(load(sceneWith(R"(, "dynamic": "yes")")).find("objects[1].dynamic: expected true or false"), std::string::npos);
}

// A glTF whose node 1 (a child of node 0, which holds the mesh) is keyed: translation LINEAR from
// (0,0,0) at 1 s to (2,0,0) at 3 s and rotation STEP; node 2 below it moves with it.
TEST(Animation, GltfAnimationMovesItsNode) {
  const std::vector<glm::vec3> positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  const std::vector<uint16_t> indices = {0, 1, 2, 0};  // padded to 4 bytes
  const std::vector<float> times = {1.0f, 3.0f};
  const std::vector<glm::vec3> translations = {{0, 0, 0}, {2, 0, 0}};
  const float s = std::sqrt(0.5f);
  const std::vector<glm::vec4> rotations = {{0, 0, 0, 1}, {0, s, 0, s}};  // x, y, z, w: 90° about +Y
  std::vector<uint8_t> bytes;
  const auto append = [&](const void* p, size_t n) {
    const size_t at = bytes.size();
    const auto* b = static_cast<const uint8_t*>(p);
    bytes.insert(bytes.end(), b, b + n);
    return at;
  };
  const size_t pos = append(positions.data(), 36), idx = append(indices.data(), 8), tim = append(times.data(), 8),
               tra = append(translations.data(), 24), rot = append(rotations.data(), 32);
  std::string b64;
  {
    static const char* kAlphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    for (size_t i = 0; i < bytes.size(); i += 3) {
      uint32_t v = static_cast<uint32_t>(bytes[i]) << 16;
      if (i + 1 < bytes.size()) v |= static_cast<uint32_t>(bytes[i + 1]) << 8;
      if (i + 2 < bytes.size()) v |= bytes[i + 2];
      for (size_t k = 0; k < 4; ++k) b64 += i + k <= bytes.size() ? kAlphabet[(v >> (18 - 6 * k)) & 63] : '=';
    }
  }
  const std::string json = fmt::format(R"({{"asset": {{"version": "2.0"}},
    "buffers": [{{"byteLength": {}, "uri": "data:application/octet-stream;base64,{}"}}],
    "bufferViews": [{{"buffer": 0, "byteOffset": {}, "byteLength": 36}}, {{"buffer": 0, "byteOffset": {}, "byteLength": 6}},
                    {{"buffer": 0, "byteOffset": {}, "byteLength": 8}}, {{"buffer": 0, "byteOffset": {}, "byteLength": 24}},
                    {{"buffer": 0, "byteOffset": {}, "byteLength": 32}}],
    "accessors": [{{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3"}},
                  {{"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"}},
                  {{"bufferView": 2, "componentType": 5126, "count": 2, "type": "SCALAR"}},
                  {{"bufferView": 3, "componentType": 5126, "count": 2, "type": "VEC3"}},
                  {{"bufferView": 4, "componentType": 5126, "count": 2, "type": "VEC4"}}],
    "meshes": [{{"primitives": [{{"attributes": {{"POSITION": 0}}, "indices": 1}}]}}],
    "extensionsUsed": ["KHR_lights_punctual"],
    "extensions": {{"KHR_lights_punctual": {{"lights": [{{"type": "spot", "intensity": 5, "spot": {{"outerConeAngle": 0.5}}}}]}}}},
    "cameras": [{{"type": "perspective", "perspective": {{"yfov": 0.8, "znear": 0.1}}}}],
    "nodes": [{{"mesh": 0, "translation": [0, 0, 5]}}, {{"name": "mover", "mesh": 0, "children": [2, 3]}}, {{"mesh": 0, "translation": [0, 1, 0]}},
              {{"name": "rig", "translation": [0, 0, 1], "camera": 0, "extensions": {{"KHR_lights_punctual": {{"light": 0}}}}}}],
    "scenes": [{{"nodes": [0, 1]}}],
    "animations": [{{"samplers": [{{"input": 2, "output": 3}}, {{"input": 2, "output": 4, "interpolation": "STEP"}}],
                     "channels": [{{"sampler": 0, "target": {{"node": 1, "path": "translation"}}}},
                                  {{"sampler": 1, "target": {{"node": 1, "path": "rotation"}}}}]}}]}})",
                                       bytes.size(), b64, pos, idx, tim, tra, rot);
  Scene scene = loaders::loadGltfFromMemory({reinterpret_cast<const uint8_t*>(json.data()), json.size()}, "anim.gltf", "").scene;
  ASSERT_EQ(scene.objects.size(), 3u);
  EXPECT_EQ(scene.animation.objects.size(), 2u) << "the keyed node and its child";
  EXPECT_FLOAT_EQ(scene.animation.durationS(), 3.0f);
  poseScene(scene, 2.0f);  // halfway: translation (1,0,0), rotation still the first STEP key
  EXPECT_NEAR(glm::length(origin(scene, 1) - glm::vec3(1, 0, 0)), 0.0f, 1e-5f);
  EXPECT_NEAR(glm::length(origin(scene, 2) - glm::vec3(1, 1, 0)), 0.0f, 1e-5f);
  EXPECT_NEAR(glm::length(origin(scene, 0) - glm::vec3(0, 0, 5)), 0.0f, 1e-6f) << "an unanimated node stays";
  poseScene(scene, 3.0f);  // the last keys: rotation 90° about +Y turns local +X to -Z
  const glm::vec3 x = glm::vec3(scene.objects[1].worldFromObject * glm::vec4(1, 0, 0, 0));
  EXPECT_NEAR(glm::length(x - glm::vec3(0, 0, -1)), 0.0f, 1e-5f);
  EXPECT_NEAR(glm::length(origin(scene, 2) - glm::vec3(2, 1, 0)), 0.0f, 1e-5f);
  // Node 3 below the mover holds the spot light and the camera, 1 m down its +Z: they turn and
  // move with it (local -Z, where both look, turns to -X).
  ASSERT_EQ(scene.lights.size(), 1u);
  EXPECT_NEAR(glm::length(scene.lights[0].position - glm::vec3(3, 0, 0)), 0.0f, 1e-5f);
  EXPECT_NEAR(glm::length(scene.lights[0].direction - glm::vec3(-1, 0, 0)), 0.0f, 1e-5f);
  EXPECT_NEAR(glm::length(scene.camera.position - glm::vec3(3, 0, 0)), 0.0f, 1e-5f);
  EXPECT_NEAR(glm::length(scene.camera.target - glm::vec3(2, 0, 0)), 0.0f, 1e-5f);
  poseScene(scene, 2.0f);
  EXPECT_NEAR(glm::length(scene.lights[0].position - glm::vec3(1, 0, 1)), 0.0f, 1e-5f);
  EXPECT_NEAR(glm::length(scene.lights[0].direction - glm::vec3(0, 0, -1)), 0.0f, 1e-5f);
  EXPECT_NEAR(glm::length(scene.camera.target - glm::vec3(1, 0, 0)), 0.0f, 1e-5f);
}

TEST(Animation, BuiltinsAtTimeZeroAreTheStillScene) {
  for (const char* name : {"boxes", "city", "room"}) {
    const Scene still = makeBuiltinScene(name);
    ASSERT_FALSE(still.animation.empty()) << name;
    EXPECT_FLOAT_EQ(still.animation.durationS(), 4.0f) << name;
    Scene posed = still;
    poseScene(posed, 0.0f);
    for (size_t i = 0; i < still.objects.size(); ++i)
      for (int c = 0; c < 4; ++c)
        EXPECT_NEAR(glm::length(posed.objects[i].worldFromObject[c] - still.objects[i].worldFromObject[c]), 0.0f, 1e-5f) << name << " " << i;
    EXPECT_NEAR(glm::length(posed.lights[0].direction - still.lights[0].direction), 0.0f, 1e-6f) << name;
    EXPECT_EQ(posed.camera.position, still.camera.position) << name;
  }
  Scene city = makeBuiltinScene("city");
  poseScene(city, 4.0f);
  EXPECT_NEAR(makeBuiltinScene("city").camera.position.z - city.camera.position.z, 5.6f, 1e-3f) << "walking at 1.4 m/s";
  Scene boxes = makeBuiltinScene("boxes");
  poseScene(boxes, 4.0f);
  EXPECT_NEAR(glm::length(origin(boxes, 4) - glm::vec3(0.0f, 0.6f, -0.2f)), 2.5f, 1e-5f) << "sphere A rolled 2.5 m";
  const glm::vec3 toSun = -boxes.lights[0].direction, toSun0 = -makeBuiltinScene("boxes").lights[0].direction;
  EXPECT_NEAR(glm::degrees(std::atan2(toSun.x, toSun.z) - std::atan2(toSun0.x, toSun0.z)), 30.0f, 1e-3f);
}

TEST(Animation, RoomLampSwingsWithItsShadeAndCord) {
  const Scene still = makeBuiltinScene("room");
  const auto named = [&](const char* name) {
    const auto it = std::find_if(still.objects.begin(), still.objects.end(), [&](const Object& o) { return o.name == name; });
    EXPECT_NE(it, still.objects.end()) << name;
    return static_cast<size_t>(it - still.objects.begin());
  };
  const size_t shade = named("lamp shade"), cord = named("lamp cord"), table = named("table top");
  // Over the 4 s the lamp, a pendulum of about 1.3 m (period about 2.3 s), passes through both
  // extremes: the bulb's largest excursion is its arm times sin(12 degrees), and it stays on
  // the circle about the hook, at the hook's depth (a swing about Z).
  float widestM = 0.0f;
  for (int k = 1; k <= 400; ++k) {
    Scene posed = still;
    poseScene(posed, 0.01f * static_cast<float>(k));
    const glm::vec3 bulb = posed.lights[0].position, rest = still.lights[0].position;
    widestM = std::max(widestM, std::fabs(bulb.x - rest.x));
    EXPECT_FLOAT_EQ(bulb.z, rest.z) << k;
    // The shade and the cord keep their offsets from the bulb's path: they turn with it about
    // the hook, so the bulb stays under the shade.
    const glm::mat4 move = posed.objects[shade].worldFromObject * glm::inverse(still.objects[shade].worldFromObject);
    EXPECT_NEAR(glm::length(glm::vec3(move * glm::vec4(rest, 1.0f)) - bulb), 0.0f, 1e-4f) << k;
    const glm::mat4 cordMove = posed.objects[cord].worldFromObject * glm::inverse(still.objects[cord].worldFromObject);
    EXPECT_NEAR(glm::length(glm::vec3(cordMove * glm::vec4(rest, 1.0f)) - bulb), 0.0f, 1e-4f) << k;
    EXPECT_EQ(posed.objects[table].worldFromObject, still.objects[table].worldFromObject) << "the furniture stays";
  }
  // The ceiling's underside (LampScenes.cpp's kRoomHeightM); keys 0.1 s apart cut the peak by
  // at most 1 %.
  const float hookY = 2.6f, armM = hookY - still.lights[0].position.y;
  EXPECT_NEAR(widestM, armM * std::sin(glm::radians(12.0f)), 0.02f * armM * std::sin(glm::radians(12.0f)));
}

TEST(Animation, RemovingALightRenumbersTheOthersAnimations) {
  SceneAnimation a;
  for (uint32_t light : {0u, 1u, 2u}) {
    LightAnimation l;
    l.light = light;
    a.lights.push_back(l);
    SunPath sun;
    sun.light = light;
    a.suns.push_back(sun);
  }
  a.removeLight(1);
  ASSERT_EQ(a.lights.size(), 2u);
  ASSERT_EQ(a.suns.size(), 2u);
  EXPECT_EQ(a.lights[0].light, 0u);
  EXPECT_EQ(a.lights[1].light, 1u) << "light 2 is light 1 now";
  EXPECT_EQ(a.suns[1].light, 1u);
}
