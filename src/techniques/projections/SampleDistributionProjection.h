#pragma once
// sdsm: sample distribution shadow maps (Lauritzen, Salvi & Lefohn, "Sample distribution shadow
// maps", I3D 2011). Cascades placed from what the camera's pixels hold, measured on the GPU each
// frame (PixelBounds: a reduction over the covered pixels that face the light): the splits are
// logarithmic within the pixels' own depth range instead of the camera's near plane to the scene's
// far end, and each cascade of a sun is the tight light-space rectangle of the pixels in its slice
// instead of the bounding sphere of the whole slice, so no texel is spent on empty space or on
// depths no pixel has. Stabilised (sun only, as csm): the depth range is taken in quarter octaves,
// each cascade's sides in eighth octaves, and its centre snapped to whole texels, so small camera
// moves keep the texel grid and edges do not crawl; the map still changes when a side crosses a
// step. A spot light's cascades are csm's fitted ones over the measured depth range. Artifacts:
// cascades change size with the view (a step is a jump in resolution); N shadow passes plus the
// reduction's pass and read back.
#include "techniques/projections/LightSpace.h"

#include "frame/Projection.h"

#include <span>
#include <vector>

namespace penumbra {

/// The side (m) of a stabilised cascade: `needed` rounded up to the ladder 2^(k/8).
float stableCascadeSide(float neededM);

/// The camera-depth slices of `count` cascades with logarithmic splits over [nearM, farM] (m):
/// slice i covers [near_i, far_i]; every slice after the first starts `blendBandM` before its
/// split, where it is blended with the one before.
struct CascadeSlices {
  std::vector<float> nearM, farM;
  float blendBandM = 0.0f;
};
CascadeSlices logarithmicSlices(float nearM, float farM, int count, float blendBandM);

class SampleDistributionProjection final : public Projection {
public:
  SampleDistributionProjection();
  std::string_view id() const override { return "sdsm"; }
  std::string_view description() const override {
    return "cascades fitted to the camera's pixels: depth range and tight light-space bounds from a GPU reduction";
  }
  /// A point light shines every way: its views are the six cube faces of --projection uniform.
  std::string incompatibility(const Light& light) const override { return pointLightIncompatibility(light); }
  /// Without the pixels (CPU callers): the same cascades fitted to the scene's geometry, over the
  /// visible receivers' depth range.
  LightFrusta computeFrusta(const Camera& camera, float aspect, const Light& light, const SceneExtent& scene,
                            int mapSize) const override;
  LightFrusta computeFrustaFromPixels(const Camera& camera, float aspect, const Light& light, const SceneExtent& scene,
                                      int mapSize, PixelBounds& pixels) const override;

private:
  LightFrusta cascades(const Camera& camera, float aspect, const Light& light, const SceneExtent& scene, int mapSize,
                       glm::vec2 depthRange, PixelBounds* pixels) const;
};

}  // namespace penumbra
