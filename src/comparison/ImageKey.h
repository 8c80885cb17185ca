#pragma once
// Keys written on the lab's pictures (compare's heatmap.png, approximation.png, texel-density.png
// and sheet.png): what the picture shows, a colour bar with its tick labels in their unit, and
// what grey means, drawn in a band under the picture so that the file reads on its own.
#include "text/ImageText.h"

#include <penumbra/Image.h>

#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <utility>
#include <vector>

namespace penumbra::report {

using text::Rgb;
using text::TextPainter;
using text::fillRect;
using text::strokeRect;

/// A colour scale and the words around it.
struct ColorKey {
  std::string title;                  ///< what the picture shows, over the bar
  std::function<Rgb(float)> color;    ///< the colour at t ∈ [0, 1] along the bar
  std::vector<std::pair<float, std::string>> ticks;  ///< t and its label (with the unit)
  std::vector<std::string> notes;     ///< lines under the bar: what grey means, the scale's origin
};

/// The narrowest band a key is drawn in (pixels): a picture narrower than this gets a wider
/// canvas, the picture centred on it.
inline constexpr int kMinKeyWidthPx = 420;

/// Pixels of height the key takes drawn `width` pixels wide (lines wrap at " · ").
int keyHeight(const ColorKey& key, int width);
/// Draws the key with its top-left corner at (x, y), `width` pixels wide.
void drawKey(ColorImage& image, int x, int y, int width, const ColorKey& key);
/// The picture with its key in a band under it (at least kMinKeyWidthPx wide).
ColorImage withKey(const ColorImage& picture, const ColorKey& key);

/// `parts` joined with " · " into lines no wider than `width` at the painter's size.
std::vector<std::string> wrapParts(const std::vector<std::string>& parts, const TextPainter& painter, int width);
/// "a · b · c" → {"a", "b", "c"}.
std::vector<std::string> splitParts(const std::string& line);

/// The signed error heatmap's key (errorHeatmap): ΔV from −fullScale (blue, too dark) to
/// +fullScale (red, too bright), `what` ΔV is, and what the grey under it is.
ColorKey heatmapKey(float fullScaleDeltaV, const std::string& what, const std::string& grey);

/// The heatmap scales an image may adapt to: full colour at one of these |ΔV|.
inline constexpr float kHeatmapScales[] = {0.01f, 0.02f, 0.05f, 0.1f, 0.2f, 0.5f, 1.0f};
/// Errors smaller than this do not count toward the scale (below one step of an 8-bit grey).
inline constexpr float kVisibleDeltaV = 1.0f / 255.0f;
/// The percentile of the visible errors the scale covers: a few pixels' outliers do not wash
/// out the rest.
inline constexpr double kHeatmapScalePercentile = 0.99;
/// A full scale that fits the errors: the smallest kHeatmapScales value at or above the
/// kHeatmapScalePercentile quantile of |V − V_ref| over the measured pixels whose error is
/// visible (kVisibleDeltaV); the smallest scale when none is. So a soft shadow off by 0.01 shows
/// in colour where a fixed ±0.5 would leave it grey.
float adaptiveHeatmapScale(std::span<const float> v, std::span<const float> vRef, std::span<const uint8_t> mask);

/// texelDensityHeatmap's key: screen pixels per shadow-map texel on a log scale.
ColorKey texelDensityKey();

}  // namespace penumbra::report
