#include "viewer/Cameras.h"

#include <algorithm>
#include <cmath>

namespace penumbra::viewer {
namespace {

glm::vec3 unitFromAngles(float yawRad, float pitchRad) {
  return {std::cos(pitchRad) * std::sin(yawRad), std::sin(pitchRad), std::cos(pitchRad) * std::cos(yawRad)};
}

float clampPitch(float p) { return std::clamp(p, -kPitchLimitRad, kPitchLimitRad); }

}  // namespace

OrbitCamera OrbitCamera::fromCamera(const Camera& camera) {
  OrbitCamera o;
  o.target = camera.target;
  const glm::vec3 d = camera.position - camera.target;
  o.distanceM = std::max(glm::length(d), kMinDistanceM);
  o.pitchRad = clampPitch(std::asin(std::clamp(d.y / o.distanceM, -1.0f, 1.0f)));
  o.yawRad = std::atan2(d.x, d.z);
  return o;
}

void OrbitCamera::apply(Camera& camera) const {
  camera.target = target;
  camera.position = target + distanceM * unitFromAngles(yawRad, pitchRad);
  camera.up = {0.0f, 1.0f, 0.0f};
}

void OrbitCamera::rotate(float dYawRad, float dPitchRad) {
  yawRad += dYawRad;
  pitchRad = clampPitch(pitchRad + dPitchRad);
}

void OrbitCamera::pan(float dxViewHeights, float dyViewHeights, float fovYRad) {
  const glm::vec3 back = unitFromAngles(yawRad, pitchRad);  // from the target toward the eye
  const glm::vec3 right = glm::normalize(glm::cross(glm::vec3(0, 1, 0), back));
  const glm::vec3 up = glm::cross(back, right);
  const float viewHeightM = 2.0f * distanceM * std::tan(0.5f * fovYRad);
  target -= (right * dxViewHeights + up * dyViewHeights) * viewHeightM;
}

void OrbitCamera::zoom(float factor) { distanceM = std::clamp(distanceM * factor, kMinDistanceM, kMaxDistanceM); }

FlyCamera FlyCamera::fromCamera(const Camera& camera) {
  FlyCamera f;
  f.position = camera.position;
  const glm::vec3 d = camera.target - camera.position;
  f.focusM = std::max(glm::length(d), OrbitCamera::kMinDistanceM);
  f.pitchRad = clampPitch(std::asin(std::clamp(d.y / f.focusM, -1.0f, 1.0f)));
  f.yawRad = std::atan2(d.x, d.z);
  return f;
}

glm::vec3 FlyCamera::forward() const { return unitFromAngles(yawRad, pitchRad); }

void FlyCamera::apply(Camera& camera) const {
  camera.position = position;
  camera.target = position + focusM * forward();
  camera.up = {0.0f, 1.0f, 0.0f};
}

void FlyCamera::look(float dYawRad, float dPitchRad) {
  yawRad += dYawRad;
  pitchRad = clampPitch(pitchRad + dPitchRad);
}

void FlyCamera::move(const glm::vec3& local) {
  const glm::vec3 f = forward();
  const glm::vec3 right = glm::normalize(glm::cross(f, glm::vec3(0, 1, 0)));
  position += right * local.x + glm::vec3(0, 1, 0) * local.y + f * local.z;
}

glm::vec3 lightAimPoint(const Light& light, const Aabb& sceneBounds) {
  const glm::vec3 centre = sceneBounds.empty() ? glm::vec3(0.0f) : sceneBounds.center();
  if (light.type != LightType::Spot) return centre;
  // The axis point closest to the centre; never behind (or at) the light.
  constexpr float kMinAimDistanceM = 0.1f;
  const glm::vec3 dir = glm::normalize(light.direction);
  const float t = std::max(glm::dot(centre - light.position, dir), kMinAimDistanceM);
  return light.position + t * dir;
}

glm::vec2 lightAngles(const Light& light, const glm::vec3& aim) {
  const glm::vec3 toLight = isPositional(light) ? glm::normalize(light.position - aim)
                                                          : -glm::normalize(light.direction);
  return {std::atan2(toLight.x, toLight.z), std::asin(std::clamp(toLight.y, -1.0f, 1.0f))};
}

void setLightAngles(Light& light, const glm::vec3& aim, float azimuthRad, float elevationRad) {
  const float e = std::clamp(elevationRad, kMinLightElevationRad, kMaxLightElevationRad);
  const glm::vec3 toLight = unitFromAngles(azimuthRad, e);
  if (isPositional(light)) {
    const float distanceM = glm::length(light.position - aim);
    light.position = aim + distanceM * toLight;
  }
  light.direction = -toLight;
}

}  // namespace penumbra::viewer
