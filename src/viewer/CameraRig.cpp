#include "viewer/CameraRig.h"

#include "viewer/ViewSession.h"

#include <penumbra/Error.h>
#include <penumbra/SceneIO.h>

#include <GLFW/glfw3.h>
#include <imgui.h>

#include <algorithm>
#include <cmath>

namespace penumbra::viewer {
namespace {

constexpr float kOrbitRadPerPixel = 0.006f;  // a full turn per ~1000 px of drag
constexpr float kLightRadPerPixel = 0.005f;
constexpr float kZoomPerWheelNotch = 1.15f;  // distance factor per wheel step
constexpr float kFlyFastFactor = 4.0f;       // Shift held in fly mode
constexpr float kFlySpeedPerSceneRadius = 0.5f;  // metres per second per metre of scene radius

void hint(const char* text) {
  ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyle().Colors[ImGuiCol_TextDisabled]);
  ImGui::TextWrapped("%s", text);
  ImGui::PopStyleColor();
}

}  // namespace

void CameraRig::home(ViewSession& session) {
  mHomeCamera = session.scene().camera;
  reset(session);
}

void CameraRig::reset(ViewSession& session) {
  const Scene& s = session.scene();
  session.cutCamera();
  follow(s.camera);
  mFlySpeedMps = std::max(s.bounds().radius(), 1.0f) * kFlySpeedPerSceneRadius;
}

void CameraRig::follow(const Camera& camera) {
  mOrbit = OrbitCamera::fromCamera(camera);
  mFlyCamera = FlyCamera::fromCamera(camera);
}

void CameraRig::setFlying(bool fly, const Camera& camera) {
  mFly = fly;
  follow(camera);
}

void CameraRig::handleInput(ViewSession& session, const glm::ivec4& viewRect, float dt) {
  const ImGuiIO& io = ImGui::GetIO();
  const glm::vec2 d(io.MouseDelta.x, io.MouseDelta.y);
  const float scale = io.DisplayFramebufferScale.y;
  const glm::vec2 mouse = glm::vec2(io.MousePos.x, io.MousePos.y) * scale;
  const bool overView = mouse.x >= static_cast<float>(viewRect.x) && mouse.y >= 0.0f &&
                        mouse.x < static_cast<float>(viewRect.x + viewRect.z) && mouse.y < static_cast<float>(viewRect.w);
  if (!io.WantCaptureKeyboard) {
    if (ImGui::IsKeyPressed(GLFW_KEY_C, false)) {
      mFly = !mFly;
      if (mFly) mFlyCamera = FlyCamera::fromCamera(session.scene().camera);
      else mOrbit = OrbitCamera::fromCamera(session.scene().camera);
      mStatus.set(mFly ? "camera: fly (WASD/QE move, left-drag looks)" : "camera: orbit (left-drag orbits, wheel zooms)", false);
    }
    if (mFly) {
      glm::vec3 move(0.0f);
      move.x = float(ImGui::IsKeyDown(GLFW_KEY_D)) - float(ImGui::IsKeyDown(GLFW_KEY_A));
      move.y = float(ImGui::IsKeyDown(GLFW_KEY_E)) - float(ImGui::IsKeyDown(GLFW_KEY_Q));
      move.z = float(ImGui::IsKeyDown(GLFW_KEY_W)) - float(ImGui::IsKeyDown(GLFW_KEY_S));
      if (move != glm::vec3(0.0f)) {
        mFlyCamera.move(move * mFlySpeedMps * dt * (io.KeyShift ? kFlyFastFactor : 1.0f));
        mFlyCamera.apply(session.camera());
      }
    }
  }
  if (viewRect.w <= 0) return;
  // A drag belongs to the view when it starts there, and goes on over the panels.
  const bool hoverView = overView && !io.WantCaptureMouse;
  const bool anyDown = io.MouseDown[0] || io.MouseDown[1] || io.MouseDown[2];
  if (!anyDown) mDragInView = false;
  else if (hoverView && (io.MouseClicked[0] || io.MouseClicked[1] || io.MouseClicked[2])) mDragInView = true;
  const bool pan = io.MouseDown[ImGuiMouseButton_Middle] || (io.MouseDown[ImGuiMouseButton_Left] && io.KeyShift);
  if (mDragInView && d != glm::vec2(0.0f)) {
    if (io.MouseDown[ImGuiMouseButton_Right]) {
      Light& light = session.light();
      const glm::vec3 aim = lightAimPoint(light, session.scene().bounds());
      const glm::vec2 angles = lightAngles(light, aim);
      setLightAngles(light, aim, angles.x - d.x * kLightRadPerPixel, angles.y - d.y * kLightRadPerPixel);
    } else if (mFly && io.MouseDown[ImGuiMouseButton_Left]) {
      mFlyCamera.look(-d.x * kOrbitRadPerPixel, -d.y * kOrbitRadPerPixel);
      mFlyCamera.apply(session.camera());
    } else if (!mFly && pan) {
      const float h = static_cast<float>(viewRect.w) / scale;
      mOrbit.pan(d.x / h, -d.y / h, session.scene().camera.fovYRad);
      mOrbit.apply(session.camera());
    } else if (!mFly && io.MouseDown[ImGuiMouseButton_Left]) {
      mOrbit.rotate(-d.x * kOrbitRadPerPixel, d.y * kOrbitRadPerPixel);
      mOrbit.apply(session.camera());
    }
  }
  if (hoverView && io.MouseWheel != 0.0f) {
    if (mFly) {
      mFlySpeedMps *= std::pow(kZoomPerWheelNotch, io.MouseWheel);
    } else {
      mOrbit.zoom(std::pow(kZoomPerWheelNotch, -io.MouseWheel));
      mOrbit.apply(session.camera());
    }
  }
}

