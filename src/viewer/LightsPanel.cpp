// The viewer's lights: the "Lights" tab (every light of the scene, add/remove, the selected
// light's editor and what its maps got this frame; it fits a 1280×720 window), the labels over the views that say whose
// image is shown and which layer each grid cell is (a point light's cube faces, csm's
// cascades), and the script's `light` action. Every edit goes through ViewSession, which checks
// it (LightEdit.h's lightProblem, the technique's incompatibility) before the next frame.
#include "viewer/LightEdit.h"
#include "viewer/Viewer.h"

#include "core/ShadowsAccess.h"

#include <penumbra/Error.h>
#include <penumbra/MapSizes.h>

#include <fmt/format.h>
#include <imgui.h>

#include <algorithm>
#include <cfloat>
#include <span>

namespace penumbra::viewer {
namespace {

constexpr size_t kListRows = 6;          // rows of the light list before it scrolls
constexpr float kDragFractionOfReach = 0.005f;  // position drag: metres per pixel per metre of scene radius
constexpr float kLabelPadPx = 2.0f;
constexpr ImU32 kLabelBackground = IM_COL32(0, 0, 0, 170);
constexpr ImU32 kLabelText = IM_COL32(255, 255, 255, 255);

// The swatch of an HDR colour: its hue at full brightness.
ImVec4 swatchOf(const glm::vec3& color) {
  const float peak = std::max({color.x, color.y, color.z});
  const glm::vec3 c = peak > 0.0f ? color / peak : color;
  return {c.x, c.y, c.z, 1.0f};
}

// A text box with its top left at `pos` (ImGui display coordinates). Returns its bottom.
float label(ImDrawList* dl, ImVec2 pos, const std::string& text) {
  const ImVec2 size = ImGui::CalcTextSize(text.c_str());
  const float bottom = pos.y + size.y + 2.0f * kLabelPadPx;
  dl->AddRectFilled(pos, ImVec2(pos.x + size.x + 2.0f * kLabelPadPx, bottom), kLabelBackground);
  dl->AddText(ImVec2(pos.x + kLabelPadPx, pos.y + kLabelPadPx), kLabelText, text.c_str());
  return bottom;
}

// Type, azimuth and elevation, position, direction: where the light is and where it points.
bool editLightPlacement(Light& l, const Aabb& bounds, float reach) {
  bool changed = false;
  int type = static_cast<int>(l.type);
  const char* types[] = {lightTypeName(LightType::Directional), lightTypeName(LightType::Spot), lightTypeName(LightType::Point)};
  if (ImGui::Combo("Type", &type, types, IM_ARRAYSIZE(types))) {
    changeLightType(l, static_cast<LightType>(type), bounds);
    changed = true;
  }
  // Azimuth and elevation as seen from the point it lights (what right-drag in the view turns).
  const glm::vec3 aim = lightAimPoint(l, bounds);
  glm::vec2 deg = glm::degrees(lightAngles(l, aim));
  bool turned = ImGui::SliderFloat("Azimuth", &deg.x, -180.0f, 180.0f, "%.1f°");
  turned |= ImGui::SliderFloat("Elevation", &deg.y, glm::degrees(kMinLightElevationRad), glm::degrees(kMaxLightElevationRad), "%.1f°");
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip(isPositional(l) ? "right-drag in the view moves it around the point it lights" : "right-drag in the view turns it");
  if (turned) {
    setLightAngles(l, aim, glm::radians(deg.x), glm::radians(deg.y));
    changed = true;
  }
  if (isPositional(l))
    changed |= ImGui::DragFloat3("Position (m)", &l.position.x, kDragFractionOfReach * reach, -kMaxCoordinateM, kMaxCoordinateM, "%.3f");
  if (l.type != LightType::Point) {
    glm::vec3 d = l.direction;
    if (ImGui::DragFloat3("Direction (unit)", &d.x, 0.01f, -1.0f, 1.0f, "%.3f") && glm::length(d) > 0.0f) {
      l.direction = glm::normalize(d);
      changed = true;
    }
  }
  return changed;
}

// Size, intensity, colour, a spot's cones and a positional light's range: what it sends out.
bool editLightEmission(Light& l, float reach) {
  bool changed = false;
  if (isPositional(l)) {
    changed |= ImGui::SliderFloat("Radius (m)", &l.size, 0.0f, kMaxLightSphereM, "%.4g", ImGuiSliderFlags_Logarithmic | ImGuiSliderFlags_AlwaysClamp);
  } else {
    float deg = glm::degrees(l.size);
    if (ImGui::SliderFloat("Angular radius (°)", &deg, 0.0f, glm::degrees(kMaxSunAngularRadiusRad), "%.3f°", ImGuiSliderFlags_Logarithmic | ImGuiSliderFlags_AlwaysClamp)) {
      l.size = glm::radians(deg);
      changed = true;
    }
  }
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("the light's size: soft-shadow filters widen the penumbra with it; 0 = hard");
  changed |= ImGui::SliderFloat(isPositional(l) ? "Intensity @ 1 m" : "Intensity (irr.)", &l.intensity, 0.0f, kMaxLightIntensity, "%.4g", ImGuiSliderFlags_Logarithmic | ImGuiSliderFlags_AlwaysClamp);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip(isPositional(l) ? "intensity at 1 m (inverse square beyond)" : "irradiance scale");
  changed |= ImGui::ColorEdit3("Colour (linear)", &l.color.x, ImGuiColorEditFlags_Float | ImGuiColorEditFlags_HDR);
  if (l.type == LightType::Spot) {
    float outerDeg = glm::degrees(l.coneAngleRad), innerDeg = glm::degrees(l.innerConeAngleRad);
    if (ImGui::SliderFloat("Outer cone (°)", &outerDeg, kMinSpotConeDeg, glm::degrees(kMaxSpotConeRad), "%.1f°", ImGuiSliderFlags_AlwaysClamp)) {
      l.coneAngleRad = glm::radians(outerDeg);
      l.innerConeAngleRad = std::min(l.innerConeAngleRad, l.coneAngleRad);  // inner ≤ outer
      changed = true;
    }
    if (ImGui::SliderFloat("Inner cone (°)", &innerDeg, 0.0f, outerDeg, "%.1f°", ImGuiSliderFlags_AlwaysClamp)) {
      l.innerConeAngleRad = glm::radians(innerDeg);
      changed = true;
    }
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("half angles: full light inside the inner cone, none beyond the outer");
  }
  if (isPositional(l)) {
    changed |= ImGui::DragFloat("Range (m)", &l.rangeM, kDragFractionOfReach * reach, 0.0f, kMaxCoordinateM, "%.3f", ImGuiSliderFlags_AlwaysClamp);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("no light and no shadow beyond it; 0 = unlimited; must exceed the radius");
  }
  return changed;
}

// Whether it casts a shadow, and its own map size and map updates (each may defer to the technique).
bool editLightShadow(Light& l, int techniqueMapSize) {
  bool changed = ImGui::Checkbox("Casts shadow", &l.castsShadow);
  // The light's own map size (texels per side); 0 = the technique's (Shadow map, above).
  const int own = l.shadow.mapSize;
  const std::string shown = own > 0 ? fmt::format("{}²", own) : fmt::format("technique's ({}²)", techniqueMapSize);
  if (ImGui::BeginCombo("Map size (texels)", shown.c_str())) {
    if (ImGui::Selectable("technique's", own == 0)) {
      l.shadow.mapSize = 0;
      changed = true;
    }
    for (int size : kShadowMapSizes)
      if (size <= gl::maxTextureSize() && ImGui::Selectable(fmt::format("{}²", size).c_str(), size == own)) {
        l.shadow.mapSize = size;
        changed = true;
      }
    ImGui::EndCombo();
  }
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("texels per side of this light's maps (a budget may give it fewer); below %d² the default bias and filters no longer keep acne and detached shadows away", kMinDefaultsMapSizeTexels);
  // The light's own map updates (docs/embedding.md#cached-maps); none = the technique's.
  const std::string policy = l.shadow.updates ? mapUpdatesName(*l.shadow.updates) : "technique's";
  if (ImGui::BeginCombo("Map updates", policy.c_str())) {
    if (ImGui::Selectable("technique's", !l.shadow.updates)) {
      l.shadow.updates.reset();
      changed = true;
    }
    for (const MapUpdates u : {MapUpdates{}, MapUpdates{MapUpdates::Policy::WhenInvalid}, MapUpdates{MapUpdates::Policy::Budget, 1},
                               MapUpdates{MapUpdates::Policy::Budget, 2}})
      if (ImGui::Selectable(mapUpdatesName(u).c_str(), l.shadow.updates == u)) {
        l.shadow.updates = u;
        changed = true;
      }
    ImGui::EndCombo();
  }
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("when this light's maps are drawn again: every frame; when invalid (static casters cached); or N maps a "
                      "frame round-robin, the others kept as an earlier frame drew them");
  return changed;
}

}  // namespace

void Viewer::drawLightsPanel() {
  drawLightList();
  // The selected light, edited on a copy that ViewSession checks.
  const Scene& scene = mSession.scene();
  const size_t selected = mSession.selectedLight();
  Light l = scene.lights.at(selected);
  const float reach = std::max(scene.bounds().radius(), 1.0f);
  ImGui::PushID("selected");
  ImGui::TextUnformatted(lightLabel(l, selected).c_str());
  bool changed = editLightPlacement(l, scene.bounds(), reach);
  changed |= editLightEmission(l, reach);
  changed |= editLightShadow(l, mSession.shadowMapSize());
  if (changed) applyLightEdit(selected, l);
  drawLightMapsReport(selected, l);
  ImGui::PopID();
}

// The scene's lights, one selectable row each, and the buttons that add and remove lights.
void Viewer::drawLightList() {
  const Scene& scene = mSession.scene();
  const size_t count = scene.lights.size();
  const float row = ImGui::GetTextLineHeightWithSpacing();
  const float rows = static_cast<float>(std::min(count, kListRows)) + 0.25f;
  if (ImGui::BeginListBox("##lights", ImVec2(-FLT_MIN, row * rows))) {
    for (size_t i = 0; i < count; ++i) {
      const Light& l = scene.lights[i];
      ImGui::PushID(static_cast<int>(i));
      ImGui::ColorButton("##tint", swatchOf(l.color), ImGuiColorEditFlags_NoTooltip | ImGuiColorEditFlags_NoPicker,
                         ImVec2(ImGui::GetTextLineHeight(), ImGui::GetTextLineHeight()));
      ImGui::SameLine();
      const std::string text = fmt::format("{}: {}  ×{:.3g}{}", i, lightTypeName(l.type), l.intensity, l.castsShadow ? "" : "  (no shadow)");
      if (ImGui::Selectable(text.c_str(), i == mSession.selectedLight())) {
        mSession.selectLight(i);
        mStatus.set(fmt::format("selected {}: the views show its images", lightLabel(l, i)), false);
      }
      ImGui::PopID();
    }
    ImGui::EndListBox();
  }
  ImGui::BeginDisabled(count >= kMaxShadowedLights);
  for (LightType type : {LightType::Directional, LightType::Spot, LightType::Point}) {
    if (ImGui::Button(fmt::format("+ {}", lightTypeName(type)).c_str())) {
      try {
        mSession.addLight(makeLight(type, scene.bounds(), scene.camera, count));
        mStatus.set(fmt::format("added {}", lightLabel(mSession.scene().lights.back(), count)), false);
      } catch (const Error& e) {
        mStatus.set(e.what(), true);
      }
    }
    ImGui::SameLine();
  }
  ImGui::EndDisabled();
  ImGui::BeginDisabled(count <= 1);
  if (ImGui::Button("Remove")) {
    try {
      const std::string removed = lightLabel(scene.lights[mSession.selectedLight()], mSession.selectedLight());
      mSession.removeLight(mSession.selectedLight());
      mStatus.set("removed " + removed, false);
    } catch (const Error& e) {
      mStatus.set(e.what(), true);
    }
  }
  ImGui::EndDisabled();
  if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled))
    ImGui::SetTooltip(count <= 1 ? "a scene needs at least one light" : "remove the selected light");
}

