// The viewer's panels (Dear ImGui), one tab per group so that each fits a 1280×720 window
// without scrolling. Parameter widgets are generated from ParamDesc tables: a combo for
// choices, an integer slider for step-1 parameters, a float slider otherwise (logarithmic when
// the range spans orders of magnitude), each showing its unit. Nothing here knows a technique.
#include "viewer/Viewer.h"
#include "viewer/Widgets.h"

#include "text/ImageText.h"
#include "techniques/Registry.h"

#include <penumbra/Error.h>
#include <penumbra/MapSizes.h>
#include <penumbra/SceneIO.h>

#include <fmt/format.h>
#include <imgui.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <set>

namespace penumbra::viewer {
namespace {

// A float slider is logarithmic when max / default exceeds this: a bias of 0.0002 in 0..0.05
// cannot be set on a linear slider a few hundred pixels wide.
constexpr float kLogRangeRatio = 50.0f;
constexpr float kGraphHeightPx = 30.0f;
constexpr float kMinSidebarWidthPx = 160.0f;
constexpr float kMaxSidebarFraction = 0.5f;  // the panels never take more than half the window
constexpr float kStatusLines = 2.0f;         // the status line's fixed height; longer text: tooltip
constexpr float kLabelRoomEm = 9.5f;         // width left for widget labels, in font heights
// ViewSession::paramGroups() is Scene, Projection, Filter, then the add-ons (contact shadows,
// temporal accumulation): the first two sit with the scene and technique choices, the filter's
// own and the add-ons' in a tab of their own (together they would run past 720 px).
constexpr size_t kTechniqueTabGroups = 2;
// DejaVu Sans at this size: as tall as ImGui's default font's lines, readable at 100 % scale.
constexpr float kFontPx = 15.0f;
// The glyphs the labels use: Latin-1, Greek (λ, α, σ, Δ), general punctuation (–, —, …),
// superscripts and subscripts, arrows, mathematical operators (−, √, ≤, ≥, ×), block shapes.
constexpr ImWchar kGlyphRanges[] = {0x0020, 0x00FF, 0x0370, 0x03FF, 0x2010, 0x205E, 0x2070, 0x209F,
                                    0x2190, 0x21FF, 0x2200, 0x22FF, 0x25A0, 0x25FF, 0};

// A unit written "a | b" (light.size: "m | rad") is the first light's: b for a sun, a otherwise.
std::string_view unitFor(const ParamDesc& d, const Scene& scene) {
  const size_t bar = d.unit.find(" | ");
  if (bar == std::string_view::npos) return d.unit;
  const bool sun = !scene.lights.empty() && scene.lights.front().type == LightType::Directional;
  return sun ? d.unit.substr(bar + 3) : d.unit.substr(0, bar);
}

void helpTooltip(const ParamDesc& d, std::string_view unit) {
  if (!ImGui::IsItemHovered()) return;
  ImGui::BeginTooltip();
  ImGui::PushTextWrapPos(ImGui::GetFontSize() * 28.0f);
  ImGui::TextUnformatted(std::string(d.key).c_str());
  ImGui::TextDisabled("%s", std::string(d.help).c_str());
  ImGui::TextDisabled("default %s %s; right-click to reset", formatParamValue(d, d.def).c_str(), std::string(unit).c_str());
  ImGui::PopTextWrapPos();
  ImGui::EndTooltip();
}

// The slider's printf format with the unit after the number ('%' in a unit doubled).
std::string sliderFormat(const char* number, std::string_view unit) {
  std::string u;
  for (const char c : unit) u += c == '%' ? std::string("%%") : std::string(1, c);
  return u.empty() ? std::string(number) : fmt::format("{} {}", number, u);
}

/// One widget for one parameter, its value shown in `unit`. Returns true and the new value when
/// the user changed it.
bool paramWidget(const ParamDesc& d, std::string_view unit, float current, float& out) {
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
    if (ImGui::SliderInt(label.c_str(), &v, static_cast<int>(d.min), static_cast<int>(d.max), sliderFormat("%d", unit).c_str(),
                         ImGuiSliderFlags_AlwaysClamp)) {
      out = static_cast<float>(v);
      changed = true;
    }
  } else {
    float v = current;
    ImGuiSliderFlags flags = ImGuiSliderFlags_AlwaysClamp;
    if (d.min >= 0.0f && d.def > 0.0f && d.max / d.def > kLogRangeRatio) flags |= ImGuiSliderFlags_Logarithmic;
    if (ImGui::SliderFloat(label.c_str(), &v, d.min, d.max, sliderFormat("%.4g", unit).c_str(), flags)) {
      if (d.step > 0.0f) v = d.min + std::round((v - d.min) / d.step) * d.step;
      out = std::clamp(v, d.min, d.max);
      changed = true;
    }
  }
  helpTooltip(d, unit);
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

// The graph's top: the smallest 1-2-5 step at or above `v` (12.3 → 20), so the scale reads at a glance.
float niceCeiling(float v) {
  const float mag = std::pow(10.0f, std::floor(std::log10(std::max(v, 1e-3f))));
  for (const float m : {1.0f, 2.0f, 5.0f, 10.0f})
    if (m * mag >= v) return m * mag;
  return 10.0f * mag;
}

// A rolling graph under its own text line (numbers never drawn over the curve), its scale in a
// gutter on its right: the top value with the unit, and 0.
void plot(const char* label, const std::deque<float>& history, const char* unit) {
  if (history.empty()) return;
  const std::vector<float> values(history.begin(), history.end());
  const float peak = *std::max_element(values.begin(), values.end());
  const float top = niceCeiling(peak * 1.05f);
  ImGui::Text("%-10s %8.2f %s  (max %.2f)", label, static_cast<double>(values.back()), unit, static_cast<double>(peak));
  const std::string topText = fmt::format("{:g} {}", static_cast<double>(top), unit);
  // One gutter for every graph (as wide as a five-digit scale), so that the graphs line up.
  const float gutter = ImGui::CalcTextSize(fmt::format("00000 {}", unit).c_str()).x + ImGui::GetStyle().ItemSpacing.x;
  ImGui::PlotLines(fmt::format("##{}", label).c_str(), values.data(), static_cast<int>(values.size()), 0, nullptr, 0.0f, top,
                   ImVec2(std::max(1.0f, ImGui::GetContentRegionAvail().x - gutter), kGraphHeightPx));
  const ImVec2 lo = ImGui::GetItemRectMin(), hi = ImGui::GetItemRectMax();
  ImDrawList* draw = ImGui::GetWindowDrawList();
  const ImU32 ink = ImGui::GetColorU32(ImGuiCol_TextDisabled);
  const float x = hi.x + ImGui::GetStyle().ItemSpacing.x;
  draw->AddText(ImVec2(x, lo.y), ink, topText.c_str());
  draw->AddText(ImVec2(x, hi.y - ImGui::GetTextLineHeight()), ink, "0");
}

}  // namespace

void Viewer::loadFont() {
  const std::span<const unsigned char> font = text::embeddedFont();
  ImFontConfig config;
  config.FontDataOwnedByAtlas = false;  // the bytes live in the binary
  std::snprintf(config.Name, sizeof(config.Name), "DejaVu Sans, %.0f px", static_cast<double>(kFontPx));
  ImGuiIO& io = ImGui::GetIO();
  // ImGui's API takes a mutable pointer; with FontDataOwnedByAtlas off it only reads the bytes.
  io.FontDefault = io.Fonts->AddFontFromMemoryTTF(const_cast<unsigned char*>(font.data()), static_cast<int>(font.size()),
                                                  kFontPx, &config, kGlyphRanges);
  PN_CHECK(io.FontDefault != nullptr, "the viewer's font could not be loaded");
  ImGuiStyle& style = ImGui::GetStyle();
  style.FramePadding.y = 2.0f;  // compact rows: every tab of parameters fits 720 px
  style.ItemSpacing.y = 3.0f;
}

std::string Viewer::layoutText() const {
  // Every label, unit and meaning the panels and legends can show, against the font's glyphs.
  std::vector<std::string> texts = {"Split λ", "°", "²", "→", "−", "ΔV", "×", "…", "≤", "Angular radius (°)", "Intensity @ 1 m"};
  auto addTable = [&](std::span<const ParamDesc> descs) {
    for (const ParamDesc& d : descs) {
      texts.emplace_back(d.label);
      texts.emplace_back(d.unit);
    }
  };
  addTable(sceneParamDescs());
  for (const std::string& id : projectionIds()) addTable(projectionParams(id));
  for (const std::string& id : filterIds()) {
    addTable(filterParams(id));
    for (const DebugImage& d : makeFilter(id)->debugImages()) texts.emplace_back(d.meaning);
  }
  const ImFont* font = ImGui::GetIO().FontDefault ? ImGui::GetIO().FontDefault : ImGui::GetFont();
  std::set<ImWchar> missing;
  for (const std::string& t : texts)
    for (const int c : text::utf8Codepoints(t))
      if (c > 0xFFFF || !font->FindGlyphNoFallback(static_cast<ImWchar>(c))) missing.insert(static_cast<ImWchar>(c));
  std::string missingText;
  for (const ImWchar c : missing) missingText += fmt::format(" U+{:04X}", static_cast<unsigned>(c));
  return fmt::format("layout panel={} content-bottom={:.0f} window-height={:.0f} scroll-max={:.0f} font=\"{}\" "
                     "missing-glyphs={}{}",
                     mLayout.panel, mLayout.contentBottom, mLayout.windowHeight, mLayout.scrollMax,
                     font->ConfigData ? font->ConfigData->Name : "", missing.size(), missingText);
}

void Viewer::drawPanels() {
  ImGui::SetNextWindowPos(ImVec2(0, 0), ImGuiCond_Always);
  const ImGuiIO& io = ImGui::GetIO();
  if (!mSidebarFitted) {  // wide enough for every tab's whole title ("Technique", not "Tech…")
    const ImGuiStyle& style = ImGui::GetStyle();
    // The window's padding and a scrollbar's room, then each tab: its title, its frame padding,
    // the gap to the next, and a quarter of a font height for what ImGui adds around a tab.
    float tabs = 2.0f * style.WindowPadding.x + style.ScrollbarSize;
    for (const PanelInfo& p : kPanels)
      tabs += ImGui::CalcTextSize(p.title).x + 2.0f * style.FramePadding.x + style.ItemInnerSpacing.x + 0.25f * ImGui::GetFontSize();
    mSidebarWidth = std::max(mSidebarWidth, std::ceil(tabs));
    mSidebarFitted = true;
  }
  const float maxWidth = io.DisplaySize.x * kMaxSidebarFraction;
  ImGui::SetNextWindowSizeConstraints(ImVec2(std::min(kMinSidebarWidthPx, maxWidth), io.DisplaySize.y),
                                      ImVec2(maxWidth, io.DisplaySize.y));
  ImGui::SetNextWindowSize(ImVec2(mSidebarWidth, io.DisplaySize.y), ImGuiCond_Once);
  ImGui::Begin("Penumbra", nullptr, ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoCollapse);
  mSidebarWidth = ImGui::GetWindowWidth();
  ImGui::PushItemWidth(-ImGui::GetFontSize() * kLabelRoomEm);

  // The status line: the latest action (or error), always at the top, at a fixed height.
  const std::string status = !mRenderError.empty() ? "render failed (showing the last good frame): " + mRenderError : mStatus.text;
  ImGui::BeginChild("##status", ImVec2(0.0f, kStatusLines * ImGui::GetTextLineHeightWithSpacing()), false,
                    ImGuiWindowFlags_NoScrollbar);
  ImGui::PushTextWrapPos(0.0f);
  if (mStatus.error || !mRenderError.empty()) ImGui::TextColored(kErrorColor, "%s", status.c_str());
  else ImGui::TextDisabled("%s", status.empty() ? "ready" : status.c_str());
  ImGui::PopTextWrapPos();
  ImGui::EndChild();
  if (ImGui::IsItemHovered() && !status.empty()) {
    ImGui::BeginTooltip();
    ImGui::PushTextWrapPos(ImGui::GetFontSize() * 40.0f);
    ImGui::TextUnformatted(status.c_str());
    ImGui::PopTextWrapPos();
    ImGui::EndTooltip();
  }

  mPlayback.drawTimeControls();
  if (ImGui::BeginTabBar("##panels", ImGuiTabBarFlags_FittingPolicyResizeDown)) {
    for (const PanelInfo& p : kPanels) {
      const bool select = mSelectPanel && *mSelectPanel == p.panel;
      if (!ImGui::BeginTabItem(p.title, nullptr, select ? ImGuiTabItemFlags_SetSelected : 0)) continue;
      switch (p.panel) {
        case Panel::Technique: drawTechniquePanel(); break;
        case Panel::Filter: drawParams(kTechniqueTabGroups, mSession.paramGroups().size()); break;
        case Panel::Lights: drawLightsPanel(); break;
        case Panel::Camera:
          mCamera.drawControls(mSession);
          mPlayback.drawControls();
          break;
        case Panel::Views: drawViewsPanel(); break;
        case Panel::Timings: drawTimingPanel(); break;
        case Panel::Tools: drawToolsPanel(); break;
      }
      mLayout.panel = p.id;
      ImGui::EndTabItem();
    }
    ImGui::EndTabBar();
  }
  mSelectPanel.reset();
  mLayout.contentBottom = ImGui::GetCursorScreenPos().y;
  mLayout.windowHeight = io.DisplaySize.y;
  mLayout.scrollMax = ImGui::GetScrollMaxY();
  ImGui::PopItemWidth();
  ImGui::End();
}

void Viewer::drawTechniquePanel() {
  if (auto s = idCombo("Scene", mSession.scene().name, builtinSceneNames())) selectScene(*s);
  ImGui::InputTextWithHint("##scenefile", "scene .json file", mScenePath, sizeof(mScenePath));
  ImGui::SameLine();
  if (ImGui::Button("Load") && mScenePath[0]) selectScene(mScenePath);
  if (auto p = idCombo("Projection", mSession.projectionId(), projectionIds())) selectProjection(*p);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", std::string(projectionDescription(mSession.projectionId())).c_str());
  if (auto f = idCombo("Filter", mSession.filterId(), filterIds())) selectFilter(*f);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", std::string(filterDescription(mSession.filterId())).c_str());
  int map = mSession.shadowMapSize();
  if (ImGui::BeginCombo("Shadow map", fmt::format("{}² texels", map).c_str())) {
    for (int size : kShadowMapSizes)  // --shadow-map's range: from the least map the defaults hold on
      if (size >= kMinDefaultsMapSizeTexels && size <= gl::maxTextureSize() &&
          ImGui::Selectable(fmt::format("{}²", size).c_str(), size == map)) {
        mSession.setShadowMapSize(size);
        mStatus.set(fmt::format("shadow map {}²", size), false);
      }
    ImGui::EndCombo();
  }
  ImGui::SliderFloat("Render scale", &mRenderScale, 0.25f, 1.0f, "%.2f × view");
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("render at this fraction of the view's size (faster on software GL)");
  drawParams(0, kTechniqueTabGroups);
  hint("the filter's own parameters, contact shadows and temporal accumulation: the Filter tab");
}

void Viewer::drawParams(size_t first, size_t last) {
  const std::vector<ParamGroup> groups = mSession.paramGroups();
  for (size_t i = first; i < std::min(last, groups.size()); ++i) {
    const ParamGroup& g = groups[i];
    ImGui::Separator();
    ImGui::TextDisabled("%s", g.title.c_str());
    if (g.descs.empty()) ImGui::TextDisabled("(no parameters)");
    unsigned lightBits = 0;  // the kinds of light that cast shadows here: other kinds' parameters change nothing
    for (const Light& l : mSession.scene().lights)
      if (l.castsShadow) lightBits |= lightKindBit(l.type);
    // An add-on that is off shows its switch alone (its other parameters change nothing then).
    const bool addOnOff = i > kTechniqueTabGroups && !g.descs.empty() && g.descs.front().choices.size() == 2 &&
                          mSession.paramValue(g.descs.front()) == 0.0f;
    for (const ParamDesc& d : g.descs) {
      if (addOnOff && &d != &g.descs.front()) break;
      float value = 0.0f;
      const std::string_view unit = unitFor(d, mSession.scene());
      const bool idle = (d.lights & lightBits) == 0;
      ImGui::BeginDisabled(idle);
      const bool changed = paramWidget(d, unit, mSession.paramValue(d), value);
      ImGui::EndDisabled();
      if (idle && ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled))
        ImGui::SetTooltip("%s acts on a kind of light this scene does not have: it cannot change this frame", std::string(d.key).c_str());
      if (changed) {
        try {
          mSession.setParam(d, value);
          mStatus.set(fmt::format("{} = {} {}", d.key, formatParamValue(d, value), unit), false);
        } catch (const Error& e) {
          mStatus.set(e.what(), true);
        }
      }
    }
  }
}

