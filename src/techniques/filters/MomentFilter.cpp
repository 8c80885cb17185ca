#include "techniques/filters/MomentFilter.h"

#include "frame/FrameContext.h"

#include <string>

namespace penumbra {

void MomentFilter::renderShadowMaps(FrameContext& frame) {
  const MomentMaps::Moments m = moments(frame);
  mMaps.render(frame, std::string(id()) + (m.source == MomentMaps::Source::Sat ? " depth" : " moments"), m);
}

void MomentFilter::prefilter(FrameContext& frame) { mMaps.prefilter(frame); }

std::vector<DebugImage> MomentFilter::debugImages() const { return mMaps.debugImages(mMomentsMeaning); }

void MomentFilter::dispatchVisibility(FrameContext& frame, std::string_view filterFile, const ShaderDefines& defines) const {
  mMaps.bind();
  frame.dispatchScreen(frame.visibilityProgram(filterFile, defines));
}

}  // namespace penumbra
