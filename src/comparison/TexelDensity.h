#pragma once
// The aliasing measure of the projections: per pixel, the number of screen pixels covered by one
// shadow-map texel (shaders/common/texel_density.glsl, an area ratio from the derivatives of the
// shadow-map coordinates), its statistics and a heatmap. Lower is better; a texel covering more
// than one pixel (value > 1) is UNDER-SAMPLED: the shadow's edge shows the texel grid there.
#include <penumbra/Renderer.h>

#include <cstddef>
#include <span>
#include <vector>

namespace penumbra {

/// "Near" pixels: surfaces within this distance (m) of the camera, where perspective aliasing is
/// worst and where a viewer looks.
inline constexpr float kTexelDensityNearM = 20.0f;
/// A texel covering more screen pixels than this is under-sampled (> 1 pixel per texel).
inline constexpr float kUndersampledPixelsPerTexel = 1.0f;

/// Statistics of screen pixels per texel over the measured pixels (covered, facing the light).
struct TexelDensityStats {
  double median = 0.0;           ///< texel_density_median
  double p95 = 0.0;              ///< texel_density_p95: 95th percentile (the worst 5% start here)
  double nearMedian = 0.0;       ///< texel_density_near_median: pixels within kTexelDensityNearM
  double undersampledPct = 0.0;  ///< undersampled_pct: % of pixels with > 1 screen pixel per texel
  size_t pixels = 0, nearPixels = 0;
};

/// Per pixel of the renderer's last frame: screen pixels per texel, in the cascade each pixel
/// uses; -1 where there is no geometry or the surface faces away from the light. Row 0 = bottom.
std::vector<float> computeTexelDensity(Renderer& renderer);

/// Statistics over the pixels with a value > 0. `gbuffer` gives each pixel's world position for
/// the near set (distance to cameraPosition ≤ nearM). All zero when nothing was measured.
/// Throws penumbra::Error when the sizes differ.
TexelDensityStats texelDensityStats(std::span<const float> pixelsPerTexel, const GBufferData& gbuffer,
                                    const glm::vec3& cameraPosition, float nearM = kTexelDensityNearM);

/// Heatmap (row 0 = top): shared/DensityRamp.h's colours of log2(pixels per texel), cool =
/// over-sampled, grey = 1:1, warm to red = under-sampled; unmeasured pixels dark grey.
ColorImage texelDensityHeatmap(std::span<const float> pixelsPerTexel, int width, int height);

}  // namespace penumbra
