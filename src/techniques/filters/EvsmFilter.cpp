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

}  // namespace

EvsmFilter::EvsmFilter()
    : ExpWarpFilter(kParams, "evsm moments", "warped moments (p, p², n, n²) of the linear light depth") {}

ExpWarpMaps::Warp EvsmFilter::warp(const FrameContext& frame) const {
  return chebyshevWarp(frame.paramInt("evsm.components") == 0 ? 2 : 4,
                       static_cast<ExpWarpStorage>(frame.paramInt("evsm.storage")), frame.param("evsm.positiveExponent"),
                       frame.param("evsm.negativeExponent"));
}

void EvsmFilter::computeVisibility(FrameContext& frame) {
  gpu::EvsmUniforms u{};
  u.warp = chebyshevWarpUniform(warp(frame));
  u.params = glm::vec4(frame.param("evsm.minVariance"), frame.param("evsm.bleedReduction"), frame.param("evsm.filterTexels"), 0.0f);
  u.mode = glm::ivec4(frame.paramInt("evsm.anisotropy"), frame.paramInt("evsm.footprint"), 0, 0);
  frame.setFilterBlock(u);
  dispatchVisibility(frame, "techniques/filters/evsm.glsl");
}

}  // namespace penumbra