void Viewer::drawViewSettings(const char* id, ViewState& view, bool allowNone) {
  std::vector<std::string> names = viewNames();
  if (allowNone) names.insert(names.begin(), kNoInset);
  if (std::find(names.begin(), names.end(), view.name) == names.end()) names.push_back(view.name);  // waiting for it
  if (auto n = idCombo(id, view.name, names)) setView(view, *n, id);
  const gl::Texture* t = view.name == kNoInset ? nullptr : findView(view.name);
  if (!t) {
    if (view.name != kNoInset) ImGui::TextDisabled("no '%s' with %s: shown when a filter has it", view.name.c_str(), mSession.filterId().c_str());
    return;
  }
  if (t == &mSession.renderer().colorTexture() || mHeatmap.owns(t)) return;  // colour images
  ImGui::PushID(id);
  DisplaySettings& s = view.settings;
  const char* channels[] = {"r", "g", "b", "a", "rgb"};
  ImGui::Combo("Channel", &s.channel, channels, IM_ARRAYSIZE(channels));
  const int layers = t->desc().target == GL_TEXTURE_2D ? 1 : t->layers();
  const bool isArray = t->desc().target == GL_TEXTURE_2D_ARRAY;
  if (layers > 1 && isArray) ImGui::Checkbox("All layers", &s.allLayers);
  if (layers > 1 && !(isArray && s.allLayers))
    ImGui::SliderInt(isArray ? "Layer" : "Slice", &s.layer, 0, layers - 1, isArray ? "%d (cascade, cube face)" : "%d (slice)");
  if (t->levels() > 1) ImGui::SliderInt("Mip level", &s.level, 0, t->levels() - 1, "level %d");
  ImGui::Checkbox("Turbo colours", &s.turbo);
  ImGui::SameLine();
  ImGui::Checkbox("Auto range", &s.autoRange);
  if (!s.autoRange) ImGui::DragFloatRange2("Range", &s.lo, &s.hi, 0.001f, 0.0f, 0.0f, "%.4g");
  const glm::vec2 r = &view == &mMain ? mMainRange : mInsetRange;
  ImGui::TextDisabled("%dx%d%s, shown range %.5g .. %.5g", t->width(), t->height(),
                      layers > 1 ? fmt::format("x{}", layers).c_str() : "", static_cast<double>(r.x), static_cast<double>(r.y));
  ImGui::PopID();
}

