// The viewer's panels (Dear ImGui). Parameter widgets are generated from ParamDesc tables:
// a combo for choices, an integer slider for step-1 parameters, a float slider otherwise
// (logarithmic when the range spans orders of magnitude). Nothing here knows a technique.
#include "viewer/Viewer.h"

#include <penumbra/Error.h>
#include <penumbra/Registry.h>
#include <penumbra/SceneIO.h>

#include <fmt/format.h>
#include <imgui.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>

namespace penumbra::viewer {
namespace {

// A float slider is logarithmic when max / default exceeds this: a bias of 0.0002 in 0..0.05
// cannot be set on a linear slider a few hundred pixels wide.
constexpr float kLogRangeRatio = 50.0f;
constexpr float kGraphHeightPx = 36.0f;
constexpr float kMinSidebarWidthPx = 160.0f;
constexpr float kMaxSidebarFraction = 0.5f;  // the panels never take more than half the window
const ImVec4 kErrorColor{1.0f, 0.45f, 0.4f, 1.0f};

void hint(const char* text) {
  ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyle().Colors[ImGuiCol_TextDisabled]);
  ImGui::TextWrapped("%s", text);
  ImGui::PopStyleColor();
}

void helpTooltip(const ParamDesc& d) {
  if (!ImGui::IsItemHovered()) return;
  ImGui::BeginTooltip();
  ImGui::PushTextWrapPos(ImGui::GetFontSize() * 28.0f);
  ImGui::TextUnformatted(std::string(d.key).c_str());
  ImGui::TextDisabled("%s", std::string(d.help).c_str());
  ImGui::TextDisabled("default %s; right-click to reset", formatParamValue(d, d.def).c_str());
  ImGui::PopTextWrapPos();
  ImGui::EndTooltip();
}

/// One widget for one parameter. Returns true and the new value when the user changed it.
bool paramWidget(const ParamDesc& d, float current, float& out) {
  const std::string label = fmt::format("{}##{}", d.label.empty() ? d.key : d.label, d.key);
  bool changed = false;
  if (d.isChoice()) {
    int index = std::clamp(static_cast<int>(current), 0, static_cast<int>(d.choices.size()) - 1);
    if (ImGui::BeginCombo(label.c_str(), std::string(d.choices[static_cast<size_t>(index)]).c_str())) {
      for (size_t i = 0; i < d.choices.size(); ++i) {
        const bool selected = static_cast<int>(i) == index;
        if (ImGui::Selectable(std::string(d.choices[i]).c_str(), selected)) {
          out = static_cast<float>(i);
          changed = true;
        }
        if (selected) ImGui::SetItemDefaultFocus();
      }
      ImGui::EndCombo();
    }
  } else if (d.isInteger()) {
    int v = static_cast<int>(std::lround(current));
    if (ImGui::SliderInt(label.c_str(), &v, static_cast<int>(d.min), static_cast<int>(d.max), "%d", ImGuiSliderFlags_AlwaysClamp)) {
      out = static_cast<float>(v);
      changed = true;
    }
  } else {
    float v = current;
    ImGuiSliderFlags flags = ImGuiSliderFlags_AlwaysClamp;
    if (d.min >= 0.0f && d.def > 0.0f && d.max / d.def > kLogRangeRatio) flags |= ImGuiSliderFlags_Logarithmic;
    if (ImGui::SliderFloat(label.c_str(), &v, d.min, d.max, "%.4g", flags)) {
      if (d.step > 0.0f) v = d.min + std::round((v - d.min) / d.step) * d.step;
      out = std::clamp(v, d.min, d.max);
      changed = true;
    }
  }
  helpTooltip(d);
  if (ImGui::BeginPopupContextItem(std::string(d.key).c_str())) {
    if (ImGui::MenuItem("Reset to default")) {
      out = d.def;
      changed = true;
    }
    ImGui::EndPopup();
  }
  return changed;
}

/// A combo over string ids; returns the chosen id when it changed.
std::optional<std::string> idCombo(const char* label, const std::string& current, const std::vector<std::string>& ids) {
  std::optional<std::string> chosen;
  if (ImGui::BeginCombo(label, current.c_str())) {
    for (const std::string& id : ids) {
      const bool selected = id == current;
      if (ImGui::Selectable(id.c_str(), selected) && !selected) chosen = id;
      if (selected) ImGui::SetItemDefaultFocus();
    }
    ImGui::EndCombo();
  }
  return chosen;
}

void plot(const char* label, const std::deque<float>& history, const char* unit) {
  if (history.empty()) return;
  const std::vector<float> values(history.begin(), history.end());
  const float peak = *std::max_element(values.begin(), values.end());
  const std::string overlay = fmt::format("{} {:.2f} {} (max {:.2f})", label, values.back(), unit, peak);
  ImGui::PlotLines(fmt::format("##{}", label).c_str(), values.data(), static_cast<int>(values.size()), 0, overlay.c_str(),
                   0.0f, std::max(peak, 1e-3f) * 1.1f, ImVec2(ImGui::GetContentRegionAvail().x, kGraphHeightPx));
}

}  // namespace