// Hands the edited copy to ViewSession, which refuses what it cannot render (the status says why).
void Viewer::applyLightEdit(size_t selected, const Light& l) {
  try {
    mSession.setLight(selected, l);
    mStatus.set(fmt::format("edited {}", lightLabel(l, selected)), false);
  } catch (const Error& e) {
    mStatus.set(e.what(), true);
  }
}

// What the selected light's maps got last frame, a button that shows them in the inset, and a
// line on what the views show.
void Viewer::drawLightMapsReport(size_t selected, const Light& l) {
  const std::vector<LightShadowReport>& reports = mSession.renderer().shadows().lightReports();
  if (selected < reports.size()) {
    const LightShadowReport& r = reports[selected];
    ImGui::TextDisabled("maps %d² × %d %s, importance %.2f", r.mapSize, r.views,
                        l.type == LightType::Point ? "cube faces" : r.views > 1 ? "views" : "view", r.importance);
    if (r.updates.policy == MapUpdates::Policy::Budget)  // what its budget left as it was
      ImGui::TextDisabled("kept %d maps last frame; oldest %d frames old", r.keptMaps, r.staleness);
  }
  if (ImGui::Button("Show its maps in the inset")) {
    const std::vector<DebugImage> own = debugImages(mSession.renderer().shadows(), mSession.shownLight());
    setView(mInset, own.size() > 1 ? own[1].name : own.front().name, "inset");  // its filter's first map, else its visibility
  }
  ImGui::PushTextWrapPos(0.0f);
  ImGui::TextDisabled("the views show the selected light's visibility and maps; right-drag in the view moves it");
  ImGui::PopTextWrapPos();
}

