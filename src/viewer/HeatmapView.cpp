#include "viewer/HeatmapView.h"

#include "viewer/ViewSession.h"
#include "viewer/Widgets.h"

#include <penumbra/Error.h>
#include <penumbra/ImageIO.h>

#include <fmt/format.h>
#include <imgui.h>

#include <utility>

namespace penumbra::viewer {
namespace {

// An RGBA8 image (row 0 = top) into `texture`, made again when its size changed.
void upload(gl::Texture& texture, const char* label, const ColorImage& img) {
  if (!texture || texture.width() != img.width || texture.height() != img.height) {
    texture = gl::Texture(label, {GL_TEXTURE_2D, GL_RGBA8, img.width, img.height, 1, 1});
    texture.setSampling(GL_NEAREST, GL_NEAREST);
  }
  const std::vector<uint8_t> bottomUp = flipRows<uint8_t>(img.rgba, img.width, img.height, 4);
  glTextureSubImage2D(texture.id(), 0, 0, 0, img.width, img.height, GL_RGBA, GL_UNSIGNED_BYTE, bottomUp.data());
}

}  // namespace

void HeatmapView::startRequested(bool shaded) {
  if (!mRequest) return;
  const int samples = *std::exchange(mRequest, std::nullopt);
  if (!mSession.hasFrame()) return mStatus.set("heatmap: no frame rendered yet", true);
  Renderer& r = mSession.renderer();
  ColorImage backdrop = shaded ? r.readColor() : ColorImage{};
  mJob.start(mSession.scene(), r.readGBuffer(), r.readVisibility(), std::move(backdrop), samples, mSession.version());
  mStatus.set(fmt::format("heatmap: tracing the reference at {} samples per pixel...", samples), false);
}

std::optional<std::string> HeatmapView::poll() {
  std::optional<std::string> show;
  if (std::optional<HeatmapResult> r = mJob.takeResult()) {
    upload(mHeatmap, "viewer error heatmap", r->image);
    const VisibilityMetrics& m = r->metrics;
    mStatus.set(fmt::format("heatmap: RMSE {:.4f}, leak {:.2f}%, over-dark {:.2f}%, penumbra RMSE {:.4f} over {} px ({} spp, {:.1f} s)",
                            m.rmse, m.leakPct, m.overDarkPct, m.penumbraRmse, m.pixels, r->samplesPerPixel, r->seconds),
                false);
    // The same frame lit with V_ref, while the renderer still holds that frame (the view has
    // not changed since the heatmap started).
    if (r->version == mSession.version()) {
      upload(mReference, "viewer reference image", mSession.renderer().shadeWithVisibility(r->vRef));
      mReferenceVersion = r->version;
    }
    mResult = std::move(r);
    show = std::exchange(mFlipWhenReady, false) && mReferenceVersion != 0 ? kReferenceView : kHeatmapView;
  }
  if (const std::string e = mJob.takeError(); !e.empty()) {
    if (mScripted) throw Error("heatmap: " + e);
    mStatus.set("heatmap: " + e, true);
  }
  return show;
}

std::optional<std::string> HeatmapView::flip(const std::string& mainView) {
  if (mReferenceVersion != 0 && mReferenceVersion == mSession.version()) {
    const bool toReference = mainView != kReferenceView;
    mStatus.set(toReference ? fmt::format("showing the reference: the frame lit with V_ref ({} spp); R flips back", samplesShown())
                            : fmt::format("showing the technique: {} · {}; R flips to the reference", mSession.filterId(),
                                          mSession.projectionId()),
                false);
    return toReference ? kReferenceView : "shaded";
  }
  // No reference of this view yet: trace one, then show it.
  mFlipWhenReady = true;
  request();
  return std::nullopt;
}

void HeatmapView::forgetScene() {
  mJob.cancel();
  mReferenceVersion = 0;
}

const gl::Texture* HeatmapView::image(const std::string& name) const {
  if (name == kHeatmapView) return mHeatmap ? &mHeatmap : nullptr;
  if (name == kReferenceView) return mReference && mReferenceVersion != 0 ? &mReference : nullptr;
  return nullptr;
}

void HeatmapView::drawProgress(float viewLeftPx) {
  if (!mJob.running()) return;
  // A small box in the view's top-left corner, shown with or without the panels.
  constexpr float kMarginPx = 8.0f;
  ImGui::SetNextWindowPos(ImVec2(viewLeftPx + kMarginPx, kMarginPx), ImGuiCond_Always);
  ImGui::SetNextWindowBgAlpha(0.7f);
  ImGui::Begin("##heatmap progress", nullptr,
               ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoInputs |
                   ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoFocusOnAppearing | ImGuiWindowFlags_NoNav);
  ImGui::TextUnformatted("tracing the reference for the error heatmap");
  ImGui::ProgressBar(mJob.progress(), ImVec2(ImGui::GetFontSize() * 18.0f, 0.0f));
  ImGui::End();
}

void HeatmapView::drawControls() {
  ImGui::SliderInt("Samples", &mSamples, 1, 1024, "%d per pixel", ImGuiSliderFlags_Logarithmic);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("light samples per pixel of the ray-traced reference (compare and bench use %d)",
                                                ReferenceOptions{}.samples);
  if (mJob.running()) {
    ImGui::ProgressBar(mJob.progress(), ImVec2(-ImGui::GetFontSize() * 5.0f, 0.0f));
    ImGui::SameLine();
    if (ImGui::Button("Cancel")) {
      mJob.cancel();
      mStatus.set("heatmap cancelled", false);
    }
  } else if (ImGui::Button("Error heatmap (H)")) {
    request();
  }
  if (mResult) {
    const VisibilityMetrics& m = mResult->metrics;
    ImGui::Text("RMSE %.4f  leak %.2f%%  over-dark %.2f%%", m.rmse, m.leakPct, m.overDarkPct);
    ImGui::Text("penumbra RMSE %.4f  (%zu px, %d spp)", m.penumbraRmse, m.pixels, mResult->samplesPerPixel);
    if (mResult->version != mSession.version()) ImGui::TextColored(kErrorColor, "stale: the view changed since");
  }
}

}  // namespace penumbra::viewer
