#include "techniques/filters/ExpWarpFilter.h"

#include "frame/FrameContext.h"

namespace penumbra {

void ExpWarpFilter::renderShadowMaps(FrameContext& frame) { mMaps.render(frame, mMapLabel, warp(frame)); }

void ExpWarpFilter::prefilter(FrameContext& frame) {
  (void)frame;
  mMaps.buildMips();
}

std::vector<DebugImage> ExpWarpFilter::debugImages() const {
  return {{std::string(kShadowMapImage), &mMaps.depth(), kShadowMapMeaning},
          {std::string(kMomentsImage), &mMaps.moments(), mMomentsMeaning}};
}

void ExpWarpFilter::dispatchVisibility(FrameContext& frame, std::string_view filterFile, const ShaderDefines& defines) const {
  mMaps.bindForFiltering();
  frame.dispatchScreen(frame.visibilityProgram(filterFile, defines));
}

}  // namespace penumbra