void Viewer::drawPanels() {
  ImGui::SetNextWindowPos(ImVec2(0, 0), ImGuiCond_Always);
  const ImGuiIO& io = ImGui::GetIO();
  const float maxWidth = io.DisplaySize.x * kMaxSidebarFraction;
  ImGui::SetNextWindowSizeConstraints(ImVec2(std::min(kMinSidebarWidthPx, maxWidth), io.DisplaySize.y),
                                      ImVec2(maxWidth, io.DisplaySize.y));
  ImGui::SetNextWindowSize(ImVec2(mSidebarWidth, io.DisplaySize.y), ImGuiCond_Once);
  ImGui::Begin("Penumbra", nullptr, ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoCollapse);
  mSidebarWidth = ImGui::GetWindowWidth();
  ImGui::PushItemWidth(-ImGui::GetFontSize() * 9.0f);  // room for labels
  if (!mStatus.empty()) {
    ImGui::PushTextWrapPos(0.0f);
    if (mStatusIsError) ImGui::TextColored(kErrorColor, "%s", mStatus.c_str());
    else ImGui::TextDisabled("%s", mStatus.c_str());
    ImGui::PopTextWrapPos();
  }
  if (!mRenderError.empty()) {
    ImGui::PushTextWrapPos(0.0f);
    ImGui::TextColored(kErrorColor, "render failed (showing the last good frame):\n%s", mRenderError.c_str());
    ImGui::PopTextWrapPos();
  }
  drawTechniquePanel();
  drawTimingPanel();
  drawViewsPanel();
  drawLightsPanel();
  drawLightCameraPanel();
  drawToolsPanel();
  ImGui::PopItemWidth();
  ImGui::End();
}

void Viewer::drawOverlay() {
  if (!mHeatmap.running()) return;
  // A small box in the view's top-left corner, shown with or without the panels.
  const float scale = ImGui::GetIO().DisplayFramebufferScale.x;
  constexpr float kMarginPx = 8.0f;
  ImGui::SetNextWindowPos(ImVec2(static_cast<float>(mViewRect.x) / scale + kMarginPx, kMarginPx), ImGuiCond_Always);
  ImGui::SetNextWindowBgAlpha(0.7f);
  ImGui::Begin("##heatmap progress", nullptr,
               ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoInputs |
                   ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoFocusOnAppearing | ImGuiWindowFlags_NoNav);
  ImGui::TextUnformatted("tracing the reference for the error heatmap");
  ImGui::ProgressBar(mHeatmap.progress(), ImVec2(ImGui::GetFontSize() * 18.0f, 0.0f));
  ImGui::End();
}

void Viewer::drawTechniquePanel() {
  if (!ImGui::CollapsingHeader("Scene and technique", ImGuiTreeNodeFlags_DefaultOpen)) return;
  if (auto s = idCombo("Scene", mSession.scene().name, builtinSceneNames())) selectScene(*s);
  ImGui::InputTextWithHint("##scenefile", "scene .json file", mScenePath, sizeof(mScenePath));
  ImGui::SameLine();
  if (ImGui::Button("Load") && mScenePath[0]) selectScene(mScenePath);
  if (auto p = idCombo("Projection", mSession.projectionId(), projectionIds())) selectProjection(*p);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", std::string(mSession.renderer().projection().description()).c_str());
  if (auto f = idCombo("Filter", mSession.filterId(), filterIds())) selectFilter(*f);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", std::string(mSession.renderer().filter().description()).c_str());
  int map = mSession.shadowMapSize();
  if (ImGui::BeginCombo("Shadow map", fmt::format("{}²", map).c_str())) {
    for (int size : kShadowMapSizes)
      if (size <= gl::maxTextureSize() && ImGui::Selectable(fmt::format("{}²", size).c_str(), size == map)) mSession.setShadowMapSize(size);
    ImGui::EndCombo();
  }
  ImGui::SliderFloat("Render scale", &mRenderScale, 0.25f, 1.0f, "%.2f");
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("render at this fraction of the view's size (faster on software GL)");
  drawParams();
}

