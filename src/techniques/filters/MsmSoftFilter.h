#pragma once
// msm-soft: moment soft shadows — a summed-area table of four depth moments, moment-based blocker
// search and Hamburger filtering over a PCSS-sized box, both O(1) (docs/msm-soft.md). The maps
// and the table are the moment family's (MomentMaps.h).
#include "frame/Filter.h"
#include "techniques/TightSearch.h"
#include "techniques/filters/MomentMaps.h"

namespace penumbra {

class MsmSoftFilter final : public Filter {
public:
  MsmSoftFilter();
  std::string_view id() const override { return "msm-soft"; }
  std::string_view description() const override {
    return "moment soft shadows: 4-moment SAT, moment-based blocker search, Hamburger bound over the penumbra";
  }
  void renderShadowMaps(FrameContext& frame) override;
  void prefilter(FrameContext& frame) override;
  void computeVisibility(FrameContext& frame) override;
  std::vector<DebugImage> debugImages() const override;

private:
  MomentMaps mMaps;
  TightSearch mTightSearch;
};

}  // namespace penumbra
