#pragma once
// Keyframed animation of a scene: object transforms (a node hierarchy, as glTF has it), lights,
// the camera and sun paths, evaluated at a time in seconds (poseScene). Pure data, no GL.
// Times before the first key hold the first key's value, times after the last hold the last
// (no looping). Rotations interpolate as quaternions (shortest-arc slerp), the rest linearly or
// as steps. Scene files: docs/scenes.md#animation; glTF: TRS channels of every animation.
#include <penumbra/Math.h>

#include <glm/gtc/quaternion.hpp>

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace penumbra {

struct Scene;

/// Between two keys: linear (slerp for rotations) or the earlier key's value until the next key.
enum class Interpolation { Linear, Step };

/// One animated quantity: key times (s, strictly increasing) and one value per key.
template <class T>
struct Keys {
  std::vector<float> timesS;
  std::vector<T> values;
  Interpolation interpolation = Interpolation::Linear;
  bool empty() const { return timesS.empty(); }
  /// The value at `timeS`; needs at least one key.
  T at(float timeS) const;
};
using Vec3Keys = Keys<glm::vec3>;
using QuatKeys = Keys<glm::quat>;
using FloatKeys = Keys<float>;

/// A translation-rotation-scale transform over time: each channel with keys overrides its rest
/// value; without any keys the transform is the rest one (or `fixed`, a glTF matrix node).
struct TransformTrack {
  glm::vec3 translation{0.0f};
  glm::quat rotation{1.0f, 0.0f, 0.0f, 0.0f};
  glm::vec3 scale{1.0f};
  std::optional<glm::mat4> fixed;  ///< a static matrix instead of T·R·S (no channel may be keyed)
  Vec3Keys translationKeys;
  QuatKeys rotationKeys;
  Vec3Keys scaleKeys;
  bool animated() const { return !translationKeys.empty() || !rotationKeys.empty() || !scaleKeys.empty(); }
  /// T(t)·R(t)·S(t).
  glm::mat4 matrixAt(float timeS) const;
};

/// A transform in a hierarchy: world(node) = world(parent) · offset · track(t), where world(-1)
/// is the identity. `offset` holds the static part above the track (a glTF node's non-animated
/// ancestors, a model's placement in a scene file).
struct AnimatedNode {
  std::string name;
  int parent = -1;  ///< an earlier node's index, or -1
  glm::mat4 offset{1.0f};
  TransformTrack track;
};

/// An object that follows a node: worldFromObject(t) = world(node, t) · nodeFromObject.
struct ObjectAnimation {
  uint32_t object = 0;
  uint32_t node = 0;
  glm::mat4 nodeFromObject{1.0f};
};

/// A light moved by a keyed transform about a pivot: position(t) = M(t)·restPosition and
/// direction(t) = M(t)·restDirection, with M(t) = T(pivot)·track(t)·T(-pivot) (a lamp swinging
/// from its hook). The rest values are the light's own at load time.
struct LightAnimation {
  uint32_t light = 0;
  /// ≥ 0: the light hangs in that animation node (a glTF light under an animated node): M(t) is
  /// the node's world transform, the rest values are in the node's frame and the pivot is unused.
  int node = -1;
  glm::vec3 pivot{0.0f};
  glm::vec3 restPosition{0.0f};
  glm::vec3 restDirection{0.0f, -1.0f, 0.0f};
  TransformTrack track;
};

/// A sun's direction over time from azimuth and elevation (degrees): the direction toward the sun
/// is (cos e · sin a, sin e, cos e · cos a), so azimuth 0° is toward +Z and 90° toward +X.
struct SunPath {
  uint32_t light = 0;
  FloatKeys azimuthDeg, elevationDeg;  ///< one time line: the same key times in both
};

/// The direction from a sun toward the scene (Light::direction) for azimuth a, elevation e.
glm::vec3 sunDirection(float azimuthDeg, float elevationDeg);

/// A camera's position and target over time (each optional), or a node it hangs in; field of
/// view, near and far stay (and up, except in a node).
struct CameraAnimation {
  Vec3Keys position, target;
  /// ≥ 0: the camera hangs in that animation node (a glTF camera under an animated node): it sits
  /// at the node's origin looking down its -Z with its +Y up, at the keys' place (none are given).
  int node = -1;
  bool empty() const { return position.empty() && target.empty() && node < 0; }
};

struct SceneAnimation {
  std::vector<AnimatedNode> nodes;
  std::vector<ObjectAnimation> objects;
  std::vector<LightAnimation> lights;
  std::vector<SunPath> suns;
  CameraAnimation camera;
  bool empty() const { return objects.empty() && lights.empty() && suns.empty() && camera.empty(); }
  /// The last key time of every channel (s); 0 for a still scene.
  float durationS() const;
  /// Every channel's key times (s), in order, each once; empty for a still scene.
  std::vector<float> keyTimes() const;
  /// Whether object `object` moves (it follows an animated node or one below an animated node).
  std::vector<bool> movingObjects(size_t objectCount) const;
  /// Light `index` was removed from the scene: its animation and sun path go, later lights'
  /// indices move down by one.
  void removeLight(uint32_t index);
  /// "" when consistent with a scene of these counts; otherwise what is wrong (an index out of
  /// range, a parent that is not earlier, key times not increasing or not finite, counts that
  /// differ, a non-unit quaternion).
  std::string problem(size_t objectCount, size_t lightCount) const;
};

/// Poses `scene` at `timeS` from scene.animation: the animated objects' worldFromObject, the
/// animated lights' position and direction, the sun paths' directions and the camera's position
/// and target. Anything not animated is left as it is, so posing twice at one time is the same
/// as posing once. A still scene is unchanged.
void poseScene(Scene& scene, float timeS);

/// "" when `scene` posed at each of `timesS` keeps what its still pose must (Scene::validate,
/// scene files' bounds): every animated object's world bounds and every animated spot and point
/// light within ±kMaxCoordinateM, a camera within them that defines a view. Otherwise the first
/// problem, with its time and what it is, in the still checks' words ("at 2 s: camera: the view
/// is along the up vector (0, 1, 0): …"). Scene::validate checks the key times (beyond 4096 of
/// them, as many evenly chosen); a sequence checks its frames' times before its first frame.
std::string poseProblem(const Scene& scene, std::span<const float> timesS);

}  // namespace penumbra
