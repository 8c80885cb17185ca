#include "comparison/Sheet.h"

#include "comparison/ImageKey.h"
#include "text/ImageText.h"

#include <penumbra/Error.h>
#include <penumbra/Metrics.h>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace penumbra::report {
namespace {

constexpr Rgb kBackground = {246, 246, 246};
constexpr Rgb kInk = {20, 20, 20};
constexpr Rgb kZoomBox = {255, 214, 0};  // the crop's outline on the heatmap: neither leak nor over-dark
constexpr float kTitlePx = 17.0f;
constexpr float kMinTextPx = 10.0f;  // text is made smaller to fit a narrow sheet, never below this
constexpr int kMarginPx = 8;
constexpr int kZoomBoxPx = 2;      // outline thickness

void blit(ColorImage& dst, const ColorImage& src, int ox, int oy) {
  for (int y = 0; y < src.height; ++y)
    std::copy_n(src.rgba.begin() + static_cast<std::ptrdiff_t>(y) * src.width * 4, static_cast<size_t>(src.width) * 4,
                dst.rgba.begin() + (static_cast<std::ptrdiff_t>(oy + y) * dst.width + ox) * 4);
}

// The window of (w / zoom) × (h / zoom) pixels (top-down) holding the most |ΔV| over measured
// pixels, by a summed-area table; the image's centre when nothing errs.
struct Window {
  int x = 0, y = 0, w = 1, h = 1;
};
Window worstWindow(const SheetInputs& in, int width, int height) {
  Window win{0, 0, std::max(1, width / kSheetZoom), std::max(1, height / kSheetZoom)};
  std::vector<double> sat(static_cast<size_t>(width + 1) * static_cast<size_t>(height + 1), 0.0);
  auto at = [&](int x, int y) -> double& { return sat[static_cast<size_t>(y) * static_cast<size_t>(width + 1) + static_cast<size_t>(x)]; };
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const size_t i = static_cast<size_t>(height - 1 - y) * static_cast<size_t>(width) + static_cast<size_t>(x);  // to row 0 = top
      const double e = in.mask.empty() || in.mask[i] ? std::abs(in.v[i] - in.vRef[i]) : 0.0;
      at(x + 1, y + 1) = e + at(x, y + 1) + at(x + 1, y) - at(x, y);
    }
  double best = 0.0;
  win.x = (width - win.w) / 2;
  win.y = (height - win.h) / 2;
  const int step = std::max(1, std::min(win.w, win.h) / 8);
  for (int y = 0; y + win.h <= height; y += step)
    for (int x = 0; x + win.w <= width; x += step) {
      const double sum = at(x + win.w, y + win.h) - at(x, y + win.h) - at(x + win.w, y) + at(x, y);
      if (sum > best) {
        best = sum;
        win.x = x;
        win.y = y;
      }
    }
  return win;
}

ColorImage magnify(const ColorImage& src, const Window& win, int width, int height) {
  ColorImage out{width, height, std::vector<uint8_t>(static_cast<size_t>(width) * static_cast<size_t>(height) * 4, 255)};
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const int sx = std::min(src.width - 1, win.x + x * win.w / width), sy = std::min(src.height - 1, win.y + y * win.h / height);
      std::copy_n(&src.rgba[(static_cast<size_t>(sy) * static_cast<size_t>(src.width) + static_cast<size_t>(sx)) * 4], 4,
                  &out.rgba[(static_cast<size_t>(y) * static_cast<size_t>(width) + static_cast<size_t>(x)) * 4]);
    }
  return out;
}

// The largest size up to `px` at which `text` fits `width` pixels (down to kMinTextPx).
float fittingSize(std::string_view text, int width, float px) {
  for (; px > kMinTextPx; px -= 1.0f)
    if (TextPainter(px).width(text) <= width) return px;
  return kMinTextPx;
}

}  // namespace

ColorImage compareSheet(const SheetInputs& in) {
  PN_CHECK(in.technique && in.reference && in.heatmap, "compareSheet: an image is missing");
  const int w = in.technique->width, h = in.technique->height;
  for (const ColorImage* img : {in.reference, in.heatmap})
    PN_CHECK(img->width == w && img->height == h,
             fmt::format("compareSheet: images of {}x{} and {}x{}", w, h, img->width, img->height));
  PN_CHECK(in.v.size() == static_cast<size_t>(w) * static_cast<size_t>(h) && in.vRef.size() == in.v.size(),
           "compareSheet: V and V_ref must have one value per pixel");

  const Window win = worstWindow(in, w, h);
  ColorImage heatmap = *in.heatmap;
  strokeRect(heatmap, win.x - kZoomBoxPx, win.y - kZoomBoxPx, win.w + 2 * kZoomBoxPx, win.h + 2 * kZoomBoxPx, kZoomBoxPx, kZoomBox);
  const ColorImage zoom = magnify(*in.heatmap, win, w, h);
  const std::pair<const ColorImage*, std::string> tiles[] = {
      {in.technique, "technique: " + in.techniqueTitle},
      {in.reference, in.referenceTitle},
      {&heatmap, "error V − V_ref: red leaks light, blue over-darkens"},
      {&zoom, fmt::format("×{} zoom of the boxed region (largest error)", kSheetZoom)},
  };

  // The footer: the heatmap's key, then the metrics.
  ColorKey key = heatmapKey(in.heatmapFullScaleDeltaV, "heatmap colour = ΔV = V − V_ref: blue too dark, red too bright",
                            in.heatmapScaleNote);
  for (const std::string& m : in.metrics) key.notes.push_back(m);
  const int footerHeight = keyHeight(key, 2 * w);

  ColorImage sheet{2 * w, 2 * (h + kSheetTitleBandPx) + footerHeight, {}};
  sheet.rgba.assign(static_cast<size_t>(sheet.width) * static_cast<size_t>(sheet.height) * 4, 255);
  fillRect(sheet, 0, 0, sheet.width, sheet.height, kBackground);
  for (size_t k = 0; k < 4; ++k) {
    const int ox = static_cast<int>(k % 2) * w, oy = static_cast<int>(k / 2) * (h + kSheetTitleBandPx);
    const TextPainter title(fittingSize(tiles[k].second, w - 2 * kMarginPx, kTitlePx));
    const int baseline = oy + (kSheetTitleBandPx + title.ascent() - title.descent()) / 2;
    title.draw(sheet, ox + kMarginPx, baseline, tiles[k].second, kInk);
    blit(sheet, *tiles[k].first, ox, oy + kSheetTitleBandPx);
  }
  drawKey(sheet, 0, 2 * (h + kSheetTitleBandPx), 2 * w, key);
  return sheet;
}

}  // namespace penumbra::report
