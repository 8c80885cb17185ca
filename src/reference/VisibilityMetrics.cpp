// Visibility error statistics over the pixels that face the light (docs/design.md, "Reference and
// metrics"). Sums run in double: a 4K image has 8M pixels, beyond float's exact integers.
#include <penumbra/Error.h>
#include <penumbra/Metrics.h>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace penumbra {

namespace {

// V_ref at pixel i's footprint (compareVisibility): the extremes of V_ref over the pixel and its 8
// neighbours inside the mask and the image; a list of samples (width 0): the pixel alone.
struct Footprint {
  float lowest, highest;
};

Footprint footprint(std::span<const float> vRef, std::span<const uint8_t> mask, size_t i, int width) {
  Footprint f{vRef[i], vRef[i]};
  if (width <= 0) return f;
  const auto w = static_cast<ptrdiff_t>(width), h = static_cast<ptrdiff_t>(vRef.size()) / w;
  const ptrdiff_t x = static_cast<ptrdiff_t>(i) % w, y = static_cast<ptrdiff_t>(i) / w;
  for (ptrdiff_t ny = std::max<ptrdiff_t>(y - 1, 0); ny <= std::min(y + 1, h - 1); ++ny)
    for (ptrdiff_t nx = std::max<ptrdiff_t>(x - 1, 0); nx <= std::min(x + 1, w - 1); ++nx) {
      const auto j = static_cast<size_t>(ny * w + nx);
      if (!mask.empty() && mask[j] == 0) continue;
      f.lowest = std::min(f.lowest, vRef[j]);
      f.highest = std::max(f.highest, vRef[j]);
    }
  return f;
}

}  // namespace

VisibilityMetrics compareVisibility(std::span<const float> v, std::span<const float> vRef,
                                    std::span<const uint8_t> mask, int width) {
  PN_CHECK(v.size() == vRef.size(),
           fmt::format("metrics: V has {} pixels but V_ref has {}", v.size(), vRef.size()));
  PN_CHECK(mask.empty() || mask.size() == v.size(),
           fmt::format("metrics: the mask has {} pixels but V has {}", mask.size(), v.size()));
  PN_CHECK(width >= 0 && (width == 0 || v.size() % static_cast<size_t>(width) == 0),
           fmt::format("metrics: {} pixels are not rows of width {}", v.size(), width));
  VisibilityMetrics m;
  double sumSquares = 0.0, sumAbs = 0.0, sum = 0.0, penumbraSquares = 0.0;
  for (size_t i = 0; i < v.size(); ++i) {
    if (!mask.empty() && mask[i] == 0) continue;
    const double delta = static_cast<double>(v[i]) - static_cast<double>(vRef[i]);
    ++m.pixels;
    sum += delta;
    sumAbs += std::abs(delta);
    sumSquares += delta * delta;
    const Footprint f = footprint(vRef, mask, i, width);
    if (delta > kLeakThresholdV) {
      ++m.leakPixels;
      if (f.highest <= kPenumbraLowV) ++m.umbraLeakPixels;
    }
    if (-delta > kLeakThresholdV) ++m.overDarkPixels;
    if (f.lowest >= kPenumbraHighV) {
      ++m.fullyLitPixels;
      if (-delta > kLeakThresholdV) ++m.acnePixels;
    }
    if (vRef[i] > kPenumbraLowV && vRef[i] < kPenumbraHighV) {
      ++m.penumbraPixels;
      penumbraSquares += delta * delta;
    }
  }
  if (m.pixels == 0) return m;
  const auto n = static_cast<double>(m.pixels);
  m.rmse = std::sqrt(sumSquares / n);
  m.mae = sumAbs / n;
  m.bias = sum / n;
  m.leakPct = 100.0 * static_cast<double>(m.leakPixels) / n;
  m.overDarkPct = 100.0 * static_cast<double>(m.overDarkPixels) / n;
  m.umbraLeakPct = 100.0 * static_cast<double>(m.umbraLeakPixels) / n;
  if (m.fullyLitPixels > 0) m.acnePct = 100.0 * static_cast<double>(m.acnePixels) / static_cast<double>(m.fullyLitPixels);
  if (m.penumbraPixels > 0) m.penumbraRmse = std::sqrt(penumbraSquares / static_cast<double>(m.penumbraPixels));
  return m;
}

