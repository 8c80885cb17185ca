#include "techniques/filters/VsmFilter.h"

#include "frame/FrameContext.h"
#include "techniques/filters/BleedReduction.h"
#include "techniques/filters/FootprintParams.h"
#include "techniques/filters/vsm.shared.h"

namespace penumbra {
namespace {

constexpr ParamDesc kParams[] = {
    {"vsm.minVariance", "Min variance",
     "floor of the variance, in texels² (depth spreads measured in the world size of a texel): hides float cancellation and the acne of flat receivers", "texels²",
     4.0f, 0.0f, 64.0f, 0.0f},
    bleedReductionParam("vsm.bleedReduction"),
    footprintWidthParam("vsm.filterTexels"),
    footprintParam("vsm.footprint"),
    footprintAnisotropyParam("vsm.anisotropy"),
};

}  // namespace

VsmFilter::VsmFilter() : MomentFilter(kParams, "moments (z, z²) of the linear light depth z") {}

MomentMaps::Moments VsmFilter::moments(const FrameContext& frame) const {
  (void)frame;
  return {.count = 2, .source = MomentMaps::Source::Mips};
}

void VsmFilter::computeVisibility(FrameContext& frame) {
  gpu::VsmUniforms u{};
  u.params = glm::vec4(frame.param("vsm.minVariance"), frame.param("vsm.bleedReduction"), frame.param("vsm.filterTexels"), 0.0f);
  u.mode = glm::ivec4(frame.paramInt("vsm.anisotropy"), 0, 0, 0);
  frame.setFilterBlock(u);
  dispatchVisibility(frame, "techniques/filters/vsm.glsl");
}

}  // namespace penumbra
