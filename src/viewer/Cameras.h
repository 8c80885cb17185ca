#pragma once
// The viewer's camera and light controls, as plain maths (unit-tested without GL):
//  - OrbitCamera: yaw/pitch/distance around a target (drag to orbit, wheel to zoom, pan).
//  - FlyCamera: position + yaw/pitch (drag to look, WASD/QE to move).
//  - orbitLight(): drags the light by azimuth/elevation: the sun's direction, or a spot
//    light's position on a sphere around the point it aims at (it keeps aiming there).
// Angles in radians; yaw is about +Y, measured from +Z toward +X; pitch/elevation above the horizon.
#include <penumbra/Scene.h>

namespace penumbra::viewer {

/// Pitch stays this far (rad) from ±90° so that the +Y up vector never aligns with the view.
inline constexpr float kPitchLimitRad = 1.55f;

/// Position = target + distance · (cos p · sin y, sin p, cos p · cos y).
struct OrbitCamera {
  glm::vec3 target{0.0f};
  float yawRad = 0.0f, pitchRad = 0.3f, distanceM = 5.0f;

  static OrbitCamera fromCamera(const Camera& camera);
  /// Writes position, target and up (+Y) into `camera`; keeps its lens.
  void apply(Camera& camera) const;
  void rotate(float dYawRad, float dPitchRad);
  /// Moves the target in the view plane by a fraction of the visible height (dx right, dy up).
  void pan(float dxViewHeights, float dyViewHeights, float fovYRad);
  /// Scales the distance by `factor` (< 1 = closer), clamped to [kMinDistanceM, kMaxDistanceM].
  void zoom(float factor);

  static constexpr float kMinDistanceM = 0.05f;  // closer than the default near plane is useless
  static constexpr float kMaxDistanceM = 1e4f;
};

/// Looks along forward = (cos p · sin y, sin p, cos p · cos y) from `position`.
struct FlyCamera {
  glm::vec3 position{0.0f};
  float yawRad = 0.0f, pitchRad = 0.0f;
  float focusM = 5.0f;  ///< distance of the written target (kept so that orbit mode resumes there)

  static FlyCamera fromCamera(const Camera& camera);
  void apply(Camera& camera) const;
  glm::vec3 forward() const;
  void look(float dYawRad, float dPitchRad);
  /// Moves by `local` metres: x = right, y = world up, z = forward.
  void move(const glm::vec3& local);
};

/// The point a spot light aims at: on its axis, level with the scene's centre. Sun: the centre.
glm::vec3 lightAimPoint(const Light& light, const Aabb& sceneBounds);

/// Light elevation above the horizon stays in [kMinLightElevationRad, kMaxLightElevationRad]:
/// a light at or below the horizon lights nothing, one exactly overhead has no azimuth.
inline constexpr float kMinLightElevationRad = 0.02f;
inline constexpr float kMaxLightElevationRad = 1.56f;

/// Azimuth (about +Y, from +Z toward +X) and elevation of the direction toward the light.
glm::vec2 lightAngles(const Light& light, const glm::vec3& aim);
/// Sets the light's azimuth/elevation (rad) as seen from `aim`; a spot light keeps its distance
/// to `aim` and aims at it. Elevation is clamped.
void setLightAngles(Light& light, const glm::vec3& aim, float azimuthRad, float elevationRad);

}  // namespace penumbra::viewer
