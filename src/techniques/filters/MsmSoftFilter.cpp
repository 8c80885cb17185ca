#include "techniques/filters/MsmSoftFilter.h"

#include "frame/FrameContext.h"
#include "techniques/filters/MomentBias.h"
#include "techniques/filters/SoftRegionParams.h"
#include "techniques/filters/msm_soft.shared.h"
#include "shared/Bindings.h"

namespace penumbra {
namespace {

constexpr ParamDesc kParams[] = {
    momentBiasParam("msm-soft.bias"),
    {"msm-soft.depthBias", "Depth bias", "the receiver depth is moved toward the light by this much, in linear depth units (fraction of the map's depth range)", "depth range",
     0.0f, 0.0f, 0.05f, 0.0f},
    softMinRadiusParam("msm-soft.minRadiusTexels"),
    softMaxRadiusParam("msm-soft.maxRadiusTexels"),
    tightSearchParam("msm-soft.tightSearch"),
};

constexpr int kMoments = 4;

}  // namespace

MsmSoftFilter::MsmSoftFilter() : Filter(kParams) {}

void MsmSoftFilter::renderShadowMaps(FrameContext& frame) {
  // Linear depth only: the SAT build forms the four moments itself, in exact fixed point.
  mMaps.ensure("msm-soft depth", frame.mapSize(), frame.viewCount());
  frame.renderViews(mMaps, frame.shadowProgram());
}

void MsmSoftFilter::prefilter(FrameContext& frame) {
  mSat.build(frame.shaders(), mMaps.depth(), kMoments);
  mTightSearch.build(frame, frame.paramInt("msm-soft.tightSearch") != 0, mMaps.depth());
}

void MsmSoftFilter::computeVisibility(FrameContext& frame) {
  gpu::MsmSoftUniforms u{};
  u.params = glm::vec4(frame.param("msm-soft.bias"), frame.param("msm-soft.depthBias"), frame.param("msm-soft.minRadiusTexels"),
                       frame.param("msm-soft.maxRadiusTexels"));
  frame.setFilterBlock(u);
  mSat.bindTable();
  ShaderDefines defines;
  mTightSearch.bind(frame.paramInt("msm-soft.tightSearch") != 0, defines);
  frame.dispatchScreen(frame.visibilityProgram("techniques/filters/msm_soft.glsl", defines));
}

std::vector<DebugImage> MsmSoftFilter::debugImages() const { return {{std::string(kShadowMapImage), &mMaps.depth(), kShadowMapMeaning}};
}

}  // namespace penumbra