void CameraRig::runAction(const ScriptAction& a, ViewSession& session) {
  const std::string& arg = a.args[0];
  if (arg != "mode") session.cutCamera();  // the camera jumps: no history to reuse
  if (arg == "mode") {
    setFlying(a.args[1] == "fly", session.scene().camera);
  } else if (arg == "orbit") {
    mFly = false;
    mOrbit.yawRad = glm::radians(scriptFloat(a, 1));
    mOrbit.pitchRad = glm::radians(scriptFloat(a, 2));
    mOrbit.distanceM = 1.0f;
    mOrbit.rotate(0.0f, 0.0f);  // clamps the pitch
    mOrbit.zoom(scriptFloat(a, 3));  // clamps the distance
    mOrbit.apply(session.camera());
  } else {  // look
    Camera& c = session.camera();
    c.position = {scriptFloat(a, 1), scriptFloat(a, 2), scriptFloat(a, 3)};
    c.target = {scriptFloat(a, 4), scriptFloat(a, 5), scriptFloat(a, 6)};
    if (glm::length(c.target - c.position) <= 0.0f) throw usageError("the target equals the position");
    follow(c);
  }
}

void CameraRig::drawControls(ViewSession& session) {
  const Scene& scene = session.scene();
  int mode = mFly ? 1 : 0;
  bool modeChanged = ImGui::RadioButton("orbit", &mode, 0);
  ImGui::SameLine();
  modeChanged |= ImGui::RadioButton("fly (C)", &mode, 1);
  if (modeChanged) {
    setFlying(mode == 1, scene.camera);
    mStatus.set(mFly ? "camera: fly" : "camera: orbit", false);
  }
  hint(mFly ? "left-drag look, WASD/QE move (Shift fast), wheel speed" : "left-drag orbit, middle/Shift-drag pan, wheel zoom");
  float fovDeg = glm::degrees(scene.camera.fovYRad);
  if (ImGui::SliderFloat("Field of view", &fovDeg, 10.0f, 120.0f, "%.0f° vertical")) session.camera().fovYRad = glm::radians(fovDeg);
  if (ImGui::Button("Reset camera")) {
    session.camera() = mHomeCamera;
    reset(session);
    mStatus.set("camera: the scene's own", false);
  }
  ImGui::SameLine();
  const std::string argument = "--camera " + cameraArgument(scene.camera);
  if (ImGui::Button("Copy --camera")) {
    ImGui::SetClipboardText(argument.c_str());
    mStatus.set("copied " + argument, false);
  }
  hint(("this view for penumbra render / compare: " + argument).c_str());
}

}  // namespace penumbra::viewer
