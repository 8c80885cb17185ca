#pragma once
// The built-in scenes lit by lamps (point and spot lights with a range) instead of the sun: a room
// and a street at night. BuiltinScenes.cpp lists them with the others.
#include <penumbra/Scene.h>

namespace penumbra {

/// `room`: three walls, a ceiling and furniture under a point lamp (light 0) and a spot light.
Scene makeRoomScene();

/// `night`: a street with eight lamps (four point, four spot) whose pools overlap; the first
/// 1, 2, 4 and 8 lights are the nearest lamps to the camera, so a sweep over the light count
/// that takes the first N lights adds lamps from the near end of the street outward.
Scene makeNightScene();

}  // namespace penumbra
