#include "viewer/Playback.h"

#include "viewer/ViewSession.h"
#include "viewer/Widgets.h"

#include <fmt/format.h>
#include <imgui.h>

#include <cmath>

namespace penumbra::viewer {
namespace {

constexpr float kPlayButtonEm = 4.0f;  // Play / Pause, in font heights
// The Speed slider's range (× real time): a 4 s animation from a minute to a quarter second.
constexpr float kMinPlaySpeed = 1.0f / 16.0f, kMaxPlaySpeed = 16.0f;

}  // namespace

void Playback::advance(float dt) {
  const float duration = mSession.duration();
  if (!mPlaying || duration <= 0.0f) return;
  float t = mSession.time() + dt * mPlaySpeed;
  bool wrapped = false;
  if (t >= duration) {
    if (mLoop) {
      t = std::fmod(t, duration);
      wrapped = true;  // back to the start: the camera jumps
    } else {
      t = duration;
      mPlaying = false;
    }
  }
  setTime(t, wrapped);
}

void Playback::setTime(float timeS, bool jump) {
  mSession.setTime(timeS, jump);
  // Orbit and fly go on from where the animation put the camera.
  if (mSession.animatesCamera() && mSession.cameraFollows()) mCamera.follow(mSession.scene().camera);
}

void Playback::setPlaying(bool playing) {
  if (playing && mSession.duration() <= 0.0f) {
    mStatus.set(fmt::format("scene {} is still: nothing to play", mSession.scene().name), false);
    return;
  }
  if (playing && !mLoop && mSession.time() >= mSession.duration()) setTime(0.0f);
  mPlaying = playing;
  mStatus.set(fmt::format("{} at {:.2f} s of {:.2f} s", playing ? "playing" : "paused", mSession.time(), mSession.duration()), false);
}

void Playback::runAction(const ScriptAction& a) {
  if (a.verb == "time") {
    mPlaying = false;
    setTime(scriptFloat(a, 0));
  } else if (a.verb == "play") {
    mPlaySpeed = a.args.empty() ? 1.0f : scriptFloat(a, 0);
    setPlaying(true);
  } else {  // pause
    setPlaying(false);
  }
}

void Playback::drawTimeControls() {
  const float duration = mSession.duration();
  if (duration <= 0.0f) return;  // a still scene: nothing to play
  if (ImGui::Button(mPlaying ? "Pause" : "Play", ImVec2(kPlayButtonEm * ImGui::GetFontSize(), 0.0f))) setPlaying(!mPlaying);
  ImGui::SameLine();
  float t = mSession.time();
  if (ImGui::SliderFloat("Time", &t, 0.0f, duration, "%.2f s")) {
    mPlaying = false;  // scrubbing holds the frame under the cursor
    setTime(t);
  }
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("drag to scrub (pauses); Space plays and pauses; loop and speed: Camera tab");
}

void Playback::drawControls() {
  if (mSession.duration() <= 0.0f) return;
  ImGui::Separator();
  ImGui::TextUnformatted("Animation");
  ImGui::Checkbox("Loop", &mLoop);
  ImGui::SliderFloat("Speed", &mPlaySpeed, kMinPlaySpeed, kMaxPlaySpeed, "%.2f × real time", ImGuiSliderFlags_Logarithmic);
  if (mSession.animatesCamera()) {
    bool follow = mSession.cameraFollows();
    if (ImGui::Checkbox("Camera follows the animation", &follow)) {
      mSession.setCameraFollows(follow);
      setTime(mSession.time());  // orbit and fly take the animated camera
    }
  }
  hint(fmt::format("this frame for penumbra render / compare: --time {:.3f}", mSession.time()).c_str());
}

}  // namespace penumbra::viewer
