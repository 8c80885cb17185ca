#include "comparison/ImageKey.h"

#include "shared/DensityRamp.h"

#include <penumbra/Metrics.h>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace penumbra::report {
namespace {

constexpr Rgb kBackground = {246, 246, 246};
constexpr Rgb kInk = {20, 20, 20};
constexpr Rgb kMutedInk = {90, 90, 90};
constexpr float kTextPx = 15.0f, kTickPx = 13.0f;
constexpr int kMarginPx = 8;
constexpr int kLineGapPx = 3;
constexpr int kBarWidthPx = 400, kBarHeightPx = 14;
constexpr int kTickLengthPx = 3;
constexpr int kBarSteps = 256;  // colour steps along the bar, at most one per pixel

int lineHeight(const TextPainter& p) { return p.ascent() + p.descent() + kLineGapPx; }

std::vector<std::string> wrapped(const std::string& text, const TextPainter& painter, int width) {
  return wrapParts(splitParts(text), painter, width);
}

Rgb toRgb(const glm::vec4& c) {
  const auto byte = [](float v) { return static_cast<uint8_t>(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f)); };
  return {byte(c.x), byte(c.y), byte(c.z)};
}

}  // namespace

std::vector<std::string> wrapParts(const std::vector<std::string>& parts, const TextPainter& painter, int width) {
  std::vector<std::string> lines;
  for (const std::string& part : parts) {
    if (!lines.empty() && painter.width(lines.back() + " · " + part) <= width) {
      lines.back() += " · " + part;
      continue;
    }
    // A part on a line of its own, broken between words where it is wider than the line.
    std::string line;
    for (size_t start = 0; start <= part.size();) {
      const size_t space = std::min(part.find(' ', start), part.size());
      const std::string word = part.substr(start, space - start);
      if (!line.empty() && painter.width(line + " " + word) > width) {
        lines.push_back(line);
        line = word;
      } else {
        line += (line.empty() ? "" : " ") + word;
      }
      start = space + 1;
    }
    lines.push_back(line);
  }
  return lines;
}

std::vector<std::string> splitParts(const std::string& line) {
  std::vector<std::string> parts;
  size_t start = 0;
  for (size_t at; (at = line.find(" · ", start)) != std::string::npos; start = at + std::string(" · ").size())
    parts.push_back(line.substr(start, at - start));
  parts.push_back(line.substr(start));
  return parts;
}

int keyHeight(const ColorKey& key, int width) {
  const TextPainter text(kTextPx), tick(kTickPx);
  const int inner = width - 2 * kMarginPx;
  int h = kMarginPx + static_cast<int>(wrapped(key.title, text, inner).size()) * lineHeight(text);
  h += kBarHeightPx + kTickLengthPx + lineHeight(tick);
  for (const std::string& n : key.notes) h += static_cast<int>(wrapped(n, tick, inner).size()) * lineHeight(tick);
  return h + kMarginPx;
}

void drawKey(ColorImage& image, int x, int y, int width, const ColorKey& key) {
  const TextPainter text(kTextPx), tick(kTickPx);
  const int inner = width - 2 * kMarginPx;
  fillRect(image, x, y, width, keyHeight(key, width), kBackground);
  int top = y + kMarginPx;
  for (const std::string& line : wrapped(key.title, text, inner)) {
    text.draw(image, x + kMarginPx, top + text.ascent(), line, kInk);
    top += lineHeight(text);
  }
  // The bar, centred ticks under it; labels kept inside the key's width.
  const int barX = x + kMarginPx, barW = std::min(kBarWidthPx, inner);
  const int steps = std::min(kBarSteps, barW);
  for (int s = 0; s < steps; ++s) {
    const int x0 = barX + s * barW / steps, x1 = barX + (s + 1) * barW / steps;
    fillRect(image, x0, top, x1 - x0, kBarHeightPx, key.color((static_cast<float>(s) + 0.5f) / static_cast<float>(steps)));
  }
  for (const auto& [t, label] : key.ticks) {
    const int tx = barX + static_cast<int>(std::lround(t * static_cast<float>(barW - 1)));
    fillRect(image, tx, top + kBarHeightPx, 1, kTickLengthPx, kInk);
    const int lx = std::clamp(tx - tick.width(label) / 2, x + kMarginPx / 2, x + width - kMarginPx / 2 - tick.width(label));
    tick.draw(image, lx, top + kBarHeightPx + kTickLengthPx + tick.ascent(), label, kMutedInk);
  }
  top += kBarHeightPx + kTickLengthPx + lineHeight(tick);
  for (const std::string& note : key.notes)
    for (const std::string& line : wrapped(note, tick, inner)) {
      tick.draw(image, x + kMarginPx, top + tick.ascent(), line, kInk);
      top += lineHeight(tick);
    }
}

