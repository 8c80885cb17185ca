// Images that show where V is wrong: a signed heatmap over a grey picture, and V as grey.
// Inputs are in the G-buffer's order (row 0 = bottom); images come out row 0 = top.
#include <penumbra/Error.h>
#include <penumbra/Metrics.h>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace penumbra {
namespace {

// The grey underlay spans [kGreyFloor, kGreyFloor + kGreyContrast·255]: dimmed and lifted so
// that both colours stand out on black shadows and on white lit areas alike.
constexpr float kGreyFloor = 40.0f;
constexpr float kGreyContrast = 0.6f;
// Rec. 709 luma weights, applied to the sRGB bytes: a display grey, not a light quantity.
constexpr float kLumaR = 0.2126f, kLumaG = 0.7152f, kLumaB = 0.0722f;

uint8_t toByte(float value) { return static_cast<uint8_t>(std::clamp(std::lround(value), 0L, 255L)); }

void checkSize(size_t count, int width, int height, const char* what) {
  PN_CHECK(width > 0 && height > 0 && count == static_cast<size_t>(width) * static_cast<size_t>(height),
           fmt::format("metrics: {} has {} values, not {}x{}", what, count, width, height));
}

}  // namespace

ColorImage colourErrorImage(std::span<const glm::vec3> v, std::span<const glm::vec3> vRef, std::span<const uint8_t> mask,
                            int width, int height, float fullScaleDeltaV) {
  checkSize(v.size(), width, height, "V");
  checkSize(vRef.size(), width, height, "V_ref");
  PN_CHECK(mask.empty() || mask.size() == v.size(), fmt::format("metrics: the mask has {} pixels, not {}", mask.size(), v.size()));
  PN_CHECK(fullScaleDeltaV > 0.0f && fullScaleDeltaV <= 1.0f,
           fmt::format("metrics: colour error full scale {} is outside (0, 1]", fullScaleDeltaV));
  constexpr float kMid = 128.0f, kSpan = 127.0f, kOutside = 40.0f;
  ColorImage image{width, height, std::vector<uint8_t>(4 * v.size())};
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const size_t in = static_cast<size_t>(y) * static_cast<size_t>(width) + static_cast<size_t>(x);
      const size_t out = static_cast<size_t>(height - 1 - y) * static_cast<size_t>(width) + static_cast<size_t>(x);
      const bool measured = mask.empty() || mask[in] != 0;
      for (int c = 0; c < 3; ++c)
        image.rgba[4 * out + static_cast<size_t>(c)] =
            measured ? toByte(kMid + kSpan * std::clamp((v[in][c] - vRef[in][c]) / fullScaleDeltaV, -1.0f, 1.0f))
                     : toByte(kOutside);
      image.rgba[4 * out + 3] = 255;
    }
  return image;
}

ColorImage visibilityImage(std::span<const float> v, int width, int height) {
  checkSize(v.size(), width, height, "V");
  ColorImage image{width, height, std::vector<uint8_t>(4 * v.size())};
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const size_t in = static_cast<size_t>(y) * static_cast<size_t>(width) + static_cast<size_t>(x);
      const size_t out = static_cast<size_t>(height - 1 - y) * static_cast<size_t>(width) + static_cast<size_t>(x);
      const uint8_t grey = toByte(255.0f * std::clamp(v[in], 0.0f, 1.0f));
      image.rgba[4 * out + 0] = image.rgba[4 * out + 1] = image.rgba[4 * out + 2] = grey;
      image.rgba[4 * out + 3] = 255;
    }
  }
  return image;
}

ColorImage errorHeatmap(std::span<const float> v, std::span<const float> vRef, std::span<const uint8_t> mask,
                        int width, int height, const ColorImage* base, const HeatmapOptions& options) {
  checkSize(v.size(), width, height, "V");
  checkSize(vRef.size(), width, height, "V_ref");
  PN_CHECK(mask.empty() || mask.size() == v.size(),
           fmt::format("metrics: the mask has {} pixels but V has {}", mask.size(), v.size()));
  PN_CHECK(!base || (base->width == width && base->height == height && base->rgba.size() == 4 * v.size()),
           fmt::format("metrics: the heatmap's base image is {}x{}, not {}x{}", base ? base->width : 0,
                       base ? base->height : 0, width, height));
  PN_CHECK(options.fullScaleDeltaV > 0.0f && options.fullScaleDeltaV <= 1.0f,
           fmt::format("metrics: heatmap full scale {} must be in (0, 1]", options.fullScaleDeltaV));
  PN_CHECK(options.dilatePx >= 0 && options.dilatePx <= kMaxHeatmapDilatePx,
           fmt::format("metrics: heatmap dilation {} px must be in [0, {}]", options.dilatePx, kMaxHeatmapDilatePx));

  // Per pixel the error it shows: its own ΔV (0 outside the mask), or with dilation the one of
  // largest magnitude in its neighbourhood, separably (rows, then columns).
  const auto index = [&](int x, int y) { return static_cast<size_t>(y) * static_cast<size_t>(width) + static_cast<size_t>(x); };
  std::vector<float> shown(v.size(), 0.0f);
  for (size_t i = 0; i < v.size(); ++i)
    if (mask.empty() || mask[i] != 0) shown[i] = v[i] - vRef[i];
  const int r = options.dilatePx;
  if (r > 0) {
    auto larger = [](float a, float b) { return std::abs(b) > std::abs(a) ? b : a; };
    std::vector<float> rows(shown.size(), 0.0f);
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x) {
        float e = 0.0f;
        for (int k = std::max(0, x - r); k <= std::min(width - 1, x + r); ++k) e = larger(e, shown[index(k, y)]);
        rows[index(x, y)] = e;
      }
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x) {
        float e = 0.0f;
        for (int k = std::max(0, y - r); k <= std::min(height - 1, y + r); ++k) e = larger(e, rows[index(x, k)]);
        shown[index(x, y)] = e;
      }
  }

  ColorImage image{width, height, std::vector<uint8_t>(4 * v.size())};
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const size_t in = static_cast<size_t>(y) * static_cast<size_t>(width) + static_cast<size_t>(x);
      const size_t out = static_cast<size_t>(height - 1 - y) * static_cast<size_t>(width) + static_cast<size_t>(x);
      float luma;
      if (base) {
        const uint8_t* p = &base->rgba[4 * out];
        luma = kLumaR * p[0] + kLumaG * p[1] + kLumaB * p[2];
      } else {
        luma = 255.0f * std::clamp(vRef[in], 0.0f, 1.0f);
      }
      const float grey = kGreyFloor + kGreyContrast * luma;
      const float delta = shown[in];
      const float t = std::min(1.0f, std::abs(delta) / options.fullScaleDeltaV);
      const uint8_t* tint = delta > 0.0f ? kLeakColor : kOverDarkColor;
      for (int c = 0; c < 3; ++c) image.rgba[4 * out + static_cast<size_t>(c)] = toByte(grey + t * (tint[c] - grey));
      image.rgba[4 * out + 3] = 255;
    }
  }
  return image;
}

}  // namespace penumbra