void Viewer::drawViewLabels() {
  if (!mSession.hasFrame()) return;
  const size_t shown = mSession.shownLight();
  const std::vector<DebugImage> own = debugImages(mSession.renderer().shadows(), shown);
  const Light& light = mSession.scene().lights.at(std::min(shown, mSession.scene().lights.size() - 1));
  const ImVec2 scale = ImGui::GetIO().DisplayFramebufferScale;
  // Window pixels (origin lower left) → ImGui display coordinates (origin top left).
  auto topLeft = [&](const glm::ivec4& r) {
    return ImVec2(static_cast<float>(r.x) / scale.x, static_cast<float>(mFramebuffer.y - (r.y + r.w)) / scale.y);
  };
  auto layerName = [&](int layer) {
    if (light.type == LightType::Point) return fmt::format("face {}", cubeFaceName(layer));
    // Views split by camera depth (csm, sdsm) are cascades; a single view is the map's only layer.
    const bool cascades = mSession.renderer().frusta().views.size() > 1;
    return fmt::format("{} {}", cascades ? "cascade" : "layer", layer);
  };
  ImDrawList* dl = ImGui::GetForegroundDrawList();
  // Inside the slot's top-left corner: the legends (Legends.cpp) sit at the main view's lower
  // left and above the inset, so the title and the cell labels stay clear of them.
  auto labelSlot = [&](const ViewState& view, const glm::ivec4& rect) {
    const auto it = std::find_if(own.begin(), own.end(), [&](const DebugImage& d) { return d.name == view.name; });
    if (it == own.end() || !it->texture || !*it->texture) return;  // not one of the light's images
    const gl::Texture& t = *it->texture;
    const int layers = t.desc().target == GL_TEXTURE_2D_ARRAY ? t.layers() : 1;
    const bool grid = layers > 1 && view.settings.allLayers;
    std::string title = fmt::format("{}: {}", lightLabel(light, shown), view.name);
    if (layers > 1 && !grid) title += ", " + layerName(std::clamp(view.settings.layer, 0, layers - 1));
    if (grid && light.type == LightType::Point && layers == kCubeFaces) title += " (cube faces)";
    const float titleBottom = label(dl, topLeft(rect), title);
    if (!grid) return;
    const int level = std::clamp(view.settings.level, 0, std::max(t.levels(), 1) - 1);
    const std::vector<glm::ivec4> cells = layerCells(rect, std::max(1, t.width() >> level), std::max(1, t.height() >> level), layers);
    for (int i = 0; i < layers; ++i) {
      const glm::ivec4& c = cells[static_cast<size_t>(i)];
      const ImVec2 corner = topLeft(c);  // each cell's top left, under the title
      label(dl, ImVec2(corner.x, std::max(corner.y, titleBottom + kLabelPadPx)), layerName(i));
    }
  };
  labelSlot(mMain, mViewRect);
  if (mInset.name != kNoInset && mInsetRect.z > 0 && mInsetRect.w > 0) labelSlot(mInset, mInsetRect);
}

