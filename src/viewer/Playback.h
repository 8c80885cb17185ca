#pragma once
// The viewer's playback of an animated scene: play, pause, loop, the speed, scrubbing, and the
// time the script sets. The animation plays at speed × real time (a script's frames: 1/30 s
// each); a jump (a scrub, a loop back to the start) cuts the temporal history, playback's steps
// do not. When the camera follows the animation, the camera rig goes on from where it put it.
#include "viewer/CameraRig.h"
#include "viewer/Script.h"
#include "viewer/StatusLine.h"

namespace penumbra::viewer {

class ViewSession;

class Playback {
public:
  Playback(ViewSession& session, CameraRig& camera, StatusLine& status) : mSession(session), mCamera(camera), mStatus(status) {}

  bool playing() const { return mPlaying; }
  /// When playing: dt × speed on, looping or stopping at the end.
  void advance(float dtSeconds);
  /// Poses the scene at `timeS`; the camera rig follows if the camera does.
  void setTime(float timeS, bool jump = true);
  /// Play from the start again when at the end and not looping; a still scene says so.
  void setPlaying(bool playing);
  /// The script's `time`, `play` and `pause`.
  void runAction(const ScriptAction& a);

  /// Play/Pause and the time slider over the tabs (nothing for a still scene).
  void drawTimeControls();
  /// The Camera tab's animation half: loop, speed, the camera following the animation.
  void drawControls();

private:
  ViewSession& mSession;
  CameraRig& mCamera;
  StatusLine& mStatus;
  bool mPlaying = false;
  bool mLoop = true;
  float mPlaySpeed = 1.0f;
};

}  // namespace penumbra::viewer
