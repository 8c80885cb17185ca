#include "viewer/Viewer.h"

#include "viewer/SceneWriter.h"

#include "shared/Enums.h"

#include <penumbra/Error.h>
#include <penumbra/ImageIO.h>
#include "techniques/Registry.h"
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

constexpr float kInsetFraction = 0.32f;      // inset side relative to the view
constexpr int kInsetMarginPx = 8;
constexpr float kMaxSidebarFraction = 0.5f;  // as in Panels.cpp: the panels never take more than half
constexpr size_t kHistoryFrames = 240;       // rolling graphs: 4 s at 60 fps
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
  mCamera.home(mSession);
  std::snprintf(mSavePath, sizeof(mSavePath), "%s-view.json", mSession.scene().name.c_str());
}

Viewer::~Viewer() {
  ImGui_ImplOpenGL3_Shutdown();
  ImGui_ImplGlfw_Shutdown();
  ImGui::DestroyContext();
}

int Viewer::run() {
  while (frame()) {
  }
  return 0;
}

bool Viewer::frame() {
  const auto start = std::chrono::steady_clock::now();
  glfwPollEvents();
  if (glfwWindowShouldClose(mWindow.window())) return false;
  if (mOptions.scripted) mScript.run();
  if (mScript.finished()) return false;

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
  mHeatmap.drawProgress(static_cast<float>(mViewRect.x) / ImGui::GetIO().DisplayFramebufferScale.x);
  drawLegends();
  const float dt = static_cast<float>(mLastFrameMs) * 1e-3f;
  const Camera before = mSession.scene().camera;
  handleInput(dt);
  const Camera& after = mSession.scene().camera;
  if (mSession.animatesCamera() && mSession.cameraFollows() &&
      (before.position != after.position || before.target != after.target || before.fovYRad != after.fovYRad)) {
    mSession.setCameraFollows(false);  // the user took the camera
    mStatus.set("camera: yours now (Camera tab: follow the animation again)", false);
  }
  mPlayback.advance(mOptions.scripted ? kScriptedFrameS : dt);
  if (const std::optional<std::string> show = mHeatmap.poll()) {
    mMain.name = *show;
    mMain.seen = true;
  }
  mHotReload.poll({&mSession, mSplit.get()});

  renderFrame();
  mHeatmap.startRequested(litView() == PN_VIEW_SHADED);  // on this frame
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
  if (!io.WantCaptureKeyboard) {
    if (ImGui::IsKeyPressed(GLFW_KEY_F1) || ImGui::IsKeyPressed(GLFW_KEY_TAB)) mOptions.showUi = !mOptions.showUi;
    if (ImGui::IsKeyPressed(GLFW_KEY_F5)) mHotReload.reloadShaders();
    if (ImGui::IsKeyPressed(GLFW_KEY_F12)) {
      if (io.KeyShift) mWindowShot = nextScreenshotPath();
      else mViewShot = nextScreenshotPath();
    }
    if (ImGui::IsKeyPressed(GLFW_KEY_H, false)) mHeatmap.request();
    if (ImGui::IsKeyPressed(GLFW_KEY_R, false)) flipReference();
    if (ImGui::IsKeyPressed(GLFW_KEY_SPACE, false)) mPlayback.setPlaying(!mPlayback.playing());
  }
  mCamera.handleInput(mSession, mViewRect, dt);  // C, the fly keys, the mouse over the view
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
    mStatus.set("split view off", false);
    return true;
  }
  try {
    Technique technique(projection, filter);
    technique.setMapSize(mSession.shadowMapSize());
    auto split = std::make_unique<ViewSession>(mWindow, mSession.scene(), technique);
    mSplit = std::move(split);
  } catch (const Error& e) {
    mStatus.set(fmt::format("split view {} · {}: {}", filter, projection, e.what()), true);
    return false;
  }
  mSplitLabel = fmt::format("{} · {}", filter, projection);
  mStatus.set(fmt::format("split view: left {} · {}, right {}", mSession.filterId(), mSession.projectionId(), mSplitLabel), false);
  return true;
}

int Viewer::litView() const {
  const LitView* v = findLitView(mMain.name);
  return v ? v->debugView : PN_VIEW_SHADED;
}

const gl::Texture* Viewer::findView(const std::string& name) const {
  if (findLitView(name)) return &mSession.renderer().colorTexture();
  if (name == kHeatmapView || name == kReferenceView) return mHeatmap.image(name);
  for (const DebugImage& d : mSession.debugImages())
    if (d.name == name && d.texture && *d.texture) return d.texture;
  return nullptr;
}

