// The legends drawn over the view: what the colours of the main view and of the inset mean
// (a debug image's values and unit, the cascades' tints, the texel-density ramp, the heatmap's
// ΔV scale), which technique each half of a split view shows, and a note where a slot waits for
// an image the current filter does not have. ImGui overlays: the view's own screenshot (F12,
// `screenshot`) stays the rendered image alone.
#include "viewer/Viewer.h"

#include "comparison/FrameComparison.h"
#include "report/ReportCharts.h"
#include "shared/DebugColors.h"
#include "shared/DensityRamp.h"
#include "shared/Viewer.h"

#include <penumbra/Metrics.h>

#include <fmt/format.h>
#include <imgui.h>

#include <cmath>
#include <functional>
#include <optional>

namespace penumbra::viewer {
namespace {

constexpr float kBarWidthEm = 14.0f;   // colour bar length, in font heights
constexpr float kBarHeightPx = 10.0f;
constexpr int kBarSegments = 32;       // gradient steps drawn per bar
constexpr float kMarginPx = 8.0f;
constexpr float kBackgroundAlpha = 0.75f;
constexpr float kLegendWrapEm = 24.0f;  // legend text wraps at this width, in font heights
constexpr ImGuiWindowFlags kOverlayFlags = ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_AlwaysAutoResize |
                                           ImGuiWindowFlags_NoInputs | ImGuiWindowFlags_NoSavedSettings |
                                           ImGuiWindowFlags_NoFocusOnAppearing | ImGuiWindowFlags_NoNav;

ImU32 rgb(float r, float g, float b) { return ImGui::ColorConvertFloat4ToU32(ImVec4(r, g, b, 1.0f)); }
ImU32 rgb(const glm::vec4& c) { return rgb(c.x, c.y, c.z); }

// A horizontal gradient bar of colour(t), t in [0, 1], with labels under its ends and middle.
void colorBar(const std::function<ImU32(float)>& color, const std::string& low, const std::string& mid, const std::string& high) {
  ImDrawList* draw = ImGui::GetWindowDrawList();
  const ImVec2 p = ImGui::GetCursorScreenPos();
  const float width = kBarWidthEm * ImGui::GetFontSize();
  for (int i = 0; i < kBarSegments; ++i) {
    const float a = static_cast<float>(i) / kBarSegments, b = static_cast<float>(i + 1) / kBarSegments;
    draw->AddRectFilledMultiColor(ImVec2(p.x + a * width, p.y), ImVec2(p.x + b * width, p.y + kBarHeightPx), color(a),
                                  color(b), color(b), color(a));
  }
  ImGui::Dummy(ImVec2(width, kBarHeightPx));
  const float y = ImGui::GetCursorPosY();
  ImGui::TextUnformatted(low.c_str());
  if (!mid.empty()) {
    ImGui::SameLine(std::max(0.0f, 0.5f * width - 0.5f * ImGui::CalcTextSize(mid.c_str()).x + ImGui::GetStyle().WindowPadding.x));
    ImGui::SetCursorPosY(y);
    ImGui::TextUnformatted(mid.c_str());
  }
  ImGui::SameLine(std::max(0.0f, width - ImGui::CalcTextSize(high.c_str()).x + ImGui::GetStyle().WindowPadding.x));
  ImGui::SetCursorPosY(y);
  ImGui::TextUnformatted(high.c_str());
}

std::string number(float v) { return fmt::format("{:.4g}", static_cast<double>(v)); }

// An overlay window at a window-pixel position (x from the left, y from the top).
bool beginOverlay(const char* id, const ImVec2& pos, const ImVec2& pivot) {
  ImGui::SetNextWindowPos(pos, ImGuiCond_Always, pivot);
  ImGui::SetNextWindowBgAlpha(kBackgroundAlpha);
  return ImGui::Begin(id, nullptr, kOverlayFlags);
}

}  // namespace

void Viewer::drawLegends() {
  if (mViewRect.z <= 0 || mViewRect.w <= 0 || !mSession.hasFrame()) return;
  const float scale = ImGui::GetIO().DisplayFramebufferScale.x;
  const float top = static_cast<float>(mFramebuffer.y - mViewRect.y - mViewRect.w) / scale;
  const float left = static_cast<float>(mViewRect.x) / scale, width = static_cast<float>(mViewRect.z) / scale;
  const float bottom = top + static_cast<float>(mViewRect.w) / scale;
  // The main view's legend in its lower-left corner. The inset's sits left of the inset, on its
  // bottom line: the view's lower edge, where a scene's subject seldom is (above the inset it
  // covered pen's contact point); when the main view has a legend too, the inset's stands on it
  // instead, so that the two never overlap whatever their widths.
  const std::optional<float> mainTop =
      drawLegend("##legend main", mMain, mMainRange, {left + kMarginPx, bottom - kMarginPx}, {0.0f, 1.0f});
  if (mInset.name != kNoInset) {
    const float insetBottom = static_cast<float>(mFramebuffer.y - mInsetRect.y) / scale;
    if (mainTop)
      drawLegend("##legend inset", mInset, mInsetRange, {left + kMarginPx, *mainTop - kMarginPx}, {0.0f, 1.0f});
    else
      drawLegend("##legend inset", mInset, mInsetRange, {static_cast<float>(mInsetRect.x) / scale - kMarginPx, insetBottom},
                 {1.0f, 1.0f});
  }
  if (mSplit && isLitView(mMain.name)) {
    // A divider and the two techniques' names over their halves.
    const float mid = left + 0.5f * width;
    ImGui::GetForegroundDrawList()->AddLine(ImVec2(mid, top), ImVec2(mid, bottom), rgb(1.0f, 1.0f, 1.0f), 2.0f);
    if (beginOverlay("##split left", ImVec2(mid - kMarginPx, top + kMarginPx), ImVec2(1, 0)))
      ImGui::Text("%s · %s", mSession.filterId().c_str(), mSession.projectionId().c_str());
    ImGui::End();
    if (beginOverlay("##split right", ImVec2(mid + kMarginPx, top + kMarginPx), ImVec2(0, 0))) ImGui::Text("%s", mSplitLabel.c_str());
    ImGui::End();
  }
}

std::optional<float> Viewer::drawLegend(const char* id, const ViewState& view, const glm::vec2& range, const glm::vec2& anchor,
                                        const glm::vec2& pivot) {
  const std::string& name = view.name;
  if (name == kShadedView) return std::nullopt;  // the picture itself
  if (!beginOverlay(id, ImVec2(anchor.x, anchor.y), ImVec2(pivot.x, pivot.y))) {
    ImGui::End();
    return anchor.y;
  }
  ImGui::PushTextWrapPos(kLegendWrapEm * ImGui::GetFontSize());
  const gl::Texture* texture = findView(name);
  if (!texture) {
    ImGui::TextWrapped("no '%s' with %s: shown again when a filter has it", name.c_str(), mSession.filterId().c_str());
  } else if (name == "cascades") {
    ImGui::TextUnformatted("cascade each pixel reads (blend bands mix two), to the camera depth where it ends:");
    const LightFrusta& frusta = mSession.renderer().frusta();
    const int views = static_cast<int>(frusta.views.size());
    for (int i = 0; i < views; ++i) {
      if (i > 0) ImGui::SameLine();
      const glm::vec4 c = gpu::cascadeColor(i);
      ImGui::ColorButton(fmt::format("##c{}", i).c_str(), ImVec4(c.x, c.y, c.z, 1.0f), ImGuiColorEditFlags_NoTooltip);
      ImGui::SameLine();
      // The last cascade (or a single view) reaches as far as anything is shadowed.
      if (i + 1 < views) ImGui::Text("%d: %s m", i + 1, report::numberText(frusta.views[static_cast<size_t>(i)].splitFarM).c_str());
      else ImGui::Text("%d", i + 1);
    }
    // One view warped by psm, tsm or lispsm has texels of every size: the texel-density view shows them.
    if (views == 1 && frusta.views.front().warped) ImGui::TextUnformatted("one warped map: see texel-density for its texels");
  } else if (name == "texel-density") {
    ImGui::TextUnformatted("screen pixels per shadow-map texel (log scale)");
    colorBar([](float t) { return rgb(gpu::densityRampColor(PN_DENSITY_LOG2_LO + t * (PN_DENSITY_LOG2_HI - PN_DENSITY_LOG2_LO))); },
             fmt::format("1/{:g}", std::exp2(-PN_DENSITY_LOG2_LO)), fmt::format("{:g}", std::exp2(0.5 * (PN_DENSITY_LOG2_LO + PN_DENSITY_LOG2_HI))),
             fmt::format("{:g}", std::exp2(PN_DENSITY_LOG2_HI)));
    ImGui::TextUnformatted("blue: over-sampled (texels smaller than pixels) · red: blocky");
  } else if (name == kHeatmapView) {
    const float full = HeatmapOptions{}.fullScaleDeltaV;
    const int spot = 2 * report::kLabHeatmap.dilatePx + 1;
    ImGui::Text("ΔV = V − V_ref (%d spp), each error over a %d×%d spot", mHeatmap.samplesShown(),
                spot, spot);
    colorBar(
        [full](float t) {
          const float delta = (2.0f * t - 1.0f) * full;
          const uint8_t* tint = delta > 0.0f ? kLeakColor : kOverDarkColor;
          const float a = std::min(1.0f, std::abs(delta) / full), grey = 0.5f;
          return rgb(grey + a * (tint[0] / 255.0f - grey), grey + a * (tint[1] / 255.0f - grey), grey + a * (tint[2] / 255.0f - grey));
        },
        fmt::format("−{:g} too dark", full), "0", fmt::format("+{:g} leaks", full));
  } else if (name == kReferenceView) {
    ImGui::TextWrapped("reference: the frame lit with V_ref (Embree, %d spp); R flips back",
                mHeatmap.samplesShown());
  } else if (texture == &mSession.renderer().colorTexture()) {
    // A lit-pass view not listed above: the colour output.
  } else {
    std::string meaning = "values as stored";
    std::optional<float> noData;
    for (const DebugImage& d : mSession.debugImages())  // the selected light's
      if (d.name == name) {
        if (!d.meaning.empty()) meaning = std::string(d.meaning);
        noData = d.noData;
      }
    ImGui::TextWrapped("%s: %s", name.c_str(), meaning.c_str());
    if (noData) {  // the viewer_display pass's colour for it
      ImGui::ColorButton("##nodata", ImVec4(PN_VIEWER_NO_DATA_RGB, 1.0f), ImGuiColorEditFlags_NoTooltip);
      ImGui::SameLine();
      ImGui::Text("slate: %s, left out of the range", number(*noData).c_str());
    }
    const DisplaySettings& s = view.settings;
    if (s.channel == DisplaySettings::kChannelRgb) {
      ImGui::Text("rgb channels, each %s … %s mapped to 0 … 1", number(range.x).c_str(), number(range.y).c_str());
    } else {
      const char* channel = "rgba" + std::min(std::max(s.channel, 0), 3);
      ImGui::Text("channel %c%s", *channel, s.autoRange ? ", range of the shown pixels" : "");
      colorBar(s.turbo ? std::function<ImU32(float)>([](float t) { return rgb(gpu::turboColor(t)); })
                       : std::function<ImU32(float)>([](float t) { return rgb(t, t, t); }),
               number(range.x), number(0.5f * (range.x + range.y)), number(range.y));
    }
  }
  ImGui::PopTextWrapPos();
  const float legendTop = ImGui::GetWindowPos().y;
  ImGui::End();
  return legendTop;
}

}  // namespace penumbra::viewer
