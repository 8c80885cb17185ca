#include "techniques/filters/EvsmSoftFilter.h"

#include "frame/FrameContext.h"
#include "techniques/filters/BleedReduction.h"
#include "techniques/filters/ExpWarpParams.h"
#include "techniques/filters/SoftRegionParams.h"
#include "techniques/filters/evsm_soft.shared.h"

namespace penumbra {
namespace {

// Four components always: the blocker search reads the negative warp (common/exp_warp.glsl).
constexpr ParamDesc kParams[] = {
    expWarpStorageParam("evsm-soft.storage"),
    positiveExponentParam("evsm-soft.positiveExponent"),
    negativeExponentParam("evsm-soft.negativeExponent"),
    {"evsm-soft.minVariance", "Min variance",
     "floor of the depth variance in texels² (as vssm.minVariance), taken through each warp's slope: keeps receivers "
     "from shadowing themselves", "texels²",
     3.0f, 0.0f, 256.0f, 0.0f},
    bleedReductionParam("evsm-soft.bleedReduction"),
    softMinRadiusParam("evsm-soft.minRadiusTexels"),
    softMaxRadiusParam("evsm-soft.maxRadiusTexels"),
    tightSearchParam("evsm-soft.tightSearch"),
    mipSplitParam("evsm-soft.mipSplit"),
    mipBoxAnisotropyParam("evsm-soft.anisotropy"),
};

constexpr int kComponents = 4;

}  // namespace

EvsmSoftFilter::EvsmSoftFilter()
    : ExpWarpFilter(kParams, "evsm-soft moments", "warped moments (p, p², n, n²) of the linear light depth") {}

ExpWarpMaps::Warp EvsmSoftFilter::warp(const FrameContext& frame) const {
  return chebyshevWarp(kComponents, static_cast<ExpWarpStorage>(frame.paramInt("evsm-soft.storage")),
                       frame.param("evsm-soft.positiveExponent"), frame.param("evsm-soft.negativeExponent"));
}

void EvsmSoftFilter::prefilter(FrameContext& frame) {
  ExpWarpFilter::prefilter(frame);
  mTightSearch.build(frame, frame.paramInt("evsm-soft.tightSearch") != 0, maps().depth());
}

void EvsmSoftFilter::computeVisibility(FrameContext& frame) {
  gpu::EvsmSoftUniforms u{};
  u.warp = chebyshevWarpUniform(warp(frame));
  u.params = glm::vec4(frame.param("evsm-soft.minVariance"), frame.param("evsm-soft.bleedReduction"),
                       frame.param("evsm-soft.minRadiusTexels"), frame.param("evsm-soft.maxRadiusTexels"));
  u.mode = glm::ivec4(frame.paramInt("evsm-soft.anisotropy"), frame.paramInt("evsm-soft.mipSplit"), 0, 0);
  frame.setFilterBlock(u);
  mPenumbraDebug.bind(frame);
  ShaderDefines defines;
  mTightSearch.bind(frame.paramInt("evsm-soft.tightSearch") != 0, defines);
  dispatchVisibility(frame, "techniques/filters/evsm_soft.glsl", defines);
}

std::vector<DebugImage> EvsmSoftFilter::debugImages() const {
  std::vector<DebugImage> out = ExpWarpFilter::debugImages();
  for (const DebugImage& d : mPenumbraDebug.debugImages()) out.push_back(d);
  return out;
}

}  // namespace penumbra
