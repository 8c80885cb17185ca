#include "comparison/FrameComparison.h"

#include <penumbra/Error.h>

#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <cstdio>

namespace penumbra::report {

std::vector<ReferenceResult> traceLights(const ReferenceTracer& tracer, const GBufferData& gbuffer,
                                         std::span<const Light> lights, const ReferenceOptions& options) {
  std::vector<ReferenceResult> refs;
  for (const Light& l : lights) refs.push_back(l.castsShadow ? tracer.trace(gbuffer, l, options) : ReferenceResult{});
  // A cache folder that cannot be written costs the cache, not the run: said once a process
  // (every later reference has the same folder).
  static std::atomic<bool> warned{false};
  for (const ReferenceResult& r : refs)
    if (!r.cacheWarning.empty() && !warned.exchange(true))
      std::fprintf(stderr, "penumbra: warning: %s; references are traced but not kept (set PENUMBRA_CACHE to a writable "
                           "folder, or --no-cache)\n", r.cacheWarning.c_str());
  return refs;
}

std::vector<glm::vec3> colourVisibility(const LightComparison& light) {
  if (!light.visibilityRgb.empty()) return light.visibilityRgb;
  std::vector<glm::vec3> grey(light.visibility.size());
  std::transform(light.visibility.begin(), light.visibility.end(), grey.begin(), [](float v) { return glm::vec3(v); });
  return grey;
}

FrameComparison compareFrame(Renderer& renderer, const GBufferData& gbuffer, std::span<const ReferenceResult> refs,
                             bool images) {
  const std::vector<Light>& lights = renderer.scene().lights;
  if (refs.size() != lights.size() || renderer.lightCount() != lights.size())
    throw Error(fmt::format("compareFrame: {} references for {} lights", refs.size(), lights.size()));
  FrameComparison c;
  std::vector<std::vector<float>> weights(lights.size());
  std::vector<LightVisibility> shadowed;
  std::vector<size_t> shadowedIndex;
  for (size_t i = 0; i < lights.size(); ++i) {
    LightComparison l;
    l.index = i;
    l.type = lights[i].type;
    l.castsShadow = lights[i].castsShadow;
    l.visibility = renderer.readVisibility(i);
    l.visibilityRgb = renderer.readVisibilityRgb(i);
    l.map = renderer.shadows().lightReports().at(i);
    if (l.castsShadow) l.metrics = compareVisibility(l.visibility, refs[i].visibility, refs[i].litMask, gbuffer.width);
    if (l.castsShadow && !refs[i].visibilityRgb.empty())
      l.colour = compareColourVisibility(colourVisibility(l), refs[i].visibilityRgb, refs[i].litMask);
    c.lights.push_back(std::move(l));
  }
  for (size_t i = 0; i < lights.size(); ++i)
    if (c.lights[i].castsShadow) shadowedIndex.push_back(i);
  if (shadowedIndex.empty()) throw usageError("compare: no light of the scene casts a shadow");
  for (size_t i : shadowedIndex) {
    if (shadowedIndex.size() > 1) weights[i] = lightWeights(gbuffer, lights[i], refs[i].litMask);
    shadowed.push_back({c.lights[i].visibility, refs[i].visibility, refs[i].visibilityCosWeighted, refs[i].litMask, weights[i]});
  }
  if (shadowedIndex.size() == 1) c.colour = c.lights[shadowedIndex.front()].colour;
  c.combined = combineLights(shadowed);
  c.metrics = compareVisibility(c.combined.v, c.combined.vRef, c.combined.mask, gbuffer.width);
  if (images) {
    c.technique = renderer.readColor();
    std::vector<std::vector<float>> refVisibility;
    std::vector<std::vector<glm::vec3>> refRgb;  // a reference in colour (translucent casters) shades in colour
    for (size_t i = 0; i < lights.size(); ++i) {
      refVisibility.push_back(c.lights[i].castsShadow ? refs[i].visibility : c.lights[i].visibility);
      refRgb.push_back(c.lights[i].castsShadow ? refs[i].visibilityRgb : std::vector<glm::vec3>{});
    }
    c.reference = renderer.shadeWithVisibility(refVisibility, refRgb);
    c.heatmap = errorHeatmap(c.combined.v, c.combined.vRef, c.combined.mask, gbuffer.width, gbuffer.height, &c.technique,
                             kLabHeatmap);
  }
  return c;
}

}  // namespace penumbra::report