ColorImage withKey(const ColorImage& picture, const ColorKey& key) {
  const int width = std::max(picture.width, kMinKeyWidthPx);
  const int band = keyHeight(key, width);
  ColorImage out{width, picture.height + band, std::vector<uint8_t>(static_cast<size_t>(width) * static_cast<size_t>(picture.height + band) * 4, 255)};
  fillRect(out, 0, 0, width, out.height, kBackground);
  const int ox = (width - picture.width) / 2;
  for (int y = 0; y < picture.height; ++y)
    std::copy_n(picture.rgba.begin() + static_cast<std::ptrdiff_t>(y) * picture.width * 4, static_cast<size_t>(picture.width) * 4,
                out.rgba.begin() + (static_cast<std::ptrdiff_t>(y) * width + ox) * 4);
  drawKey(out, 0, picture.height, width, key);
  return out;
}

ColorKey heatmapKey(float fullScale, const std::string& what, const std::string& grey) {
  ColorKey k;
  k.title = what;
  k.color = [fullScale](float t) {
    // errorHeatmap's blend over a mid grey, for ΔV from −fullScale to +fullScale.
    constexpr float kGrey = 128.0f;
    const float delta = (2.0f * t - 1.0f) * fullScale;
    const float a = std::min(1.0f, std::abs(delta) / fullScale);
    const uint8_t* tint = delta > 0.0f ? kLeakColor : kOverDarkColor;
    Rgb c{};
    for (size_t i = 0; i < 3; ++i) c[i] = static_cast<uint8_t>(std::lround(kGrey + a * (static_cast<float>(tint[i]) - kGrey)));
    return c;
  };
  const auto label = [](float v) { return v == 0.0f ? std::string("0") : fmt::format("{}{:g}", v > 0.0f ? "+" : "−", std::abs(v)); };
  for (const float f : {-1.0f, -0.5f, 0.0f, 0.5f, 1.0f}) k.ticks.emplace_back(0.5f * (f + 1.0f), label(f * fullScale));
  k.ticks.front().second += " too dark";
  k.ticks.back().second += " too bright";
  k.notes = {fmt::format("ΔV in units of the light's visibility (0 = shadowed, 1 = lit) · full colour at |ΔV| ≥ {:g} · "
                         "the colour's strength ∝ |ΔV| below it",
                         fullScale),
             grey};
  return k;
}

float adaptiveHeatmapScale(std::span<const float> v, std::span<const float> vRef, std::span<const uint8_t> mask) {
  std::vector<float> visible;
  for (size_t i = 0; i < v.size() && i < vRef.size(); ++i) {
    if (!mask.empty() && !mask[i]) continue;
    const float e = std::abs(v[i] - vRef[i]);
    if (e > kVisibleDeltaV) visible.push_back(e);
  }
  if (visible.empty()) return kHeatmapScales[0];
  const auto nth = visible.begin() + static_cast<std::ptrdiff_t>(kHeatmapScalePercentile * static_cast<double>(visible.size() - 1));
  std::nth_element(visible.begin(), nth, visible.end());
  for (const float s : kHeatmapScales)
    if (s >= *nth) return s;
  return kHeatmapScales[std::size(kHeatmapScales) - 1];
}

ColorKey texelDensityKey() {
  ColorKey k;
  k.title = "screen pixels per shadow-map texel, log scale: 1 = one texel per pixel";
  k.color = [](float t) { return toRgb(gpu::densityRampColor(PN_DENSITY_LOG2_LO + t * (PN_DENSITY_LOG2_HI - PN_DENSITY_LOG2_LO))); };
  const float span = PN_DENSITY_LOG2_HI - PN_DENSITY_LOG2_LO;
  for (float e = PN_DENSITY_LOG2_LO; e <= PN_DENSITY_LOG2_HI; e += 2.0f) {
    const std::string label = e < 0.0f ? fmt::format("1/{:g}", std::exp2(-e)) : fmt::format("{:g}", std::exp2(e));
    k.ticks.emplace_back((e - PN_DENSITY_LOG2_LO) / span, label);
  }
  k.notes = {"blue: texels smaller than pixels (map resolution spent where it is not seen) · light grey: one texel per "
             "pixel · warm to red: texels larger than pixels (blocky, aliased shadow edges)",
             "dark grey: no shadow map covers the pixel (background, or a surface facing away from the light)"};
  return k;
}

}  // namespace penumbra::report
