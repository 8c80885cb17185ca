#include "techniques/filters/VsmFilter.h"

#include "frame/FrameContext.h"
#include "frame/MipBuilder.h"
#include "techniques/filters/BleedReduction.h"
#include "techniques/filters/FootprintParams.h"
#include "techniques/filters/vsm.shared.h"
#include "shared/Bindings.h"

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

VsmFilter::VsmFilter() : Filter(kParams) {}

void VsmFilter::renderShadowMaps(FrameContext& frame) {
  constexpr int kFullMipChain = 0;
  mMaps.ensure("vsm moments", frame.mapSize(), frame.viewCount(), GL_RG32F, kFullMipChain);
  const ShaderDefines defines = ShaderDefines().set("PN_MOMENT_COUNT", 2).set("PN_MOMENT_SLOPE_VARIANCE");
  // Cleared to the moments of the far plane (z = 1): no occluder where nothing was drawn.
  frame.renderViews(mMaps, frame.shadowProgram("passes/moments.frag.glsl", defines), glm::vec4(1.0f));
}

void VsmFilter::prefilter(FrameContext& frame) {
  (void)frame;
  MipBuilder::build(mMaps.color());
}

void VsmFilter::computeVisibility(FrameContext& frame) {
  gpu::VsmUniforms u{};
  u.params = glm::vec4(frame.param("vsm.minVariance"), frame.param("vsm.bleedReduction"), frame.param("vsm.filterTexels"), 0.0f);
  u.mode = glm::ivec4(frame.paramInt("vsm.anisotropy"), 0, 0, 0);
  frame.setFilterBlock(u);
  MipBuilder::setTrilinear(mMaps.color());
  mMaps.color().bindUnit(PN_TEX_FILTER0);
  frame.dispatchScreen(frame.visibilityProgram("techniques/filters/vsm.glsl"));
}

std::vector<DebugImage> VsmFilter::debugImages() const { return {{std::string(kShadowMapImage), &mMaps.depth(), kShadowMapMeaning},
          {std::string(kMomentsImage), &mMaps.color(), "moments (z, z²) of the linear light depth z"}};
}

}  // namespace penumbra
