// The built-in scenes' motion: a rolling ball and a sweeping sun on boxes, a vehicle and a
// walking camera on city, a swinging lamp in room. Every key at time 0 is the still scene's value, so the still frame
// (every test and cached reference of it) stays what it was.
#include "sceneio/BuiltinAnimation.h"

#include <penumbra/Error.h>

#include <fmt/format.h>
#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>

namespace penumbra::sceneio {
namespace {

// Keys per second of a rolling ball: slerp takes the short way, so keys must be less than half a
// turn apart (here 0.6 rad at most).
constexpr int kRollKeysPerSecond = 2;

uint32_t objectNamed(const Scene& s, const std::string& name) {
  const auto it = std::find_if(s.objects.begin(), s.objects.end(), [&](const Object& o) { return o.name == name; });
  PN_CHECK(it != s.objects.end(), fmt::format("built-in scene {}: no object '{}'", s.name, name));
  return static_cast<uint32_t>(it - s.objects.begin());
}

/// A node at the object's rest translation that the object follows.
AnimatedNode& follow(Scene& s, uint32_t object, const std::string& name) {
  AnimatedNode n;
  n.name = name;
  n.track.translation = glm::vec3(s.objects[object].worldFromObject[3]);
  s.animation.objects.push_back({object, static_cast<uint32_t>(s.animation.nodes.size()),
                                 glm::translate(glm::mat4(1.0f), -n.track.translation) * s.objects[object].worldFromObject});
  s.animation.nodes.push_back(std::move(n));
  return s.animation.nodes.back();
}

/// Linear keys of a straight drive from `from` at time 0 to `to` at kBuiltinDurationS.
Vec3Keys straight(const glm::vec3& from, const glm::vec3& to) {
  Vec3Keys k;
  k.timesS = {0.0f, kBuiltinDurationS};
  k.values = {from, to};
  return k;
}

}  // namespace

void animateBoxes(Scene& s) {
  // Toward the camera's right, between box B and box C's corner (clear of both).
  constexpr float kRollM = 2.5f, kRadiusM = 0.6f;  // sphere A's radius (makeBoxes)
  constexpr float kSunSweepDeg = 30.0f;
  const uint32_t ball = objectNamed(s, "sphere A");
  AnimatedNode& node = follow(s, ball, "rolling ball");
  const glm::vec3 start = node.track.translation, direction = glm::normalize(glm::vec3(1.0f, 0.0f, 0.3f));
  // Rolling without slipping: the ball turns about up × direction by distance / radius.
  const glm::vec3 axis = glm::cross(glm::vec3(0.0f, 1.0f, 0.0f), direction);
  const int keys = static_cast<int>(kBuiltinDurationS) * kRollKeysPerSecond;
  for (int k = 0; k <= keys; ++k) {
    const float f = static_cast<float>(k) / static_cast<float>(keys), distanceM = f * kRollM;
    node.track.translationKeys.timesS.push_back(f * kBuiltinDurationS);
    node.track.translationKeys.values.push_back(start + direction * distanceM);
    node.track.rotationKeys.timesS.push_back(f * kBuiltinDurationS);
    node.track.rotationKeys.values.push_back(glm::angleAxis(distanceM / kRadiusM, axis));
  }
  // The sun's azimuth and elevation at rest (sunDirection's convention), then a sweep.
  const glm::vec3 toSun = -s.lights.front().direction;
  const float elevationDeg = glm::degrees(std::asin(toSun.y)), azimuthDeg = glm::degrees(std::atan2(toSun.x, toSun.z));
  SunPath path;
  path.light = 0;
  path.azimuthDeg.timesS = path.elevationDeg.timesS = {0.0f, kBuiltinDurationS};
  path.azimuthDeg.values = {azimuthDeg, azimuthDeg + kSunSweepDeg};
  path.elevationDeg.values = {elevationDeg, elevationDeg};
  s.animation.suns.push_back(std::move(path));
}

void animateCity(Scene& s) {
  // A van on the avenue's left lane, behind the camera at time 0 (its shadow falls behind too).
  constexpr float kLaneX = -1.5f, kStartZ = 318.0f, kSpeedMps = 12.0f;
  const glm::vec3 vanSize(1.8f, 1.5f, 4.5f);
  const glm::vec3 start(kLaneX, 0.5f * vanSize.y, kStartZ);
  const uint32_t van = addObject(s, "vehicle", makeBox(vanSize), {0.75f, 0.2f, 0.15f}, glm::translate(glm::mat4(1.0f), start));
  follow(s, van, "vehicle").track.translationKeys = straight(start, start - glm::vec3(0.0f, 0.0f, kSpeedMps * kBuiltinDurationS));
  // The camera walks down the avenue at walking pace, looking where it goes.
  constexpr float kWalkMps = 1.4f;
  const glm::vec3 step(0.0f, 0.0f, -kWalkMps * kBuiltinDurationS);
  s.animation.camera.position = straight(s.camera.position, s.camera.position + step);
  s.animation.camera.target = straight(s.camera.target, s.camera.target + step);
}

void animateRoom(Scene& s) {
  // The lamp (light 0, its shade and its cord) swings from the cord's hook in the ceiling like a
  // pendulum, across the room (about Z, so the table's shadow sweeps along the floor and the wall).
  constexpr float kAmplitudeDeg = 12.0f, kGravityMps2 = 9.81f;
  constexpr int kKeysPerSecond = 10;  // a smooth sine; slerp between keys 3 degrees apart at most
  PN_CHECK(!s.lights.empty() && s.lights.front().type == LightType::Point, "built-in scene room: light 0 is the lamp");
  const uint32_t cord = objectNamed(s, "lamp cord"), shade = objectNamed(s, "lamp shade");
  const Aabb cordBounds = s.meshes[s.objects[cord].mesh].bounds().transformed(s.objects[cord].worldFromObject);
  const Light& lamp = s.lights.front();
  const glm::vec3 hook(lamp.position.x, cordBounds.hi.y, lamp.position.z);
  const float periodS = glm::two_pi<float>() * std::sqrt((hook.y - lamp.position.y) / kGravityMps2);
  TransformTrack swing;
  const int keys = static_cast<int>(kBuiltinDurationS) * kKeysPerSecond;
  for (int k = 0; k <= keys; ++k) {
    const float t = kBuiltinDurationS * static_cast<float>(k) / static_cast<float>(keys);
    const float angle = glm::radians(kAmplitudeDeg) * std::sin(glm::two_pi<float>() * t / periodS);
    swing.rotationKeys.timesS.push_back(t);
    swing.rotationKeys.values.push_back(glm::angleAxis(angle, glm::vec3(0.0f, 0.0f, 1.0f)));
  }
  s.animation.lights.push_back({.light = 0, .pivot = hook, .restPosition = lamp.position,
                                .restDirection = lamp.direction, .track = swing});
  AnimatedNode node;
  node.name = "swinging lamp";
  node.track = swing;
  node.track.translation = hook;
  const uint32_t nodeIndex = static_cast<uint32_t>(s.animation.nodes.size());
  s.animation.nodes.push_back(std::move(node));
  for (const uint32_t o : {shade, cord})
    s.animation.objects.push_back({o, nodeIndex, glm::translate(glm::mat4(1.0f), -hook) * s.objects[o].worldFromObject});
}

}  // namespace penumbra::sceneio