ColourMetrics compareColourVisibility(std::span<const glm::vec3> v, std::span<const glm::vec3> vRef,
                                      std::span<const uint8_t> mask) {
  PN_CHECK(v.size() == vRef.size(), fmt::format("metrics: V has {} pixels but the RGB V_ref has {}", v.size(), vRef.size()));
  PN_CHECK(mask.empty() || mask.size() == v.size(),
           fmt::format("metrics: the mask has {} pixels but V has {}", mask.size(), v.size()));
  ColourMetrics m;
  std::array<double, 3> squares{};
  for (size_t i = 0; i < v.size(); ++i) {
    if (!mask.empty() && mask[i] == 0) continue;
    ++m.pixels;
    for (int c = 0; c < 3; ++c) {
      const double delta = static_cast<double>(v[i][c]) - static_cast<double>(vRef[i][c]);
      squares[static_cast<size_t>(c)] += delta * delta;
    }
  }
  if (m.pixels == 0) return m;
  const auto n = static_cast<double>(m.pixels);
  for (size_t c = 0; c < 3; ++c) m.channelRmse[c] = std::sqrt(squares[c] / n);
  m.rmse = std::sqrt((squares[0] + squares[1] + squares[2]) / (3.0 * n));
  return m;
}

std::vector<float> lightWeights(const GBufferData& gbuffer, const Light& light, std::span<const uint8_t> litMask) {
  const size_t n = static_cast<size_t>(gbuffer.width) * static_cast<size_t>(gbuffer.height);
  if (gbuffer.position.size() != n || gbuffer.normal.size() != n || litMask.size() != n)
    throw Error(fmt::format("lightWeights: {} mask pixels for a {}x{} G-buffer", litMask.size(), gbuffer.width, gbuffer.height));
  // Rec. 709 luminance of the light's colour (linear RGB).
  const float luminance = light.intensity * glm::dot(light.color, glm::vec3(0.2126f, 0.7152f, 0.0722f));
  std::vector<float> w(n, 0.0f);
  for (size_t i = 0; i < n; ++i) {
    if (!litMask[i] || !gbuffer.covered(i)) continue;
    const glm::vec3 p(gbuffer.position[i]), normal(gbuffer.normal[i]);
    glm::vec3 toLight = -glm::normalize(light.direction);
    float attenuation = 1.0f;
    if (isPositional(light)) {
      const glm::vec3 d = light.position - p;
      const float d2 = std::max(glm::dot(d, d), 1e-8f);
      toLight = d / std::sqrt(d2);
      attenuation = lightFalloff(light, p) / d2;
    }
    w[i] = luminance * std::max(glm::dot(normal, toLight), 0.0f) * attenuation;
  }
  return w;
}

CombinedVisibility combineLights(std::span<const LightVisibility> lights) {
  if (lights.empty()) throw Error("combineLights: no light");
  const size_t n = lights[0].v.size();
  for (const LightVisibility& l : lights)
    if (l.v.size() != n || l.vRef.size() != n || l.vRefCosWeighted.size() != n || l.litMask.size() != n ||
        (lights.size() > 1 && l.weight.size() != n))
      throw Error(fmt::format("combineLights: per-light arrays of different sizes ({} pixels expected)", n));
  CombinedVisibility c;
  if (lights.size() == 1) {
    c.v.assign(lights[0].v.begin(), lights[0].v.end());
    c.vRef.assign(lights[0].vRef.begin(), lights[0].vRef.end());
    c.vRefCosWeighted.assign(lights[0].vRefCosWeighted.begin(), lights[0].vRefCosWeighted.end());
    c.mask.assign(lights[0].litMask.begin(), lights[0].litMask.end());
    return c;
  }
  c.v.assign(n, 1.0f);
  c.vRef.assign(n, 1.0f);
  c.vRefCosWeighted.assign(n, 1.0f);
  c.mask.assign(n, 0);
  for (size_t i = 0; i < n; ++i) {
    double sw = 0.0, sv = 0.0, sr = 0.0, sc = 0.0;
    int lit = 0;
    for (const LightVisibility& l : lights) {
      if (!l.litMask[i]) continue;
      ++lit;
      sw += l.weight[i];
      sv += l.weight[i] * l.v[i];
      sr += l.weight[i] * l.vRef[i];
      sc += l.weight[i] * l.vRefCosWeighted[i];
    }
    if (lit == 0) continue;
    c.mask[i] = 1;
    if (sw <= 0.0) {  // lit at grazing angles only: the lights whose masks are set count equally
      sv = sr = sc = 0.0;
      for (const LightVisibility& l : lights)
        if (l.litMask[i]) sv += l.v[i], sr += l.vRef[i], sc += l.vRefCosWeighted[i];
      sw = lit;
    }
    c.v[i] = static_cast<float>(sv / sw);
    c.vRef[i] = static_cast<float>(sr / sw);
    c.vRefCosWeighted[i] = static_cast<float>(sc / sw);
  }
  return c;
}

}  // namespace penumbra