void Viewer::drawParams() {
  for (const ParamGroup& g : mSession.paramGroups()) {
    ImGui::Separator();
    ImGui::TextUnformatted(g.title.c_str());
    if (g.descs.empty()) ImGui::TextDisabled("(no parameters)");
    for (const ParamDesc& d : g.descs) {
      float value = 0.0f;
      if (paramWidget(d, mSession.paramValue(d), value)) {
        try {
          mSession.setParam(d, value);
        } catch (const Error& e) {
          setStatus(e.what(), true);
        }
      }
    }
  }
}

void Viewer::drawLightCameraPanel() {
  if (!ImGui::CollapsingHeader("Light and camera", ImGuiTreeNodeFlags_DefaultOpen)) return;
  const Scene& scene = mSession.scene();
  const Light& light = scene.lights.at(mSession.selectedLight());
  const glm::vec3 aim = lightAimPoint(light, scene.bounds());
  glm::vec2 deg = glm::degrees(lightAngles(light, aim));
  hint(isPositional(light) ? "the selected light (Lights), a spot or point light: right-drag in the view moves it around the point it lights"
                           : "the selected light (Lights), a sun: right-drag in the view turns it");
  bool moved = ImGui::SliderFloat("Azimuth", &deg.x, -180.0f, 180.0f, "%.1f°");
  moved |= ImGui::SliderFloat("Elevation", &deg.y, glm::degrees(kMinLightElevationRad), glm::degrees(kMaxLightElevationRad), "%.1f°");
  if (moved) setLightAngles(mSession.light(), aim, glm::radians(deg.x), glm::radians(deg.y));

  int mode = mFly ? 1 : 0;
  ImGui::TextUnformatted("Camera");
  ImGui::SameLine();
  bool modeChanged = ImGui::RadioButton("orbit", &mode, 0);
  ImGui::SameLine();
  modeChanged |= ImGui::RadioButton("fly (C)", &mode, 1);
  if (modeChanged) {
    mFly = mode == 1;
    mOrbit = OrbitCamera::fromCamera(scene.camera);
    mFlyCamera = FlyCamera::fromCamera(scene.camera);
  }
  hint(mFly ? "left-drag look, WASD/QE move (Shift fast), wheel speed" : "left-drag orbit, middle/Shift-drag pan, wheel zoom");
  float fovDeg = glm::degrees(scene.camera.fovYRad);
  if (ImGui::SliderFloat("Field of view", &fovDeg, 10.0f, 120.0f, "%.0f°")) mSession.camera().fovYRad = glm::radians(fovDeg);
  if (ImGui::Button("Reset camera")) {
    mSession.camera() = mHomeCamera;
    resetCamera();
  }
  ImGui::SameLine();
  const std::string argument = "--camera " + cameraArgument(scene.camera);
  if (ImGui::Button("Copy --camera")) ImGui::SetClipboardText(argument.c_str());
  hint(("this view for penumbra render / compare: " + argument).c_str());
}

void Viewer::drawViewSettings(const char* id, ViewState& view, bool allowNone) {
  std::vector<std::string> names = viewNames();
  if (allowNone) names.insert(names.begin(), kNoInset);
  if (auto n = idCombo(id, view.name, names)) view.name = *n;
  const gl::Texture* t = view.name == kNoInset ? nullptr : findView(view.name);
  if (!t || t == &mSession.renderer().colorTexture() || t == &mHeatmapTexture) return;  // colour images: as they are
  ImGui::PushID(id);
  DisplaySettings& s = view.settings;
  const char* channels[] = {"r", "g", "b", "a", "rgb"};
  ImGui::Combo("Channel", &s.channel, channels, IM_ARRAYSIZE(channels));
  const int layers = t->desc().target == GL_TEXTURE_2D ? 1 : t->layers();
  const bool isArray = t->desc().target == GL_TEXTURE_2D_ARRAY;
  if (layers > 1 && isArray) ImGui::Checkbox("All layers", &s.allLayers);
  if (layers > 1 && !(isArray && s.allLayers)) ImGui::SliderInt(isArray ? "Layer" : "Slice", &s.layer, 0, layers - 1);
  if (t->levels() > 1) ImGui::SliderInt("Mip level", &s.level, 0, t->levels() - 1);
  ImGui::Checkbox("Turbo colours", &s.turbo);
  ImGui::SameLine();
  ImGui::Checkbox("Auto range", &s.autoRange);
  if (!s.autoRange) ImGui::DragFloatRange2("Range", &s.lo, &s.hi, 0.001f, 0.0f, 0.0f, "%.4g");
  const glm::vec2 r = &view == &mMain ? mMainRange : mInsetRange;
  ImGui::TextDisabled("%dx%d%s, shown range %.5g .. %.5g", t->width(), t->height(),
                      layers > 1 ? fmt::format("x{}", layers).c_str() : "", r.x, r.y);
  ImGui::PopID();
}

