// Texel-density statistics and heatmap; the per-pixel values come from a GPU pass.
#include "comparison/TexelDensity.h"

#include "shared/DensityRamp.h"

#include <penumbra/Error.h>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace penumbra {
namespace {

constexpr uint8_t kUnmeasuredGrey = 40;

// The q-quantile (q in [0,1]) by nearest rank; `values` is reordered.
double quantile(std::vector<float>& values, double q) {
  if (values.empty()) return 0.0;
  const size_t k = std::min(values.size() - 1, static_cast<size_t>(std::floor(q * static_cast<double>(values.size() - 1) + 0.5)));
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(k), values.end());
  return values[k];
}

uint8_t toByte(float v) { return static_cast<uint8_t>(std::clamp(std::lround(v * 255.0f), 0L, 255L)); }

}  // namespace

std::vector<float> computeTexelDensity(Renderer& renderer) {
  return renderer.computeScreenScalar("passes/texel_density.comp.glsl");
}

TexelDensityStats texelDensityStats(std::span<const float> pixelsPerTexel, const GBufferData& gbuffer,
                                    const glm::vec3& cameraPosition, float nearM) {
  PN_CHECK(pixelsPerTexel.size() == gbuffer.position.size(),
           fmt::format("texel density: {} values for a G-buffer of {} pixels", pixelsPerTexel.size(), gbuffer.position.size()));
  std::vector<float> all, near;
  size_t under = 0;
  for (size_t i = 0; i < pixelsPerTexel.size(); ++i) {
    const float d = pixelsPerTexel[i];
    if (!(d > 0.0f) || !std::isfinite(d)) continue;
    all.push_back(d);
    if (d > kUndersampledPixelsPerTexel) ++under;
    if (glm::length(glm::vec3(gbuffer.position[i]) - cameraPosition) <= nearM) near.push_back(d);
  }
  TexelDensityStats s;
  s.pixels = all.size();
  s.nearPixels = near.size();
  if (all.empty()) return s;
  s.undersampledPct = 100.0 * static_cast<double>(under) / static_cast<double>(all.size());
  s.median = quantile(all, 0.5);
  s.p95 = quantile(all, 0.95);
  s.nearMedian = quantile(near, 0.5);
  return s;
}

ColorImage texelDensityHeatmap(std::span<const float> pixelsPerTexel, int width, int height) {
  PN_CHECK(width > 0 && height > 0 && pixelsPerTexel.size() == static_cast<size_t>(width) * static_cast<size_t>(height),
           fmt::format("texel density heatmap: {} values for {}x{}", pixelsPerTexel.size(), width, height));
  ColorImage img;
  img.width = width;
  img.height = height;
  img.rgba.resize(pixelsPerTexel.size() * 4);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const float d = pixelsPerTexel[static_cast<size_t>(y) * static_cast<size_t>(width) + static_cast<size_t>(x)];
      uint8_t* out = &img.rgba[(static_cast<size_t>(height - 1 - y) * static_cast<size_t>(width) + static_cast<size_t>(x)) * 4];
      if (d > 0.0f && std::isfinite(d)) {
        const glm::vec4 c = gpu::densityRampColor(std::log2(d));
        out[0] = toByte(c.x);
        out[1] = toByte(c.y);
        out[2] = toByte(c.z);
      } else {
        out[0] = out[1] = out[2] = kUnmeasuredGrey;
      }
      out[3] = 255;
    }
  return img;
}

}  // namespace penumbra
