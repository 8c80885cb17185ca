#include "techniques/filters/VssmFilter.h"

#include "frame/FrameContext.h"
#include "techniques/filters/BleedReduction.h"
#include "techniques/filters/SoftRegionParams.h"
#include "techniques/filters/vssm.shared.h"

namespace penumbra {
namespace {

constexpr std::string_view kSourceNames[] = {"sat", "mip"};
static_assert(PN_VSSM_SOURCE_SAT == 0 && PN_VSSM_SOURCE_MIP == 1, "kSourceNames follows the PN_VSSM_SOURCE_* order");

constexpr ParamDesc kParams[] = {
    {"vssm.source", "Source", "where region means of (z, z^2) come from: sat (summed-area table, exact boxes) or mip (mip chain, trilinear approximation)", "",
     PN_VSSM_SOURCE_SAT, 0, 1, 1, kSourceNames, "PN_VSSM_SOURCE"},
    {"vssm.minVariance", "Min variance", "floor of the variance, in texels² (depth spreads measured in the world size of a texel): keeps receivers from shadowing themselves", "texels²",
     3.0f, 0.0f, 256.0f, 0.0f},
    bleedReductionParam("vssm.bleedReduction"),
    softMinRadiusParam("vssm.minRadiusTexels"),
    softMaxRadiusParam("vssm.maxRadiusTexels"),
    tightSearchParam("vssm.tightSearch"),
    mipSplitParam("vssm.mipSplit"),
    mipBoxAnisotropyParam("vssm.anisotropy"),
};

}  // namespace

VssmFilter::VssmFilter() : MomentFilter(kParams, "moments (z, z²) of the linear light depth z") {}

MomentMaps::Moments VssmFilter::moments(const FrameContext& frame) const {
  const bool fromSat = frame.paramInt("vssm.source") == PN_VSSM_SOURCE_SAT;
  return {.count = 2, .source = fromSat ? MomentMaps::Source::Sat : MomentMaps::Source::Mips};
}

void VssmFilter::prefilter(FrameContext& frame) {
  MomentFilter::prefilter(frame);
  // From the depth map, or from the moments' z (channel r) with source=mip.
  mTightSearch.build(frame, frame.paramInt("vssm.tightSearch") != 0, maps().linearDepth());
}

void VssmFilter::computeVisibility(FrameContext& frame) {
  gpu::VssmUniforms u{};
  u.params = glm::vec4(frame.param("vssm.minVariance"), frame.param("vssm.bleedReduction"), frame.param("vssm.minRadiusTexels"),
                       frame.param("vssm.maxRadiusTexels"));
  u.mode = glm::ivec4(frame.paramInt("vssm.anisotropy"), frame.paramInt("vssm.mipSplit"), 0, 0);
  frame.setFilterBlock(u);
  mPenumbraDebug.bind(frame);
  ShaderDefines defines;
  mTightSearch.bind(frame.paramInt("vssm.tightSearch") != 0, defines);
  dispatchVisibility(frame, "techniques/filters/vssm.glsl", defines);
}

std::vector<DebugImage> VssmFilter::debugImages() const {
  std::vector<DebugImage> out = MomentFilter::debugImages();
  for (const DebugImage& d : mPenumbraDebug.debugImages()) out.push_back(d);
  return out;
}

}  // namespace penumbra