std::vector<std::string> Viewer::viewNames() const {
  std::vector<std::string> names;
  for (const LitView& v : kLitViews) names.emplace_back(v.name);
  for (const char* own : {kHeatmapView, kReferenceView})
    if (mHeatmap.image(own)) names.emplace_back(own);
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
      mStatus.set(fmt::format("view '{}': no such image", view.name), true);
      view.name = kShadedView;
      texture = findView(kShadedView);
    } else {
      return false;  // e.g. sdf keeps no shadow-map: the slot waits for a filter that does
    }
    DisplaySettings s = view.settings;
    for (const DebugImage& d : mSession.debugImages())  // the image's own "no data" value, if any
      if (d.name == view.name) s.noData = d.noData;
    if (texture == &mSession.renderer().colorTexture() || mHeatmap.owns(texture)) {
      s = DisplaySettings{};  // colour images are shown as they are
      s.channel = DisplaySettings::kChannelRgb;
      s.autoRange = false;
    }
    try {
      range = mDisplay.draw(*texture, s, rect, clip);
    } catch (const Error& e) {
      if (mOptions.scripted) throw;
      mStatus.set(fmt::format("view '{}': {}", view.name, e.what()), true);
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

void Viewer::flipReference() {
  if (const std::optional<std::string> show = mHeatmap.flip(mMain.name)) {
    mMain.name = *show;
    mMain.seen = true;
  }
}

void Viewer::setView(ViewState& view, const std::string& name, const char* slot) {
  view.name = name;
  const gl::Texture* t = name == kNoInset ? nullptr : findView(name);
  view.seen = name == kNoInset || t != nullptr;
  // V in colour (translucent casters tint it: an RGBA32F layer) is shown as colour.
  if (t && t->desc().format == GL_RGBA32F && name == "visibility") view.settings.channel = DisplaySettings::kChannelRgb;
  mStatus.set(fmt::format("{}: {}", slot, name), false);
}

void Viewer::showView(bool inset, const std::string& name) {
  if (inset)
    setView(mInset, name, "inset");
  else
    setView(mMain, name, "main view");
}

void Viewer::openPanel(const std::string& id) {
  for (const PanelInfo& p : kPanels)
    if (id == p.id) mSelectPanel = p.panel;
}

void Viewer::requestScreenshot(Shot shot, const std::filesystem::path& path) {
  switch (shot) {
    case Shot::View: mViewShot = path; break;
    case Shot::Window: mWindowShot = path; break;
    case Shot::Inset:
      if (mInset.name == kNoInset) throw usageError("no inset is shown (inset NAME first)");
      mInsetShot = path;
      break;
  }
}

bool Viewer::selectScene(const std::string& nameOrPath) {
  try {
    mSession.loadScene(nameOrPath);
  } catch (const Error& e) {
    mStatus.set(fmt::format("scene {}: {}", nameOrPath, e.what()), true);
    return false;
  }
  mCamera.home(mSession);
  mHeatmap.forgetScene();
  if (mMain.name == kHeatmapView || mMain.name == kReferenceView) mMain.name = kShadedView;  // another scene's
  if (mSplit) setSplit(mSplit->filterId(), mSplit->projectionId());  // the right half on the new scene
  glfwSetWindowTitle(mWindow.window(), title(mSession).c_str());
  std::snprintf(mSavePath, sizeof(mSavePath), "%s-view.json", mSession.scene().name.c_str());
  mStatus.set(fmt::format("scene {}", mSession.scene().name), false);
  return true;
}

bool Viewer::selectProjection(const std::string& id) {
  try {
    mSession.setProjection(id);
  } catch (const Error& e) {
    mStatus.set(e.what(), true);
    return false;
  }
  glfwSetWindowTitle(mWindow.window(), title(mSession).c_str());
  mStatus.set(fmt::format("projection {} (filter {})", id, mSession.filterId()), false);
  return true;
}

bool Viewer::selectFilter(const std::string& id) {
  try {
    mSession.setFilter(id);
  } catch (const Error& e) {
    mStatus.set(e.what(), true);
    return false;
  }
  glfwSetWindowTitle(mWindow.window(), title(mSession).c_str());
  mStatus.set(fmt::format("filter {} (projection {})", id, mSession.projectionId()), false);
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
  mStatus.set(fmt::format("screenshot {} {}x{} scene={} projection={} filter={} view={} --camera {}", path.string(), img.width,
                        img.height, mSession.scene().name, mSession.projectionId(), mSession.filterId(), mMain.name,
                        cameraArgument(mSession.scene().camera)),
            false);
}

void Viewer::screenshotWindow(const std::filesystem::path& path) {
  const ColorImage img = readWindow({0, 0, mFramebuffer.x, mFramebuffer.y});
  writePng(path, img.width, img.height, img.rgba);
  mStatus.set(fmt::format("screenshot-window {} {}x{}", path.string(), img.width, img.height), false);
}

void Viewer::screenshotInset(const std::filesystem::path& path) {
  const ColorImage img = readWindow(mInsetRect);
  writePng(path, img.width, img.height, img.rgba);
  mStatus.set(fmt::format("screenshot-inset {} {}x{} view={}", path.string(), img.width, img.height, mInset.name), false);
}

void Viewer::saveSettings(const std::filesystem::path& path) {
  saveSceneFile(path, mSession.scene(), mSession.technique());
  mStatus.set(fmt::format("saved {} (penumbra render --scene {})", path.string(), path.string()), false);
}

}  // namespace penumbra::viewer
