#pragma once
// The renderer's last frame against references traced on the same G-buffer, one per light: the
// metrics (each light's and the combination's) and the three images `penumbra compare` and
// `penumbra bench` show (technique | reference | heatmap).
#include <penumbra/Metrics.h>
#include <penumbra/Reference.h>
#include <penumbra/Renderer.h>

#include <optional>
#include <span>
#include <vector>

namespace penumbra::report {

/// The heatmaps the lab writes (compare's heatmap.png and sheet, the bench's grid) show each
/// error over a 3 × 3 spot (HeatmapOptions::dilatePx): a one-pixel leak on a thin fence slat
/// stays visible at the default size. The metrics and the EXR files are per pixel.
inline constexpr HeatmapOptions kLabHeatmap{.fullScaleDeltaV = HeatmapOptions{}.fullScaleDeltaV, .dilatePx = 1};

/// One light of the frame against its reference.
struct LightComparison {
  size_t index = 0;
  LightType type = LightType::Directional;
  bool castsShadow = true;        ///< false: V = 1 by contract; left out of the combination
  std::vector<float> visibility;  ///< the light's V (row 0 = bottom; the channels' mean where V has colour)
  /// The light's V per channel where the frame's V has colour (Shadows::visibilityHasColour);
  /// empty otherwise.
  std::vector<glm::vec3> visibilityRgb;
  VisibilityMetrics metrics;      ///< V against V_ref over the light's litMask
  /// Where the light's reference has colour (translucent casters in the scene): V (RGB, or its
  /// one channel as grey) against the RGB V_ref over the same mask; empty otherwise.
  std::optional<ColourMetrics> colour;
  LightShadowReport map;          ///< what the shadow budget gave it
};

/// The light's V in colour: visibilityRgb where the frame's V has colour, else its one channel as grey.
std::vector<glm::vec3> colourVisibility(const LightComparison& light);

struct FrameComparison {
  /// The combined V, V_ref and cos-weighted V_ref (combineLights over the lights that cast
  /// shadows; with one light, that light's own arrays) and its mask.
  CombinedVisibility combined;
  VisibilityMetrics metrics;  ///< combined V against combined V_ref
  /// The colour metrics of the frame where exactly one light casts shadows and its reference has
  /// colour (that light's LightComparison::colour); empty otherwise (several lights' colours are
  /// not combined).
  std::optional<ColourMetrics> colour;
  std::vector<LightComparison> lights;
  /// Filled when images are asked for: the frame's colour, the same frame lit with every light's
  /// V_ref, and the signed error heatmap of the combination over the technique's image (kLabHeatmap).
  ColorImage technique, reference, heatmap;
};

/// Traces every light of the renderer's scene on `gbuffer` (the renderer's last G-buffer); a
/// light that casts no shadow gets no trace (an empty result). A reference that could not be
/// kept in the cache folder (ReferenceResult::cacheWarning) is said once a process on stderr.
std::vector<ReferenceResult> traceLights(const ReferenceTracer& tracer, const GBufferData& gbuffer,
                                         std::span<const Light> lights, const ReferenceOptions& options);

/// Compares the last frame of `renderer` with `refs` (traceLights on that frame's G-buffer, one
/// per light). Throws penumbra::Error when counts or sizes differ.
FrameComparison compareFrame(Renderer& renderer, const GBufferData& gbuffer, std::span<const ReferenceResult> refs,
                             bool images);

}  // namespace penumbra::report
