// Visibility error statistics over the pixels that face the light (docs/design.md, "Reference and
// metrics"). Sums run in double: a 4K image has 8M pixels, beyond float's exact integers.
#include <penumbra/Error.h>
#include <penumbra/Metrics.h>

#include <fmt/format.h>

#include <cmath>

namespace penumbra {

VisibilityMetrics compareVisibility(std::span<const float> v, std::span<const float> vRef,
                                    std::span<const uint8_t> mask) {
  PN_CHECK(v.size() == vRef.size(),
           fmt::format("metrics: V has {} pixels but V_ref has {}", v.size(), vRef.size()));
  PN_CHECK(mask.empty() || mask.size() == v.size(),
           fmt::format("metrics: the mask has {} pixels but V has {}", mask.size(), v.size()));
  VisibilityMetrics m;
  double sumSquares = 0.0, sumAbs = 0.0, sum = 0.0, penumbraSquares = 0.0;
  for (size_t i = 0; i < v.size(); ++i) {
    if (!mask.empty() && mask[i] == 0) continue;
    const double delta = static_cast<double>(v[i]) - static_cast<double>(vRef[i]);
    ++m.pixels;
    sum += delta;
    sumAbs += std::abs(delta);
    sumSquares += delta * delta;
    if (delta > kLeakThresholdV) {
      ++m.leakPixels;
      if (vRef[i] <= kPenumbraLowV) ++m.umbraLeakPixels;
    }
    if (-delta > kLeakThresholdV) ++m.overDarkPixels;
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
  if (m.penumbraPixels > 0) m.penumbraRmse = std::sqrt(penumbraSquares / static_cast<double>(m.penumbraPixels));
  return m;
}

}  // namespace penumbra
