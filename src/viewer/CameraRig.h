#pragma once
// The viewer's camera rig: what moves the camera (and, with the right button, the selected
// light) from the mouse and the keys over the view. Orbit (drag orbits, middle/Shift-drag pans,
// the wheel zooms) or fly (drag looks, WASD/QE move, the wheel sets the speed), the scene's own
// camera to go back to, and the script's `camera` action. Everything goes through ViewSession,
// which the rig moves and never owns.
#include "viewer/Cameras.h"
#include "viewer/Script.h"
#include "viewer/StatusLine.h"

#include <glm/glm.hpp>

namespace penumbra::viewer {

class ViewSession;

class CameraRig {
public:
  explicit CameraRig(StatusLine& status) : mStatus(status) {}

  /// A scene was loaded: its camera is the one "Reset camera" goes back to; the rig starts there.
  void home(ViewSession& session);
  /// Back to the scene's own camera (a cut: no history to reuse).
  void reset(ViewSession& session);
  /// Orbit and fly go on from `camera` (after the animation or a script placed it).
  void follow(const Camera& camera);
  bool flying() const { return mFly; }
  void setFlying(bool fly, const Camera& camera);

  /// Keys and mouse of one frame (ImGui's input), for the view at `viewRect` (window pixels,
  /// origin lower left). A drag belongs to the view when it starts there.
  void handleInput(ViewSession& session, const glm::ivec4& viewRect, float dtSeconds);
  /// The script's `camera orbit|look|mode` action.
  void runAction(const ScriptAction& a, ViewSession& session);
  /// The Camera tab's camera half: mode, field of view, reset, the --camera argument.
  void drawControls(ViewSession& session);

private:
  StatusLine& mStatus;
  bool mFly = false;
  bool mDragInView = false;  ///< a mouse drag that started over the view
  Camera mHomeCamera;        ///< the scene's own camera ("Reset camera")
  OrbitCamera mOrbit;
  FlyCamera mFlyCamera;
  float mFlySpeedMps = 2.0f;
};

}  // namespace penumbra::viewer
