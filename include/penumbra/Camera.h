#pragma once
// The camera the light's views are fitted to (cascade splits, warps, the budget's importance).
// Conventions (docs/design.md): right-handed, metres; the view looks down -Z.
#include <penumbra/Math.h>

#include <string>

namespace penumbra {

/// Every world-space coordinate (vertices, the camera's position and target) stays within ±1e6 m
/// (as the scene file's shape sizes): beyond that the float maths of the shadow passes stops
/// meaning anything.
inline constexpr float kMaxCoordinateM = 1e6f;

/// A camera as the light's views are fitted to it: where it stands and looks, how wide it sees,
/// and how far.
struct Camera {
  glm::vec3 position{0.0f, 2.0f, 6.0f};
  glm::vec3 target{0.0f};
  glm::vec3 up{0.0f, 1.0f, 0.0f};
  float fovYRad = 0.8f;   ///< vertical field of view (a perspective camera)
  float nearM = 0.05f;
  float farM = 200.0f;
  /// An orthographic camera (an editor's top view, an isometric game): half the height of the
  /// view (m), the same at every distance; fovYRad is then unused. 0 = a perspective camera.
  float orthoHalfHeightM = 0.0f;

  bool orthographic() const { return orthoHalfHeightM > 0.0f; }

  /// "" when the camera defines a view; otherwise what is wrong: the target on the position, an
  /// up vector that is zero, not finite or along the view direction (a camera looking straight
  /// down with the default up renders nothing meaningful). Scene files, --camera and
  /// Scene::validate() check it.
  std::string viewProblem() const;
  glm::mat4 viewFromWorld() const;
  /// Reversed-Z, [0,1] clip depth (glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE)): near → 1, far → 0
  /// (infinitely far for a perspective camera; at farM for an orthographic one).
  glm::mat4 clipFromView(float aspect) const;
  glm::vec3 forward() const { return glm::normalize(target - position); }
};

}  // namespace penumbra