void Viewer::executeLight(const ScriptAction& a) {
  const std::string& sub = a.args[0];
  const Scene& scene = mSession.scene();
  // Light indices were checked against kMaxShadowedLights when the script was read; ViewSession
  // checks them against the scene's lights now.
  auto index = [&] { return static_cast<size_t>(scriptInt(a, 1, 0, static_cast<int>(kMaxShadowedLights) - 1)); };
  if (sub == "select") {
    mSession.selectLight(index());
  } else if (sub == "add") {
    const size_t added = scene.lights.size();
    mSession.addLight(makeLight(parseLightType(a.args[1]), scene.bounds(), scene.camera, added));
    mStatus.set(fmt::format("added {}", lightLabel(mSession.scene().lights.back(), added)), false);
  } else if (sub == "remove") {
    const size_t i = index();
    const std::string removed = lightLabel(mSession.lightAt(i), i);
    mSession.removeLight(i);
    mStatus.set("removed " + removed, false);
  } else if (sub == "set") {
    const size_t i = index();
    const std::span<const std::string> value = std::span(a.args).subspan(3);
    mSession.setLight(i, setLightField(mSession.lightAt(i), a.args[2], value, scene.bounds()));
  } else {  // angles, direction, position: the selected light
    const size_t i = mSession.selectedLight();
    Light l = scene.lights.at(i);
    if (sub == "angles") {
      setLightAngles(l, lightAimPoint(l, scene.bounds()), glm::radians(scriptFloat(a, 1)), glm::radians(scriptFloat(a, 2)));
      mSession.setLight(i, l);
    } else {
      mSession.setLight(i, setLightField(l, sub, std::span(a.args).subspan(1), scene.bounds()));
    }
  }
}

}  // namespace penumbra::viewer