void Viewer::drawViewsPanel() {
  drawViewSettings("Main view", mMain, false);
  ImGui::Separator();
  drawViewSettings("Inset", mInset, true);
  ImGui::Separator();
  if (ImGui::Button(mMain.name == kReferenceView ? "Show the technique (R)" : "Show the reference (R)")) flipReference();
  hint("R flips the view between the technique and the same frame lit with the ray-traced V_ref (traced first if needed)");
  drawSplitControls();
}

void Viewer::drawSplitControls() {
  bool on = mSplit != nullptr;
  if (ImGui::Checkbox("Split view", &on)) setSplit(on ? mSession.filterId() : "", mSession.projectionId());
  if (!mSplit) {
    hint("left half: this technique; right half: another, same camera and light");
    return;
  }
  std::string filter = mSplit->filterId(), projection = mSplit->projectionId();
  if (auto f = idCombo("Right filter", filter, filterIds())) setSplit(*f, projection);
  else if (auto p = idCombo("Right projection", projection, projectionIds())) setSplit(filter, *p);
}

void Viewer::drawTimingPanel() {
  const PassTimings& t = mSession.renderer().timings();
  plot("frame", mFrameHistory, "ms");
  for (const auto& [pass, ms] : t.ms) {
    (void)ms;
    plot(pass.c_str(), mPassHistory[pass], "ms");
  }
  ImGui::TextDisabled("passes by %s on %s", t.clock.c_str(), mWindow.info().renderer.c_str());
}

void Viewer::drawToolsPanel() {
  mHeatmap.drawControls();
  ImGui::Separator();
  mHotReload.drawControls();
  ImGui::Separator();
  ImGui::InputText("##save", mSavePath, sizeof(mSavePath));
  ImGui::SameLine();
  if (ImGui::Button("Save settings")) {
    try {
      saveSettings(mSavePath);
    } catch (const Error& e) {
      mStatus.set(e.what(), true);
    }
  }
  if (ImGui::Button("Screenshot (F12)")) mViewShot = nextScreenshotPath();
  ImGui::SameLine();
  if (ImGui::Button("with panels (Shift+F12)")) mWindowShot = nextScreenshotPath();
}

}  // namespace penumbra::viewer
