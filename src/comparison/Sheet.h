#pragma once
// compare's sheet.png: the technique, the reference, the error heatmap and a magnified crop of
// the heatmap where the error is largest, 2 × 2, each tile under a title; below them a colour
// legend of the heatmap and the metrics, written on the picture so that it reads on its own.
#include <penumbra/Image.h>

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace penumbra::report {

/// Height of the title band above each tile (pixels). Below the 2 × 2 tiles a footer holds the
/// legend and the metrics, as tall as their lines need at the sheet's width.
inline constexpr int kSheetTitleBandPx = 28;
/// The fourth tile shows the heatmap region with the most error at this magnification.
inline constexpr int kSheetZoom = 4;

struct SheetInputs {
  const ColorImage* technique = nullptr;  ///< the frame lit with V (row 0 = top)
  const ColorImage* reference = nullptr;  ///< the frame lit with V_ref
  const ColorImage* heatmap = nullptr;    ///< errorHeatmap of V against V_ref (dilated or not)
  /// V, V_ref and the lit mask (G-buffer order, row 0 = bottom): where the error is largest.
  std::span<const float> v, vRef;
  std::span<const uint8_t> mask;
  float heatmapFullScaleDeltaV = 0.5f;  ///< the heatmap's HeatmapOptions::fullScaleDeltaV
  std::string heatmapScaleNote;         ///< why that scale, and what the grey is (heatmapKey's last note)
  std::string techniqueTitle;  ///< "pcss · uniform on pen"
  std::string referenceTitle;  ///< "reference: Embree, 256 light samples per pixel"
  std::vector<std::string> metrics;  ///< one line each, written under the legend
};

/// The sheet: width 2·w, height 2·(h + kSheetTitleBandPx) + the footer's (the heatmap's key,
/// ImageKey.h, then the metrics, wrapped at " · ") for w × h images; titles are made smaller to
/// fit a narrow sheet. Throws penumbra::Error
/// when the images' sizes differ.
ColorImage compareSheet(const SheetInputs& in);

}  // namespace penumbra::report
