#include "viewer/Viewer.h"

#include "viewer/SceneWriter.h"

#include "shared/Enums.h"

#include <penumbra/Error.h>
#include <penumbra/ImageIO.h>
#include "shadows/Registry.h"
#include <penumbra/SceneIO.h>

#include <GLFW/glfw3.h>
#include <fmt/format.h>
#include <imgui.h>
#include <imgui_impl_glfw.h>
#include <imgui_impl_opengl3.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

namespace penumbra::viewer {
namespace {

constexpr float kOrbitRadPerPixel = 0.006f;  // a full turn per ~1000 px of drag
constexpr float kLightRadPerPixel = 0.005f;
constexpr float kZoomPerWheelNotch = 1.15f;  // distance factor per wheel step
constexpr float kFlyFastFactor = 4.0f;       // Shift held in fly mode
constexpr float kInsetFraction = 0.32f;      // inset side relative to the view
constexpr int kInsetMarginPx = 8;
constexpr float kMaxSidebarFraction = 0.5f;  // as in Panels.cpp: the panels never take more than half
constexpr size_t kHistoryFrames = 240;       // rolling graphs: 4 s at 60 fps
constexpr float kFlySpeedPerSceneRadius = 0.5f;  // metres per second per metre of scene radius
constexpr float kScriptedFrameS = 1.0f / 30.0f;   // a script's frame plays this much of the animation

// The lit pass's views (RenderOptions::debugView), shown as the colour output.
struct LitView {
  const char* name;
  int debugView;
};
constexpr LitView kLitViews[] = {
    {kShadedView, PN_VIEW_SHADED},
    {"cascades", PN_VIEW_CASCADES},
    {"texel-density", PN_VIEW_TEXEL_DENSITY},
};

const LitView* findLitView(const std::string& name) {
  for (const LitView& v : kLitViews)
    if (name == v.name) return &v;
  return nullptr;
}

std::string join(const std::vector<std::string>& items, const char* separator) {
  std::string out;
  for (const std::string& i : items) out += (out.empty() ? "" : separator) + i;
  return out;
}

std::string title(const ViewSession& s) {
  return fmt::format("Penumbra view: {} | --projection {} --filter {}", s.scene().name, s.projectionId(), s.filterId());
}

}  // namespace

bool isLitView(std::string_view name) { return findLitView(std::string(name)) != nullptr; }

Viewer::Viewer(Scene scene, const Technique& technique, ViewerOptions options)
    : mOptions(std::move(options)),
      mWindow(mOptions.width, mOptions.height, "Penumbra view", {.debug = false, .verbose = mOptions.verbose}),
      mSession(mWindow, std::move(scene), technique),
      mDisplay(mSession.renderer().shaders()),
      mStatus{{}, false, mOptions.scripted || mOptions.verbose},
      mHotReload(mSession.renderer().shaders(), mOptions.shaderTree, mOptions.reloadTechniqueFolders, mStatus) {
  glfwSwapInterval(mOptions.vsync ? 1 : 0);
  glfwSetWindowTitle(mWindow.window(), title(mSession).c_str());
  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini left in the working directory
  ImGui::StyleColorsDark();
  loadFont();
  ImGui_ImplGlfw_InitForOpenGL(mWindow.window(), true);
  ImGui_ImplOpenGL3_Init("#version 450 core");
  mHomeCamera = mSession.scene().camera;
  resetCamera();
  std::snprintf(mSavePath, sizeof(mSavePath), "%s-view.json", mSession.scene().name.c_str());
}

Viewer::~Viewer() {
  mHeatmap.cancel();
  ImGui_ImplOpenGL3_Shutdown();
  ImGui_ImplGlfw_Shutdown();
  ImGui::DestroyContext();
}

int Viewer::run() {
  while (frame()) {
  }
  return 0;
}

void Viewer::resetCamera() {
  const Scene& s = mSession.scene();
  mSession.cutCamera();
  mOrbit = OrbitCamera::fromCamera(s.camera);
  mFlyCamera = FlyCamera::fromCamera(s.camera);
  mFlySpeedMps = std::max(s.bounds().radius(), 1.0f) * kFlySpeedPerSceneRadius;
}

void Viewer::setStatus(std::string message, bool error) { mStatus.set(std::move(message), error); }

bool Viewer::frame() {
  const auto start = std::chrono::steady_clock::now();
  glfwPollEvents();
  if (glfwWindowShouldClose(mWindow.window())) return false;
  if (mOptions.scripted) runScript();
  if (mQuit) return false;

  ImGui_ImplOpenGL3_NewFrame();
  ImGui_ImplGlfw_NewFrame();
  ImGui::NewFrame();
  try {
    drawFrame();
  } catch (...) {
    ImGui::EndFrame();  // leave ImGui consistent for the shutdown that follows
    throw;
  }
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  recordTimings(ms);
  ++mFrameCount;
  return mOptions.frames <= 0 || mFrameCount < mOptions.frames;
}

void Viewer::drawFrame() {
  if (mOptions.showUi) drawPanels();
  layout();
  drawOverlay();
  drawLegends();
  const float dt = static_cast<float>(mLastFrameMs) * 1e-3f;
  const Camera before = mSession.scene().camera;
  handleInput(dt);
  const Camera& after = mSession.scene().camera;
  if (mSession.animatesCamera() && mSession.cameraFollows() &&
      (before.position != after.position || before.target != after.target || before.fovYRad != after.fovYRad)) {
    mSession.setCameraFollows(false);  // the user took the camera
    setStatus("camera: yours now (Camera tab: follow the animation again)", false);
  }
  advanceTime(mOptions.scripted ? kScriptedFrameS : dt);
  pollHeatmap();
  mHotReload.poll({&mSession, mSplit.get()});

  renderFrame();
  if (mHeatmapRequest) startHeatmap(*std::exchange(mHeatmapRequest, std::nullopt));  // on this frame
  drawViews();
  drawViewLabels();
  if (mViewShot) screenshotView(*std::exchange(mViewShot, std::nullopt));
  ImGui::Render();
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glViewport(0, 0, mFramebuffer.x, mFramebuffer.y);
  ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
  if (mWindowShot) screenshotWindow(*std::exchange(mWindowShot, std::nullopt));
  if (mInsetShot) screenshotInset(*std::exchange(mInsetShot, std::nullopt));
  glfwSwapBuffers(mWindow.window());
}

void Viewer::layout() {
  glfwGetFramebufferSize(mWindow.window(), &mFramebuffer.x, &mFramebuffer.y);
  const float scale = ImGui::GetIO().DisplayFramebufferScale.x;
  const int sidebar = mOptions.showUi ? static_cast<int>(std::min(mSidebarWidth * scale, kMaxSidebarFraction * static_cast<float>(mFramebuffer.x))) : 0;
  mViewRect = {sidebar, 0, std::max(0, mFramebuffer.x - sidebar), mFramebuffer.y};
  const int insetW = static_cast<int>(kInsetFraction * static_cast<float>(mViewRect.z));
  const int insetH = static_cast<int>(kInsetFraction * static_cast<float>(mViewRect.w));
  mInsetRect = {mViewRect.x + mViewRect.z - insetW - kInsetMarginPx, kInsetMarginPx, insetW, insetH};
}

void Viewer::handleInput(float dt) {
  const ImGuiIO& io = ImGui::GetIO();
  const glm::vec2 d(io.MouseDelta.x, io.MouseDelta.y);
  const float scale = io.DisplayFramebufferScale.y;
  const glm::vec2 mouse = glm::vec2(io.MousePos.x, io.MousePos.y) * scale;
  const bool overView = mouse.x >= static_cast<float>(mViewRect.x) && mouse.y >= 0.0f &&
                        mouse.x < static_cast<float>(mViewRect.x + mViewRect.z) && mouse.y < static_cast<float>(mViewRect.w);
  if (!io.WantCaptureKeyboard) {
    if (ImGui::IsKeyPressed(GLFW_KEY_F1) || ImGui::IsKeyPressed(GLFW_KEY_TAB)) mOptions.showUi = !mOptions.showUi;
    if (ImGui::IsKeyPressed(GLFW_KEY_F5)) mHotReload.reloadShaders();
    if (ImGui::IsKeyPressed(GLFW_KEY_F12)) {
      if (io.KeyShift) mWindowShot = nextScreenshotPath();
      else mViewShot = nextScreenshotPath();
    }
    if (ImGui::IsKeyPressed(GLFW_KEY_C, false)) {
      mFly = !mFly;
      if (mFly) mFlyCamera = FlyCamera::fromCamera(mSession.scene().camera);
      else mOrbit = OrbitCamera::fromCamera(mSession.scene().camera);
      setStatus(mFly ? "camera: fly (WASD/QE move, left-drag looks)" : "camera: orbit (left-drag orbits, wheel zooms)", false);
    }
    if (ImGui::IsKeyPressed(GLFW_KEY_H, false)) mHeatmapRequest = mHeatmapSamples;
    if (ImGui::IsKeyPressed(GLFW_KEY_R, false)) flipReference();
    if (ImGui::IsKeyPressed(GLFW_KEY_SPACE, false)) setPlaying(!mPlaying);
    if (mFly) {
      glm::vec3 move(0.0f);
      move.x = float(ImGui::IsKeyDown(GLFW_KEY_D)) - float(ImGui::IsKeyDown(GLFW_KEY_A));
      move.y = float(ImGui::IsKeyDown(GLFW_KEY_E)) - float(ImGui::IsKeyDown(GLFW_KEY_Q));
      move.z = float(ImGui::IsKeyDown(GLFW_KEY_W)) - float(ImGui::IsKeyDown(GLFW_KEY_S));
      if (move != glm::vec3(0.0f)) {
        mFlyCamera.move(move * mFlySpeedMps * dt * (io.KeyShift ? kFlyFastFactor : 1.0f));
        mFlyCamera.apply(mSession.camera());
      }
    }
  }
  if (mViewRect.w <= 0) return;
  // A drag belongs to the view when it starts there, and goes on over the panels.
  const bool hoverView = overView && !io.WantCaptureMouse;
  const bool anyDown = io.MouseDown[0] || io.MouseDown[1] || io.MouseDown[2];
  if (!anyDown) mDragInView = false;
  else if (hoverView && (io.MouseClicked[0] || io.MouseClicked[1] || io.MouseClicked[2])) mDragInView = true;
  const bool pan = io.MouseDown[ImGuiMouseButton_Middle] || (io.MouseDown[ImGuiMouseButton_Left] && io.KeyShift);
  if (mDragInView && d != glm::vec2(0.0f)) {
    if (io.MouseDown[ImGuiMouseButton_Right]) {
      Light& light = mSession.light();
      const glm::vec3 aim = lightAimPoint(light, mSession.scene().bounds());
      const glm::vec2 angles = lightAngles(light, aim);
      setLightAngles(light, aim, angles.x - d.x * kLightRadPerPixel, angles.y - d.y * kLightRadPerPixel);
    } else if (mFly && io.MouseDown[ImGuiMouseButton_Left]) {
      mFlyCamera.look(-d.x * kOrbitRadPerPixel, -d.y * kOrbitRadPerPixel);
      mFlyCamera.apply(mSession.camera());
    } else if (!mFly && pan) {
      const float h = static_cast<float>(mViewRect.w) / scale;
      mOrbit.pan(d.x / h, -d.y / h, mSession.scene().camera.fovYRad);
      mOrbit.apply(mSession.camera());
    } else if (!mFly && io.MouseDown[ImGuiMouseButton_Left]) {
      mOrbit.rotate(-d.x * kOrbitRadPerPixel, d.y * kOrbitRadPerPixel);
      mOrbit.apply(mSession.camera());
    }
  }
  if (hoverView && io.MouseWheel != 0.0f) {
    if (mFly) {
      mFlySpeedMps *= std::pow(kZoomPerWheelNotch, io.MouseWheel);
    } else {
      mOrbit.zoom(std::pow(kZoomPerWheelNotch, -io.MouseWheel));
      mOrbit.apply(mSession.camera());
    }
  }
}

void Viewer::advanceTime(float dt) {
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

void Viewer::setTime(float timeS, bool jump) {
  mSession.setTime(timeS, jump);
  if (mSession.animatesCamera() && mSession.cameraFollows()) {
    // Orbit and fly go on from where the animation put the camera.
    mOrbit = OrbitCamera::fromCamera(mSession.scene().camera);
    mFlyCamera = FlyCamera::fromCamera(mSession.scene().camera);
  }
}

void Viewer::setPlaying(bool playing) {
  if (playing && mSession.duration() <= 0.0f) {
    setStatus(fmt::format("scene {} is still: nothing to play", mSession.scene().name), false);
    return;
  }
  if (playing && !mLoop && mSession.time() >= mSession.duration()) setTime(0.0f);
  mPlaying = playing;
  setStatus(fmt::format("{} at {:.2f} s of {:.2f} s", playing ? "playing" : "paused", mSession.time(), mSession.duration()), false);
}

void Viewer::renderFrame() {
  if (mViewRect.z <= 0 || mViewRect.w <= 0) return;
  const int w = std::max(1, static_cast<int>(std::lround(mRenderScale * static_cast<float>(mViewRect.z))));
  const int h = std::max(1, static_cast<int>(std::lround(mRenderScale * static_cast<float>(mViewRect.w))));
  try {
    const bool cut = mSession.cameraCutPending();
    mSession.render(w, h, litView());
    if (mSplit && cut) mSplit->cutCamera();
    if (mSplit) renderSplit(w, h);
    mRenderError.clear();
  } catch (const Error& e) {
    if (mOptions.scripted) throw;
    mRenderError = e.what();  // shown in the panels; the last good frame stays on screen
  }
}

void Viewer::renderSplit(int width, int height) {
  // The right half sees what the left half sees: the same pose, camera, lights and map size.
  mSplit->setTime(mSession.time(), false);  // a jump reaches it as the main view's cut
  mSplit->camera() = mSession.scene().camera;
  mSplit->lights() = mSession.scene().lights;
  if (mSplit->shadowMapSize() != mSession.shadowMapSize()) mSplit->setShadowMapSize(mSession.shadowMapSize());
  mSplit->render(width, height, litView());
}

bool Viewer::setSplit(const std::string& filter, const std::string& projection) {
  if (filter.empty()) {
    mSplit.reset();
    setStatus("split view off", false);
    return true;
  }
  try {
    Technique technique(projection, filter);
    technique.setMapSize(mSession.shadowMapSize());
    auto split = std::make_unique<ViewSession>(mWindow, mSession.scene(), technique);
    mSplit = std::move(split);
  } catch (const Error& e) {
    setStatus(fmt::format("split view {} · {}: {}", filter, projection, e.what()), true);
    return false;
  }
  mSplitLabel = fmt::format("{} · {}", filter, projection);
  setStatus(fmt::format("split view: left {} · {}, right {}", mSession.filterId(), mSession.projectionId(), mSplitLabel), false);
  return true;
}

int Viewer::litView() const {
  const LitView* v = findLitView(mMain.name);
  return v ? v->debugView : PN_VIEW_SHADED;
}

const gl::Texture* Viewer::findView(const std::string& name) const {
  if (findLitView(name)) return &mSession.renderer().colorTexture();
  if (name == kHeatmapView) return mHeatmapTexture ? &mHeatmapTexture : nullptr;
  if (name == kReferenceView) return mReferenceTexture && mReferenceVersion != 0 ? &mReferenceTexture : nullptr;
  for (const DebugImage& d : mSession.debugImages())
    if (d.name == name && d.texture && *d.texture) return d.texture;
  return nullptr;
}

std::vector<std::string> Viewer::viewNames() const {
  std::vector<std::string> names;
  for (const LitView& v : kLitViews) names.emplace_back(v.name);
  if (mHeatmapTexture) names.emplace_back(kHeatmapView);
  if (mReferenceTexture && mReferenceVersion != 0) names.emplace_back(kReferenceView);
  for (const DebugImage& d : mSession.debugImages())
    if (d.texture && *d.texture) names.push_back(d.name);
  return names;
}

void Viewer::drawViews() {
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glViewport(0, 0, mFramebuffer.x, mFramebuffer.y);
  glDisable(GL_SCISSOR_TEST);
  glClearColor(0.08f, 0.08f, 0.09f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT);
  if (!mSession.hasFrame()) return;
  // Returns false when the slot's image does not exist with this technique (drawn: nothing).
  auto show = [&](ViewState& view, const glm::ivec4& rect, glm::vec2& range, const glm::ivec4* clip) {
    const gl::Texture* texture = findView(view.name);
    if (texture) {
      view.seen = true;
    } else if (!view.seen) {
      // Never found with any technique so far: a typo, not a filter that lacks the image.
      if (mOptions.scripted)
        throw usageError(fmt::format("view '{}': no such image (available: {})", view.name, join(viewNames(), ", ")));
      setStatus(fmt::format("view '{}': no such image", view.name), true);
      view.name = kShadedView;
      texture = findView(kShadedView);
    } else {
      return false;  // e.g. sdf keeps no shadow-map: the slot waits for a filter that does
    }
    DisplaySettings s = view.settings;
    for (const DebugImage& d : mSession.debugImages())  // the image's own "no data" value, if any
      if (d.name == view.name) s.noData = d.noData;
    if (texture == &mSession.renderer().colorTexture() || texture == &mHeatmapTexture || texture == &mReferenceTexture) {
      s = DisplaySettings{};  // colour images are shown as they are
      s.channel = DisplaySettings::kChannelRgb;
      s.autoRange = false;
    }
    try {
      range = mDisplay.draw(*texture, s, rect, clip);
    } catch (const Error& e) {
      if (mOptions.scripted) throw;
      setStatus(fmt::format("view '{}': {}", view.name, e.what()), true);
      view.name = kShadedView;
    }
    return true;
  };
  if (!show(mMain, mViewRect, mMainRange, nullptr)) {
    ViewState shaded{kShadedView, {}, true};
    glm::vec2 unused;
    show(shaded, mViewRect, unused, nullptr);
  }
  if (mSplit && mSplit->hasFrame() && findLitView(mMain.name)) {
    const glm::ivec4 right{mViewRect.x + mViewRect.z / 2, mViewRect.y, mViewRect.z - mViewRect.z / 2, mViewRect.w};
    DisplaySettings s;
    s.channel = DisplaySettings::kChannelRgb;
    s.autoRange = false;
    mDisplay.draw(mSplit->renderer().colorTexture(), s, mViewRect, &right);
  }
  if (mInset.name != kNoInset && mInsetRect.z > 0 && mInsetRect.w > 0) show(mInset, mInsetRect, mInsetRange, nullptr);
}

void Viewer::recordTimings(double frameMs) {
  mLastFrameMs = frameMs;
  auto push = [](std::deque<float>& h, double v) {
    h.push_back(static_cast<float>(v));
    while (h.size() > kHistoryFrames) h.pop_front();
  };
  push(mFrameHistory, frameMs);
  for (const auto& [pass, ms] : mSession.renderer().timings().ms) push(mPassHistory[pass], ms);
}

void Viewer::pollHeatmap() {
  if (std::optional<HeatmapResult> r = mHeatmap.takeResult()) {
    const ColorImage& img = r->image;
    if (!mHeatmapTexture || mHeatmapTexture.width() != img.width || mHeatmapTexture.height() != img.height) {
      mHeatmapTexture = gl::Texture("viewer error heatmap", {GL_TEXTURE_2D, GL_RGBA8, img.width, img.height, 1, 1});
      mHeatmapTexture.setSampling(GL_NEAREST, GL_NEAREST);
    }
    const std::vector<uint8_t> bottomUp = flipRows<uint8_t>(img.rgba, img.width, img.height, 4);
    glTextureSubImage2D(mHeatmapTexture.id(), 0, 0, 0, img.width, img.height, GL_RGBA, GL_UNSIGNED_BYTE, bottomUp.data());
    const VisibilityMetrics& m = r->metrics;
    setStatus(fmt::format("heatmap: RMSE {:.4f}, leak {:.2f}%, over-dark {:.2f}%, penumbra RMSE {:.4f} over {} px ({} spp, {:.1f} s)",
                          m.rmse, m.leakPct, m.overDarkPct, m.penumbraRmse, m.pixels, r->samplesPerPixel, r->seconds),
              false);
    // The same frame lit with V_ref, while the renderer still holds that frame (the view has
    // not changed since the heatmap started).
    if (r->version == mSession.version()) {
      const ColorImage ref = mSession.renderer().shadeWithVisibility(r->vRef);
      if (!mReferenceTexture || mReferenceTexture.width() != ref.width || mReferenceTexture.height() != ref.height) {
        mReferenceTexture = gl::Texture("viewer reference image", {GL_TEXTURE_2D, GL_RGBA8, ref.width, ref.height, 1, 1});
        mReferenceTexture.setSampling(GL_NEAREST, GL_NEAREST);
      }
      const std::vector<uint8_t> refBottomUp = flipRows<uint8_t>(ref.rgba, ref.width, ref.height, 4);
      glTextureSubImage2D(mReferenceTexture.id(), 0, 0, 0, ref.width, ref.height, GL_RGBA, GL_UNSIGNED_BYTE, refBottomUp.data());
      mReferenceVersion = r->version;
    }
    mHeatmapResult = std::move(r);
    mMain.name = std::exchange(mFlipWhenReady, false) && mReferenceVersion != 0 ? kReferenceView : kHeatmapView;
    mMain.seen = true;
  }
  if (const std::string e = mHeatmap.takeError(); !e.empty()) {
    if (mOptions.scripted) throw Error("heatmap: " + e);
    setStatus("heatmap: " + e, true);
  }
}

void Viewer::startHeatmap(int samples) {
  if (!mSession.hasFrame()) return setStatus("heatmap: no frame rendered yet", true);
  Renderer& r = mSession.renderer();
  // The backdrop is the shaded colour; a lit-pass debug view (cascade tints) would mislead.
  ColorImage backdrop = litView() == PN_VIEW_SHADED ? r.readColor() : ColorImage{};
  mHeatmap.start(mSession.scene(), r.readGBuffer(), r.readVisibility(), std::move(backdrop), samples, mSession.version());
  setStatus(fmt::format("heatmap: tracing the reference at {} samples per pixel...", samples), false);
}

void Viewer::flipReference() {
  if (mReferenceVersion != 0 && mReferenceVersion == mSession.version()) {
    const bool toReference = mMain.name != kReferenceView;
    mMain.name = toReference ? kReferenceView : kShadedView;
    mMain.seen = true;
    setStatus(toReference ? fmt::format("showing the reference: the frame lit with V_ref ({} spp); R flips back",
                                        mHeatmapResult ? mHeatmapResult->samplesPerPixel : 0)
                          : fmt::format("showing the technique: {} · {}; R flips to the reference", mSession.filterId(),
                                        mSession.projectionId()),
              false);
    return;
  }
  // No reference of this view yet: trace one, then show it.
  mFlipWhenReady = true;
  mHeatmapRequest = mHeatmapSamples;
}

void Viewer::setView(ViewState& view, const std::string& name, const char* slot) {
  view.name = name;
  const gl::Texture* t = name == kNoInset ? nullptr : findView(name);
  view.seen = name == kNoInset || t != nullptr;
  // V in colour (translucent casters tint it: an RGBA32F layer) is shown as colour.
  if (t && t->desc().format == GL_RGBA32F && name == "visibility") view.settings.channel = DisplaySettings::kChannelRgb;
  setStatus(fmt::format("{}: {}", slot, name), false);
}

bool Viewer::selectScene(const std::string& nameOrPath) {
  try {
    mSession.loadScene(nameOrPath);
  } catch (const Error& e) {
    setStatus(fmt::format("scene {}: {}", nameOrPath, e.what()), true);
    return false;
  }
  mHomeCamera = mSession.scene().camera;
  resetCamera();
  mHeatmap.cancel();
  if (mMain.name == kHeatmapView || mMain.name == kReferenceView) mMain.name = kShadedView;  // another scene's
  mReferenceVersion = 0;
  if (mSplit) setSplit(mSplit->filterId(), mSplit->projectionId());  // the right half on the new scene
  glfwSetWindowTitle(mWindow.window(), title(mSession).c_str());
  std::snprintf(mSavePath, sizeof(mSavePath), "%s-view.json", mSession.scene().name.c_str());
  setStatus(fmt::format("scene {}", mSession.scene().name), false);
  return true;
}

bool Viewer::selectProjection(const std::string& id) {
  try {
    mSession.setProjection(id);
  } catch (const Error& e) {
    setStatus(e.what(), true);
    return false;
  }
  glfwSetWindowTitle(mWindow.window(), title(mSession).c_str());
  setStatus(fmt::format("projection {} (filter {})", id, mSession.filterId()), false);
  return true;
}

bool Viewer::selectFilter(const std::string& id) {
  try {
    mSession.setFilter(id);
  } catch (const Error& e) {
    setStatus(e.what(), true);
    return false;
  }
  glfwSetWindowTitle(mWindow.window(), title(mSession).c_str());
  setStatus(fmt::format("filter {} (projection {})", id, mSession.projectionId()), false);
  return true;
}

std::filesystem::path Viewer::nextScreenshotPath() const {
  for (int i = 1;; ++i) {
    std::filesystem::path p = fmt::format("penumbra-view-{:03}.png", i);
    if (!std::filesystem::exists(p)) return p;
  }
}

void Viewer::screenshotView(const std::filesystem::path& path) {
  const ColorImage img = readWindow(mViewRect);
  writePng(path, img.width, img.height, img.rgba);
  setStatus(fmt::format("screenshot {} {}x{} scene={} projection={} filter={} view={} --camera {}", path.string(), img.width,
                        img.height, mSession.scene().name, mSession.projectionId(), mSession.filterId(), mMain.name,
                        cameraArgument(mSession.scene().camera)),
            false);
}

void Viewer::screenshotWindow(const std::filesystem::path& path) {
  const ColorImage img = readWindow({0, 0, mFramebuffer.x, mFramebuffer.y});
  writePng(path, img.width, img.height, img.rgba);
  setStatus(fmt::format("screenshot-window {} {}x{}", path.string(), img.width, img.height), false);
}

void Viewer::screenshotInset(const std::filesystem::path& path) {
  const ColorImage img = readWindow(mInsetRect);
  writePng(path, img.width, img.height, img.rgba);
  setStatus(fmt::format("screenshot-inset {} {}x{} view={}", path.string(), img.width, img.height, mInset.name), false);
}

void Viewer::saveSettings(const std::filesystem::path& path) {
  saveSceneFile(path, mSession.scene(), mSession.technique());
  setStatus(fmt::format("saved {} (penumbra render --scene {})", path.string(), path.string()), false);
}

}  // namespace penumbra::viewer
