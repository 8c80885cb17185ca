#include "techniques/projections/SampleDistributionProjection.h"

#include "techniques/projections/CascadedProjection.h"
#include "techniques/projections/LightSpace.h"
#include "shared/Bindings.h"

#include <penumbra/Error.h>

#include <algorithm>
#include <cmath>

namespace penumbra {
namespace {

constexpr std::string_view kOnOff[] = {"off", "on"};

constexpr ParamDesc kParams[] = {
    {"sdsm.cascades", "Cascades", "number of cascades (one shadow map each, same resolution)", "maps", 4.0f, 1.0f,
     static_cast<float>(PN_MAX_CASCADES), 1.0f},
    {"sdsm.stabilize", "Stabilise", "sun: depth range in quarter octaves, cascade sides in eighth octaves, centres snapped to whole texels, so edges do not crawl", "",
     1.0f, 0.0f, 1.0f, 1.0f, kOnOff},
    {"sdsm.blendBandM", "Blend band", "camera depth (m) before each split where two cascades are mixed; at most half the shortest cascade", "m",
     2.0f, 0.0f, 100.0f, 0.0f},
    {"sdsm.marginTexels", "Margin", "border added around each cascade, in texels", "texels", 2.0f, 0.0f, 64.0f, 1.0f},
};

constexpr float kSideStepsPerOctave = 8.0f;  // stableCascadeSide: at most 9 % more side than needed
constexpr float kSpotMinNearM = 0.01f;       // as csm: a spot cascade's nearest near plane
// A slice thinner than this share of its depth is widened: the pixels' range can be one depth.
constexpr float kMinRangeFraction = 1e-3f;

}  // namespace

float stableCascadeSide(float neededM) {
  return std::exp2(std::ceil(std::log2(std::max(neededM, 1e-6f)) * kSideStepsPerOctave) / kSideStepsPerOctave);
}

CascadeSlices logarithmicSlices(float nearM, float farM, int count, float blendBandM) {
  // λ = 1: equal depth ratios per cascade, which is what keeps a pixel's footprint and a texel's
  // in proportion over the depth range (the perspective aliasing of a view grows with depth).
  const std::vector<float> z = practicalSplits(nearM, farM, count, 1.0f);
  float shortest = farM - nearM;
  for (int i = 0; i + 1 < count; ++i) shortest = std::min(shortest, z[static_cast<size_t>(i) + 1] - z[static_cast<size_t>(i)]);
  CascadeSlices s;
  s.blendBandM = count > 1 ? std::min(blendBandM, 0.5f * shortest) : 0.0f;
  for (int i = 0; i < count; ++i) {
    s.nearM.push_back(i == 0 ? nearM : z[static_cast<size_t>(i)] - s.blendBandM);
    s.farM.push_back(z[static_cast<size_t>(i) + 1]);
  }
  return s;
}

SampleDistributionProjection::SampleDistributionProjection() : Projection(kParams) {}

LightFrusta SampleDistributionProjection::cascades(const Camera& camera, float aspect, const Light& light,
                                                   const SceneExtent& scene, int mapSize, glm::vec2 depthRange,
                                                   PixelBounds* pixels) const {
  const int count = paramInt("sdsm.cascades");
  const bool sun = light.type == LightType::Directional;
  const bool stabilize = paramInt("sdsm.stabilize") != 0 && sun;
  float nearM = std::max(depthRange.x, camera.nearM);
  float farM = std::max(depthRange.y, nearM * (1.0f + kMinRangeFraction));
  if (stabilize) {  // quarter octaves: the splits stay put while the range moves a little
    nearM = stableNearDistance(nearM, camera.nearM);
    farM = stableFarDistance(farM);
  }
  const CascadeSlices slices = logarithmicSlices(nearM, farM, count, param("sdsm.blendBandM"));
  LightFrusta f;
  f.blendBandM = slices.blendBandM;
  const float marginTexels = param("sdsm.marginTexels");
  const float marginFraction = marginTexels / static_cast<float>(mapSize);
  std::vector<Aabb> boxes;
  const glm::mat4 lightFromWorld = sunViewMatrix(scene, light);
  if (sun && pixels) boxes = pixels->sliceBounds(lightFromWorld, slices.nearM, slices.farM);
  for (int i = 0; i < count; ++i) {
    const size_t k = static_cast<size_t>(i);
    const float a = slices.nearM[k], b = slices.farM[k];
    ShadowView v;
    if (!boxes.empty() && !boxes[k].empty()) {
      // The pixels' own rectangle in the sun's fixed basis: the only texels they will read (a
      // caster that shadows a pixel lies on its ray, at the same place in the light's plane).
      const glm::vec2 lo(boxes[k].lo), hi(boxes[k].hi);
      // One texel more than the rectangle on each side before the margin: snapping moves the
      // centre by up to half a texel.
      const float fill = 1.0f - 2.0f * (marginTexels + 1.0f) / static_cast<float>(mapSize);
      glm::vec2 side = glm::max(hi - lo, glm::vec2(1e-3f)) / std::max(fill, 0.5f);
      if (stabilize) side = {stableCascadeSide(side.x), stableCascadeSide(side.y)};
      // Unstabilised, the sides follow the pixels exactly and the snap is to a grid that changes
      // with them: no help, no harm.
      v = snappedSunView(scene, lightFromWorld, 0.5f * (lo + hi), 0.5f * side, mapSize);
    } else {
      // No pixel in this slice (or a spot light): csm's fit to the slice's geometry.
      v = fittedCascade(camera, aspect, light, scene, std::max(a, kSpotMinNearM), b, marginFraction);
    }
    v.splitFarM = b;
    f.views.push_back(v);
  }
  return f;
}

LightFrusta SampleDistributionProjection::computeFrusta(const Camera& camera, float aspect, const Light& light,
                                                        const SceneExtent& scene, int mapSize) const {
  const ViewRegion region = wholeViewRegion(camera, aspect, light, scene);
  glm::vec2 range(camera.nearM, region.farM);
  if (!region.body.empty()) range = cameraDepthRange(region.body, camera);
  return cascades(camera, aspect, light, scene, mapSize, range, nullptr);
}

LightFrusta SampleDistributionProjection::computeFrustaFromPixels(const Camera& camera, float aspect, const Light& light,
                                                                  const SceneExtent& scene, int mapSize,
                                                                  PixelBounds& pixels) const {
  const glm::vec2 range = pixels.depthRange();
  if (!(range.x <= range.y)) return computeFrusta(camera, aspect, light, scene, mapSize);  // no pixel faces the light
  return cascades(camera, aspect, light, scene, mapSize, range, &pixels);
}

}  // namespace penumbra
