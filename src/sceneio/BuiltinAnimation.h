#pragma once
// The built-in scenes' motion (BuiltinAnimation.cpp): keys over the still scenes that
// BuiltinScenes.cpp builds, whose pose at time 0 is the still scene.
#include <penumbra/Scene.h>

namespace penumbra::sceneio {

/// boxes: sphere A rolls 2.5 m toward the camera's right (+X, a little +Z) and the sun's azimuth sweeps 30° over kBuiltinDurationS.
void animateBoxes(Scene& boxes);
/// city: adds a vehicle (from behind the camera, out of view at time 0) driving down the avenue,
/// and walks the camera down it.
void animateCity(Scene& city);

/// room: the hanging lamp (light 0 with its shade and cord) swings 12 degrees either way from its
/// hook, at a pendulum's period.
void animateRoom(Scene& room);

/// Length of the built-in animations (s).
inline constexpr float kBuiltinDurationS = 4.0f;

}  // namespace penumbra::sceneio
