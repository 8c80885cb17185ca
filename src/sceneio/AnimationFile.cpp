// Scene-file animation blocks (AnimationFile.h). Shape of every block:
//   {"interpolation": "linear" | "step", "keys": [{"timeS": 0, <values>}, …]}
// Key times strictly increase; a channel's keys are the keys that give its value.
#include "sceneio/AnimationFile.h"

#include <penumbra/Error.h>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <set>

namespace penumbra::sceneio {
namespace {

using Json = nlohmann::json;

// Most keys in one block: a hand-written or scripted path; keeps a runaway file from allocating.
constexpr size_t kMaxKeys = 100000;
// Key times in seconds: a day is longer than any sequence Penumbra renders.
constexpr float kMaxTimeS = 1e6f;
constexpr float kMinElevationDeg = -90.0f, kMaxElevationDeg = 90.0f;

[[noreturn]] void fail(const JsonPlace& at, const std::string& key, const std::string& what) {
  throw Error(fmt::format("{}: {}{}: {}", at.file, at.path, key.empty() ? "" : "." + key, what));
}

void checkKeys(const Json& j, const JsonPlace& at, const std::set<std::string>& allowed) {
  if (!j.is_object()) fail(at, "", "expected an object");
  for (const auto& [k, v] : j.items())
    if (!allowed.count(k)) fail(at, k, "unknown key");
}

float number(const Json& j, const JsonPlace& at, const std::string& key, float lo, float hi) {
  const Json& v = j.at(key);
  if (!v.is_number() || !std::isfinite(v.get<double>())) fail(at, key, "expected a number");
  const double d = v.get<double>();
  if (d < lo || d > hi) fail(at, key, fmt::format("{} is outside [{}, {}]", d, lo, hi));
  return static_cast<float>(d);
}

glm::vec3 vec3(const Json& j, const JsonPlace& at, const std::string& key) {
  const Json& v = j.at(key);
  if (!v.is_array() || v.size() != 3) fail(at, key, "expected an array of 3 numbers");
  glm::vec3 r;
  for (int i = 0; i < 3; ++i) {
    if (!v[static_cast<size_t>(i)].is_number() || !std::isfinite(v[static_cast<size_t>(i)].get<float>()))
      fail(at, key, "expected an array of 3 numbers");
    r[i] = v[static_cast<size_t>(i)].get<float>();
    if (std::abs(r[i]) > kMaxCoordinateM) fail(at, key, "beyond ±1e6");
  }
  return r;
}

/// Checks the block's own keys (interpolation, keys, and `extra`), returns its interpolation and
/// calls `key(json, place, timeS)` for each key in order, after checking its time increases.
template <class F>
Interpolation readBlock(const Json& j, const JsonPlace& at, const std::set<std::string>& extra, const std::set<std::string>& keyFields, F&& key) {
  std::set<std::string> allowed = extra;
  allowed.insert({"interpolation", "keys"});
  checkKeys(j, at, allowed);
  Interpolation interpolation = Interpolation::Linear;
  if (j.contains("interpolation")) {
    const Json& v = j.at("interpolation");
    const std::string name = v.is_string() ? v.get<std::string>() : "";
    if (name == "step") interpolation = Interpolation::Step;
    else if (name != "linear") fail(at, "interpolation", "expected \"linear\" or \"step\"");
  }
  if (!j.contains("keys") || !j.at("keys").is_array() || j.at("keys").empty()) fail(at, "keys", "expected a non-empty array of keys");
  const Json& keys = j.at("keys");
  if (keys.size() > kMaxKeys) fail(at, "keys", fmt::format("{} keys, more than the limit of {}", keys.size(), kMaxKeys));
  std::set<std::string> keyAllowed = keyFields;
  keyAllowed.insert("timeS");
  float previous = -kMaxTimeS - 1.0f;
  for (size_t i = 0; i < keys.size(); ++i) {
    const JsonPlace kp{at.file, fmt::format("{}.keys[{}]", at.path, i)};
    checkKeys(keys[i], kp, keyAllowed);
    if (!keys[i].contains("timeS")) fail(kp, "timeS", "missing (the key's time in seconds)");
    const float t = number(keys[i], kp, "timeS", -kMaxTimeS, kMaxTimeS);
    if (!(t > previous)) fail(kp, "timeS", fmt::format("{} s must be after the previous key's {} s", t, previous));
    previous = t;
    key(keys[i], kp, t);
  }
  return interpolation;
}

template <class T>
void push(Keys<T>& k, float t, const T& v, Interpolation interpolation) {
  k.timesS.push_back(t);
  k.values.push_back(v);
  k.interpolation = interpolation;
}

/// translate/rotateDeg/scale keys into a track whose rest is already set. `noTranslate`, when
/// given, is why a key's translate is refused (it would have no effect).
void readTrack(const Json& j, const JsonPlace& at, TransformTrack& track, bool allowScale, const std::set<std::string>& extra,
               const char* noTranslate = nullptr) {
  std::set<std::string> fields = {"translate", "rotateDeg"};
  if (allowScale) fields.insert("scale");
  const Interpolation interpolation = readBlock(j, at, extra, fields, [&](const Json& k, const JsonPlace& kp, float t) {
    if (k.contains("translate") && noTranslate) fail(kp, "translate", noTranslate);
    if (k.contains("translate")) push(track.translationKeys, t, vec3(k, kp, "translate"), Interpolation::Linear);
    if (k.contains("rotateDeg")) push(track.rotationKeys, t, rotationFromDegrees(vec3(k, kp, "rotateDeg")), Interpolation::Linear);
    if (k.contains("scale")) {
      const glm::vec3 s = vec3(k, kp, "scale");
      if (glm::any(glm::equal(s, glm::vec3(0.0f)))) fail(kp, "scale", "must not be zero");
      push(track.scaleKeys, t, s, Interpolation::Linear);
    }
  });
  track.translationKeys.interpolation = track.rotationKeys.interpolation = track.scaleKeys.interpolation = interpolation;
}

}  // namespace

glm::quat rotationFromDegrees(const glm::vec3& d) {
  return glm::angleAxis(glm::radians(d.y), glm::vec3(0, 1, 0)) * glm::angleAxis(glm::radians(d.x), glm::vec3(1, 0, 0)) *
         glm::angleAxis(glm::radians(d.z), glm::vec3(0, 0, 1));
}

TransformTrack readObjectAnimation(const Json& j, const JsonPlace& at, const glm::vec3& translate, const glm::vec3& rotateDeg,
                                   const glm::vec3& scale) {
  TransformTrack t;
  t.translation = translate;
  t.rotation = rotationFromDegrees(rotateDeg);
  t.scale = scale;
  readTrack(j, at, t, true, {});
  return t;
}

LightAnimation readLightAnimation(const Json& j, const JsonPlace& at, const Light& rest, uint32_t index) {
  LightAnimation a;
  a.light = index;
  a.restPosition = rest.position;
  a.restDirection = rest.direction;
  // A sun is a direction: moving it, or turning it about a point, would change nothing.
  const bool sun = rest.type == LightType::Directional;
  constexpr const char* kSunHasNoPosition = "a sun has no position (turn its direction with rotateDeg, or give it a sunPath)";
  if (j.is_object() && j.contains("pivot")) {
    if (sun) fail(at, "pivot", kSunHasNoPosition);
    a.pivot = vec3(j, at, "pivot");
  }
  readTrack(j, at, a.track, false, {"pivot"}, sun ? kSunHasNoPosition : nullptr);
  return a;
}

SunPath readSunPath(const Json& j, const JsonPlace& at, uint32_t index) {
  SunPath p;
  p.light = index;
  const Interpolation interpolation =
      readBlock(j, at, {}, {"azimuthDeg", "elevationDeg"}, [&](const Json& k, const JsonPlace& kp, float t) {
        for (const char* key : {"azimuthDeg", "elevationDeg"})
          if (!k.contains(key)) fail(kp, key, "missing (a sun path key gives azimuthDeg and elevationDeg)");
        push(p.azimuthDeg, t, number(k, kp, "azimuthDeg", -kMaxTimeS, kMaxTimeS), Interpolation::Linear);
        push(p.elevationDeg, t, number(k, kp, "elevationDeg", kMinElevationDeg, kMaxElevationDeg), Interpolation::Linear);
      });
  p.azimuthDeg.interpolation = p.elevationDeg.interpolation = interpolation;
  return p;
}

CameraAnimation readCameraAnimation(const Json& j, const JsonPlace& at) {
  CameraAnimation c;
  const Interpolation interpolation = readBlock(j, at, {}, {"position", "target"}, [&](const Json& k, const JsonPlace& kp, float t) {
    if (k.contains("position")) push(c.position, t, vec3(k, kp, "position"), Interpolation::Linear);
    if (k.contains("target")) push(c.target, t, vec3(k, kp, "target"), Interpolation::Linear);
  });
  c.position.interpolation = c.target.interpolation = interpolation;
  return c;
}

}  // namespace penumbra::sceneio