void Viewer::drawViewsPanel() {
  if (!ImGui::CollapsingHeader("Debug views", ImGuiTreeNodeFlags_DefaultOpen)) return;
  drawViewSettings("Main view", mMain, false);
  drawViewSettings("Inset", mInset, true);
}

void Viewer::drawTimingPanel() {
  if (!ImGui::CollapsingHeader("Timings", ImGuiTreeNodeFlags_DefaultOpen)) return;
  const PassTimings& t = mSession.renderer().timings();
  plot("frame", mFrameHistory, "ms");
  for (const auto& [pass, ms] : t.ms) {
    (void)ms;
    plot(pass.c_str(), mPassHistory[pass], "ms");
  }
  ImGui::TextDisabled("passes by %s on %s", t.clock.c_str(), mWindow.info().renderer.c_str());
}

void Viewer::drawToolsPanel() {
  if (!ImGui::CollapsingHeader("Heatmap, shaders, files", ImGuiTreeNodeFlags_DefaultOpen)) return;
  ImGui::SliderInt("Samples", &mHeatmapSamples, 1, 1024, "%d", ImGuiSliderFlags_Logarithmic);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("light samples per pixel of the ray-traced reference");
  if (mHeatmap.running()) {
    ImGui::ProgressBar(mHeatmap.progress(), ImVec2(-ImGui::GetFontSize() * 5.0f, 0.0f));
    ImGui::SameLine();
    if (ImGui::Button("Cancel")) mHeatmap.cancel();
  } else if (ImGui::Button("Error heatmap (H)")) {
    mHeatmapRequest = mHeatmapSamples;
  }
  if (mHeatmapResult) {
    const VisibilityMetrics& m = mHeatmapResult->metrics;
    ImGui::Text("RMSE %.4f  leak %.2f%%  over-dark %.2f%%", m.rmse, m.leakPct, m.overDarkPct);
    ImGui::Text("penumbra RMSE %.4f  (%zu px, %d spp)", m.penumbraRmse, m.pixels, mHeatmapResult->samplesPerPixel);
    if (mHeatmapResult->version != mSession.version()) ImGui::TextColored(kErrorColor, "stale: the view changed since");
  }
  ImGui::Separator();
  if (mWatcher) {
    ImGui::Checkbox("Auto reload", &mAutoReload);
    ImGui::SameLine();
    if (ImGui::Button("Reload shaders (F5)")) reloadShaders();
    ImGui::TextDisabled("from %s", mWatcher->sourceTree().string().c_str());
    for (const std::string& e : mWatcher->errors()) {
      ImGui::PushTextWrapPos(0.0f);
      ImGui::TextColored(kErrorColor, "%s", e.c_str());
      ImGui::PopTextWrapPos();
    }
  } else {
    ImGui::TextDisabled("shader hot reload: start with --shader-dir");
  }
  ImGui::Separator();
  ImGui::InputText("##save", mSavePath, sizeof(mSavePath));
  ImGui::SameLine();
  if (ImGui::Button("Save settings")) {
    try {
      saveSettings(mSavePath);
    } catch (const Error& e) {
      setStatus(e.what(), true);
    }
  }
  if (ImGui::Button("Screenshot (F12)")) mViewShot = nextScreenshotPath();
  ImGui::SameLine();
  if (ImGui::Button("with panels (Shift+F12)")) mWindowShot = nextScreenshotPath();
}

}  // namespace penumbra::viewer
