#include "techniques/filters/PcssFilter.h"

#include "frame/FrameContext.h"
#include "techniques/filters/pcss.shared.h"
#include "shared/Bindings.h"

#include <algorithm>

namespace penumbra {
namespace {

// 64 = the Poisson disk's size (common/sampling.glsl, kPoissonDiskSize).
constexpr float kMaxTaps = 64.0f;

constexpr ParamDesc kParams[] = {
    {"pcss.blockerSamples", "Blocker samples", "taps of the blocker search (box pattern: the largest odd grid with at most this many)", "taps",
     16.0f, 1.0f, kMaxTaps, 1.0f, {}, "PN_PCSS_BLOCKER_SAMPLES"},
    {"pcss.filterSamples", "Filter samples", "taps of the percentage-closer filter (box pattern: the largest odd grid with at most this many)", "taps",
     32.0f, 1.0f, kMaxTaps, 1.0f, {}, "PN_PCSS_FILTER_SAMPLES"},
    {"pcss.pattern", "Pattern", "sampling pattern of both steps: box grid or Poisson disk rotated per pixel", "",
     PN_KERNEL_POISSON, 0, 1, 1, kKernelNames, "PN_PCSS_PATTERN"},
    {"pcss.minRadiusTexels", "Min radius", "smallest filter radius in texels: anti-aliases the hard edge at contact", "texels",
     1.0f, 0.0f, 8.0f, 0.0f},
    {"pcss.maxRadiusTexels", "Max radius", "largest search and filter radius in texels: bounds the footprint (wider penumbrae are cut to it)", "texels",
     96.0f, 1.0f, 512.0f, 0.0f},
    {"pcss.hardwareCompare", "Hardware compare", "on: each filter tap is the hardware's bilinear 2x2 comparison (sampler2DShadow)", "",
     0.0f, 0.0f, 1.0f, 1.0f, kOffOn},
    {"pcss.constantBias", "Constant bias", "depth offset in linear light-depth units (fraction of the map's depth range), added to the plane bias", "depth range",
     0.0f, 0.0f, 0.05f, 0.0f},
    tightSearchParam("pcss.tightSearch"),
    {"pcss.slopeBias", "Slope bias", "slope-scaled offset in texels of the receiver plane's depth slope, added to the plane bias", "texels",
     0.0f, 0.0f, 16.0f, 0.0f},
    {"pcss.planeBiasTexels", "Plane bias", "every tap compares the receiver's own plane at its texel's centre, moved back along the receiver's normal by this many texels of world size plus the tap texel's distance from the receiver in texels", "texels",
     1.0f, 0.0f, 16.0f, 0.0f},
};

}  // namespace

PcssFilter::PcssFilter() : Filter(kParams) {}

void PcssFilter::renderShadowMaps(FrameContext& frame) {
  frame.ensureMaps(mMaps, "pcss shadow map");
  frame.renderViews(mMaps, frame.shadowProgram());
}

void PcssFilter::prefilter(FrameContext& frame) {
  mTightSearch.build(frame, frame.paramInt("pcss.tightSearch") != 0, mMaps.depth());
}

void PcssFilter::computeVisibility(FrameContext& frame) {
  gpu::PcssUniforms u{};
  const float mapRadius = maxKernelRadiusTexels(frame.mapSize());
  u.params = glm::vec4(frame.param("pcss.constantBias"), frame.param("pcss.slopeBias"), std::min(frame.param("pcss.minRadiusTexels"), mapRadius),
                       std::min(frame.param("pcss.maxRadiusTexels"), mapRadius));
  u.bias = glm::vec4(frame.param("pcss.planeBiasTexels"), 0.0f, 0.0f, 0.0f);
  frame.setFilterBlock(u);
  const bool hardware = frame.paramInt("pcss.hardwareCompare") != 0 && !frame.paged();  // a paged map is read texel by texel
  ShaderDefines defines;
  if (hardware) defines.set("PN_HARDWARE_COMPARE");
  mTightSearch.bind(frame.paramInt("pcss.tightSearch") != 0, defines);
  // One map at two units: raw depths for the blocker search, comparisons for the filter.
  mMaps.depth().bindUnit(PN_TEX_FILTER0);
  mMaps.depth().bindUnit(PN_TEX_FILTER1);
  if (hardware) mCompare.bind(PN_TEX_FILTER1);
  mPenumbraDebug.bind(frame);
  frame.dispatchScreen(frame.visibilityProgram("techniques/filters/pcss.glsl", defines));
  if (hardware) ComparisonSampler::unbind(PN_TEX_FILTER1);
}

std::vector<DebugImage> PcssFilter::debugImages() const {
  std::vector<DebugImage> out = {{std::string(kShadowMapImage), &mMaps.depth(), kShadowMapMeaning}};
  for (const DebugImage& d : mPenumbraDebug.debugImages()) out.push_back(d);
  return out;
}

}  // namespace penumbra
