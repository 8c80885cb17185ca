#include "techniques/filters/EvsmFilter.h"

#include "frame/FrameContext.h"
#include "techniques/filters/BleedReduction.h"
#include "techniques/filters/ExpWarpParams.h"
#include "techniques/filters/FootprintParams.h"
#include "techniques/filters/evsm.shared.h"

namespace penumbra {
namespace {

constexpr std::string_view kComponentNames[] = {"2", "4"};

constexpr ParamDesc kParams[] = {
    {"evsm.components", "Components",
     "2: the positive warp (p, p²); 4: also the negative warp (n, n²), and V is the smaller of the two bounds "
     "(twice the memory, far less light where receivers are not planar)", "",
     1.0f, 0.0f, 1.0f, 1.0f, kComponentNames},
    expWarpStorageParam("evsm.storage"),
    positiveExponentParam("evsm.positiveExponent"),
    negativeExponentParam("evsm.negativeExponent"),
    {"evsm.minVariance", "Min variance",
     "floor of the depth variance in texels² (as vsm.minVariance), taken through each warp's slope: hides the "
     "acne of receivers that are not quite planar", "texels²",
     4.0f, 0.0f, 64.0f, 0.0f},
    bleedReductionParam("evsm.bleedReduction"),
    footprintWidthParam("evsm.filterTexels"),
    footprintParam("evsm.footprint"),
    footprintAnisotropyParam("evsm.anisotropy"),
};

ExpWarpMaps::Warp evsmWarp(const FrameContext& f) {
  ExpWarpMaps::Warp w;
  w.components = f.paramInt("evsm.components") == 0 ? 2 : 4;
  w.storage = static_cast<ExpWarpStorage>(f.paramInt("evsm.storage"));
  w.positive = clampWarpExponent(f.param("evsm.positiveExponent"), w.storage);
  w.negative = w.components == 4 ? clampWarpExponent(f.param("evsm.negativeExponent"), w.storage) : 0.0f;
  return w;
}

}  // namespace

EvsmFilter::EvsmFilter() : Filter(kParams) {}

void EvsmFilter::renderShadowMaps(FrameContext& frame) { mMaps.render(frame, "evsm moments", evsmWarp(frame)); }

void EvsmFilter::prefilter(FrameContext& frame) {
  (void)frame;
  mMaps.buildMips();
}

void EvsmFilter::computeVisibility(FrameContext& frame) {
  const ExpWarpMaps::Warp w = evsmWarp(frame);
  gpu::EvsmUniforms u{};
  u.warp = glm::vec4(w.positive, w.negative, minRelativeWarpVariance(w.storage), static_cast<float>(w.components));
  u.params = glm::vec4(frame.param("evsm.minVariance"), frame.param("evsm.bleedReduction"), frame.param("evsm.filterTexels"), 0.0f);
  u.mode = glm::ivec4(frame.paramInt("evsm.anisotropy"), frame.paramInt("evsm.footprint"), 0, 0);
  frame.setFilterBlock(u);
  mMaps.bindForFiltering();
  frame.dispatchScreen(frame.visibilityProgram("techniques/filters/evsm.glsl"));
}

std::vector<DebugImage> EvsmFilter::debugImages() const { return {{std::string(kShadowMapImage), &mMaps.depth(), kShadowMapMeaning},
          {std::string(kMomentsImage), &mMaps.moments(), "warped moments (p, p², n, n²) of the linear light depth"}};
}

}  // namespace penumbra
