#pragma once
// The renderer's last frame against a reference traced on the same G-buffer: the metrics and the
// three images `penumbra compare` and `penumbra bench` show (technique | reference | heatmap).
#include <penumbra/Metrics.h>
#include <penumbra/Reference.h>
#include <penumbra/Renderer.h>

namespace penumbra::report {

/// The heatmaps the lab writes (compare's heatmap.png and sheet, the bench's grid) show each
/// error over a 3 × 3 spot (HeatmapOptions::dilatePx): a one-pixel leak on a thin fence slat
/// stays visible at the default size. The metrics and the EXR files are per pixel.
inline constexpr HeatmapOptions kLabHeatmap{.fullScaleDeltaV = HeatmapOptions{}.fullScaleDeltaV, .dilatePx = 1};

struct FrameComparison {
  std::vector<float> visibility;  ///< the frame's V (row 0 = bottom)
  VisibilityMetrics metrics;      ///< V against V_ref over the reference's litMask
  /// Filled when images are asked for: the frame's colour, the same frame lit with V_ref, and
  /// the signed error heatmap over the technique's image (Metrics.h errorHeatmap, kLabHeatmap).
  ColorImage technique, reference, heatmap;
};

/// Compares the last frame of `renderer` with `ref` (traced on that frame's G-buffer). Throws
/// penumbra::Error when the sizes differ.
FrameComparison compareFrame(Renderer& renderer, const ReferenceResult& ref, bool images);

}  // namespace penumbra::report
