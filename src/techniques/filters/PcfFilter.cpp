#include "techniques/filters/PcfFilter.h"

#include "frame/FrameContext.h"
#include "techniques/filters/pcf.shared.h"
#include "shared/Bindings.h"

#include <algorithm>
#include <cmath>

namespace penumbra {
namespace {

static_assert(PN_KERNEL_BOX == 0 && PN_KERNEL_POISSON == 1, "kKernelNames follows the PN_KERNEL_* order");

// 64 = the Poisson disk's size (common/sampling.glsl, kPoissonDiskSize).
constexpr float kMaxPoissonTaps = 64.0f;

constexpr ParamDesc kParams[] = {
    {"pcf.kernel", "Kernel", "box: a (2·ceil(r)+1)² grid of comparisons, one per texel; poisson: pcf.samples taps of a Poisson disk rotated per pixel", "",
     PN_KERNEL_POISSON, 0, 1, 1, kKernelNames, "PN_PCF_KERNEL"},
    {"pcf.radiusTexels", "Radius", "kernel radius in shadow-map texels (0 = one comparison, a hard shadow)", "texels",
     2.0f, 0.0f, 32.0f, 0.0f},
    {"pcf.samples", "Samples", "taps of the Poisson kernel (the box kernel's count follows its radius)", "taps",
     16.0f, 1.0f, kMaxPoissonTaps, 1.0f, {}, "PN_PCF_SAMPLES"},
    {"pcf.hardwareCompare", "Hardware compare", "on: each tap is the hardware's bilinear 2x2 comparison (sampler2DShadow), smoother edges for the same tap count", "",
     0.0f, 0.0f, 1.0f, 1.0f, kOffOn},
    {"pcf.constantBias", "Constant bias", "depth offset in linear light-depth units (fraction of the map's depth range), added to the plane bias", "depth range",
     0.0f, 0.0f, 0.05f, 0.0f},
    {"pcf.slopeBias", "Slope bias", "slope-scaled offset in texels of the receiver plane's depth slope, added to the plane bias", "texels",
     0.0f, 0.0f, 16.0f, 0.0f},
    {"pcf.planeBiasTexels", "Plane bias", "every tap compares the receiver's own plane at its texel's centre, moved back along the receiver's normal by this many texels of world size plus the tap texel's distance from the receiver in texels", "texels",
     1.0f, 0.0f, 16.0f, 0.0f},
};

}  // namespace

void ComparisonSampler::bind(GLuint unit) {
  if (!mSampler) {
    gl::SamplerDesc desc;
    desc.compare = true;  // bilinear, clamp to edge: the hardware's 2x2 comparison
    mSampler = gl::Sampler("hardware depth comparison", desc);
  }
  mSampler.bindUnit(unit);
}

PcfFilter::PcfFilter() : Filter(kParams) {}

void PcfFilter::renderShadowMaps(FrameContext& frame) {
  frame.ensureMaps(mMaps, "pcf shadow map");
  frame.renderViews(mMaps, frame.shadowProgram());
}

void PcfFilter::computeVisibility(FrameContext& frame) {
  gpu::PcfUniforms u{};
  const float radiusTexels = std::min(frame.param("pcf.radiusTexels"), maxKernelRadiusTexels(frame.mapSize()));
  u.params = glm::vec4(radiusTexels, frame.param("pcf.constantBias"), frame.param("pcf.slopeBias"), frame.param("pcf.planeBiasTexels"));
  frame.setFilterBlock(u);
  const bool hardware = frame.paramInt("pcf.hardwareCompare") != 0 && !frame.paged();  // a paged map is read texel by texel
  ShaderDefines defines;
  if (hardware) defines.set("PN_HARDWARE_COMPARE");
  // One view: the box kernel's size is known here (cascades hold the radius in metres, so theirs
  // vary per view and are found in the shader).
  if (frame.viewCount() == 1) defines.set("PN_PCF_BOX_HALF_SIDE", static_cast<int>(std::ceil(radiusTexels)));
  mMaps.depth().bindUnit(PN_TEX_FILTER0);
  if (hardware) mCompare.bind(PN_TEX_FILTER0);
  frame.dispatchScreen(frame.visibilityProgram("techniques/filters/pcf.glsl", defines));
  if (hardware) ComparisonSampler::unbind(PN_TEX_FILTER0);
}

std::vector<DebugImage> PcfFilter::debugImages() const { return {{std::string(kShadowMapImage), &mMaps.depth(), kShadowMapMeaning}}; }

}  // namespace penumbra
