#include "techniques/filters/MsmSoftFilter.h"

#include "frame/FrameContext.h"
#include "techniques/filters/MomentParams.h"
#include "techniques/filters/SoftRegionParams.h"
#include "techniques/filters/msm_soft.shared.h"

namespace penumbra {
namespace {

constexpr ParamDesc kParams[] = {
    momentBiasParam("msm-soft.bias"),
    momentDepthBiasParam("msm-soft.depthBias"),
    softMinRadiusParam("msm-soft.minRadiusTexels"),
    softMaxRadiusParam("msm-soft.maxRadiusTexels"),
    tightSearchParam("msm-soft.tightSearch"),
};

constexpr int kMoments = 4;

}  // namespace

MsmSoftFilter::MsmSoftFilter() : MomentFilter(kParams, {}) {}

MomentMaps::Moments MsmSoftFilter::moments(const FrameContext& frame) const {
  (void)frame;
  return {.count = kMoments, .source = MomentMaps::Source::Sat};
}

void MsmSoftFilter::prefilter(FrameContext& frame) {
  MomentFilter::prefilter(frame);
  mTightSearch.build(frame, frame.paramInt("msm-soft.tightSearch") != 0, maps().linearDepth());
}

void MsmSoftFilter::computeVisibility(FrameContext& frame) {
  gpu::MsmSoftUniforms u{};
  u.params = glm::vec4(frame.param("msm-soft.bias"), frame.param("msm-soft.depthBias"), frame.param("msm-soft.minRadiusTexels"),
                       frame.param("msm-soft.maxRadiusTexels"));
  frame.setFilterBlock(u);
  ShaderDefines defines;
  mTightSearch.bind(frame.paramInt("msm-soft.tightSearch") != 0, defines);
  dispatchVisibility(frame, "techniques/filters/msm_soft.glsl", defines);
}

}  // namespace penumbra
