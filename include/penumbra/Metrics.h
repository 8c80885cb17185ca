#pragma once
// The ruler: how far a technique's visibility V is from the reference V_ref, and images that
// show where. Pure C++ (no GL). Per-pixel inputs are width × height arrays in the G-buffer's
// row order (row 0 = bottom); output images are row 0 = top, ready for writePng.
#include <penumbra/Image.h>
#include <penumbra/Scene.h>

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace penumbra {

/// V − V_ref above this counts as a leak (light where the truth has shadow), V_ref − V above it
/// as over-darkening. 0.1 is a visible step on a lit surface yet well above the reference's
/// own noise at 256 samples (σ ≤ 0.03 in a penumbra).
inline constexpr float kLeakThresholdV = 0.1f;
/// Penumbra pixels: V_ref strictly inside (kPenumbraLowV, kPenumbraHighV). The margins keep
/// the reference's sampling noise on fully lit/umbra pixels out of the penumbra statistic.
inline constexpr float kPenumbraLowV = 0.02f;
inline constexpr float kPenumbraHighV = 0.98f;

/// Errors of V against V_ref over the mask's pixels. Percentages are of the mask's pixels.
struct VisibilityMetrics {
  double rmse = 0.0;          ///< sqrt(mean (V − V_ref)²)
  double mae = 0.0;           ///< mean |V − V_ref|
  double bias = 0.0;          ///< mean (V − V_ref): > 0 = too bright on average
  double leakPct = 0.0;       ///< % of pixels with V − V_ref > kLeakThresholdV
  double overDarkPct = 0.0;   ///< % of pixels with V_ref − V > kLeakThresholdV
  /// % of pixels that leak inside the reference's umbra (V_ref <= kPenumbraLowV at the pixel's
  /// footprint, below): light where no part of the light is visible. Separates light bleeding
  /// (variance methods' overlapping occluders) and detached shadows from an edge that is merely
  /// too sharp or too soft, which leaks at V_ref > 0.
  double umbraLeakPct = 0.0;
  double penumbraRmse = 0.0;  ///< RMSE over penumbra pixels only (0 when there are none)
  /// Acne: % of the fully lit pixels (V_ref >= kPenumbraHighV at the pixel's footprint, below)
  /// that V darkens by more than kLeakThresholdV — self-shadowing, the over-darkening a bias
  /// exists to remove. Unlike the other percentages, of the fully lit pixels, not of the mask (0
  /// when there are none).
  double acnePct = 0.0;
  size_t pixels = 0;          ///< pixels in the mask
  size_t leakPixels = 0, overDarkPixels = 0, penumbraPixels = 0, umbraLeakPixels = 0;
  size_t fullyLitPixels = 0, acnePixels = 0;
};

/// Compares V with V_ref where mask ≠ 0 (ReferenceResult::litMask). An empty mask means every
/// pixel. Throws penumbra::Error when the sizes differ (or width does not divide them). All zeros
/// when the mask selects nothing. Also measures the split approximation:
/// compareVisibility(ref.visibility, ref.visibilityCosWeighted, ref.litMask).rmse is its error in
/// units of V.
///
/// With the image's width, acne and umbra leaks are judged at each pixel's footprint: V_ref is
/// the light's visibility at the pixel's centre, so a point light's hard edge that crosses a
/// pixel leaves it V_ref = 1 or 0 although the edge runs through it, and any anti-aliased V
/// (a filter's kernel, a texel's blend) rightly lands between. A pixel therefore counts as fully
/// lit (umbra) only where V_ref is so at it and at its 8 neighbours inside the mask: the band
/// excluded is one pixel, the reference's own resolution, however wide a technique's kernel is.
/// Acne away from the reference's shadow edges, and a detached shadow's gap wider than a pixel,
/// count in full; the edge's pixels keep counting in rmse, leak_pct and overdark_pct. width 0: the
/// arrays are samples, not an image, and each is its own footprint.
VisibilityMetrics compareVisibility(std::span<const float> v, std::span<const float> vRef,
                                    std::span<const uint8_t> mask, int width = 0);

/// V against an RGB V_ref (ReferenceResult::visibilityRgb, a scene with translucent casters)
/// over the mask's pixels: the RMSE over all three channels and each channel's own. A one-channel
/// technique's V enters as grey (V, V, V).
struct ColourMetrics {
  double rmse = 0.0;                       ///< sqrt(mean over pixels and channels of (V_c − V_ref,c)²)
  std::array<double, 3> channelRmse{};     ///< red, green, blue
  size_t pixels = 0;
};

/// Throws penumbra::Error when the sizes differ; all zeros when the mask selects nothing.
ColourMetrics compareColourVisibility(std::span<const glm::vec3> v, std::span<const glm::vec3> vRef,
                                      std::span<const uint8_t> mask);

/// The colour of the error: on the mask's pixels mid grey (128) where V = V_ref, each channel
/// brighter where V lets through more of that colour than V_ref and darker where less, fully at
/// ±fullScaleDeltaV (a black shadow under a red glass: dark in red, less so in green and blue,
/// so it reads cyan, the light it is missing). Other pixels dark grey. Inputs row 0 = bottom,
/// output row 0 = top. Throws on size mismatch.
ColorImage colourErrorImage(std::span<const glm::vec3> v, std::span<const glm::vec3> vRef, std::span<const uint8_t> mask,
                            int width, int height, float fullScaleDeltaV = 0.5f);

/// Several lights' V as one number per pixel, for metrics over a frame lit by many lights:
/// V = Σ wᵢ·Vᵢ / Σ wᵢ, each light weighted by its unshadowed contribution at the pixel
/// (lightWeights), and the same for V_ref. A pixel counts (mask) where any light's litMask is
/// set; where every weight there is 0 (lit at grazing angles only), the lights whose masks are
/// set count equally. With one light the result is that light's V, V_ref and mask unchanged.
struct CombinedVisibility {
  std::vector<float> v, vRef, vRefCosWeighted;
  std::vector<uint8_t> mask;
};

/// One light's share in a combination: its V, the reference's, the pixels it lights and its weights.
struct LightVisibility {
  std::span<const float> v, vRef, vRefCosWeighted;
  std::span<const uint8_t> litMask;
  std::span<const float> weight;  ///< lightWeights() of the light (empty with one light)
};

/// The luminance of light's unshadowed irradiance at each covered G-buffer pixel: intensity ×
/// luminance(colour) × max(N·L, 0) × lightFalloff × 1/d² for spot and point lights (the lit
/// pass's terms, without albedo); 0 where litMask is 0.
std::vector<float> lightWeights(const GBufferData& gbuffer, const Light& light, std::span<const uint8_t> litMask);

/// Combines the lights (at least one, all the same size). Throws penumbra::Error on mismatched sizes.
CombinedVisibility combineLights(std::span<const LightVisibility> lights);

struct HeatmapOptions {
  /// |ΔV| at which the error colour is fully opaque over the grey; smaller errors blend in
  /// linearly, so colour intensity ∝ |ΔV|. Range (0, 1], default 0.5.
  float fullScaleDeltaV = 0.5f;
  /// Each pixel shows the largest error (by |ΔV|, with its sign) within this many pixels of it,
  /// among the measured ones: a one-pixel error becomes a (2r+1)² spot that reads at a glance.
  /// 0 = every pixel its own error. Range [0, kMaxHeatmapDilatePx].
  int dilatePx = 0;
};
inline constexpr int kMaxHeatmapDilatePx = 8;

/// Signed error heatmap: a dimmed grey version of `base` (sRGB RGBA8, row 0 = top, the same
/// size; e.g. the technique's colour image), or of V_ref when `base` is null, with leaks
/// (V > V_ref) tinted kLeakColor and over-darkening (V < V_ref) tinted kOverDarkColor, by
/// |ΔV| / fullScaleDeltaV (after dilation). Pixels outside a non-empty mask stay grey unless an
/// error is dilated over them. Throws on size mismatch.
ColorImage errorHeatmap(std::span<const float> v, std::span<const float> vRef, std::span<const uint8_t> mask,
                        int width, int height, const ColorImage* base = nullptr,
                        const HeatmapOptions& options = {});

/// Leaks in warm red, over-darkening in blue: distinguishable for the common colour-vision
/// deficiencies and from any grey.
inline constexpr uint8_t kLeakColor[3] = {230, 40, 20};
inline constexpr uint8_t kOverDarkColor[3] = {20, 110, 255};

/// V as grey (linear: 0 → 0, 1 → 255, no sRGB curve: the picture shows the number, not light);
/// values are clamped to [0, 1]. Input row 0 = bottom, output row 0 = top.
ColorImage visibilityImage(std::span<const float> v, int width, int height);

}  // namespace penumbra
