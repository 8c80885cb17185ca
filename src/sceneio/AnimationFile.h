#pragma once
// The animation blocks of scene files (docs/scenes.md#animation): an object's, a light's and the
// camera's "animation" and a sun's "sunPath". Every key is checked; errors name the file and the
// field ("scenes/x.json: objects[2].animation.keys[1].timeS: must be after 0.5").
#include <penumbra/Animation.h>
#include <penumbra/Scene.h>

#include <nlohmann/json_fwd.hpp>

#include <string>

namespace penumbra::sceneio {

/// Where a block is in its file, for messages.
struct JsonPlace {
  std::string file, path;
};

/// An object's "animation": keys of translate, rotateDeg and scale (each optional per key) over
/// the object's own transform (its values are the rest of any channel no key gives).
TransformTrack readObjectAnimation(const nlohmann::json& j, const JsonPlace& at, const glm::vec3& translate,
                                   const glm::vec3& rotateDeg, const glm::vec3& scale);
/// A light's "animation": an optional pivot and keys of translate and rotateDeg, moving `rest`.
LightAnimation readLightAnimation(const nlohmann::json& j, const JsonPlace& at, const Light& rest, uint32_t index);
/// A sun's "sunPath": keys of azimuthDeg and elevationDeg (both in every key).
SunPath readSunPath(const nlohmann::json& j, const JsonPlace& at, uint32_t index);
/// The camera's "animation": keys of position and target (each optional per key).
CameraAnimation readCameraAnimation(const nlohmann::json& j, const JsonPlace& at);

/// The rotation of a scene file's rotateDeg (about Y, then X, then Z, as readTransform applies them).
glm::quat rotationFromDegrees(const glm::vec3& rotateDeg);

}  // namespace penumbra::sceneio
