#pragma once
// msm-soft: moment soft shadows — a summed-area table of four depth moments, moment-based blocker
// search and Hamburger filtering over a PCSS-sized box, both O(1) (docs/msm-soft.md).
#include "frame/SatBuilder.h"
#include "frame/ShadowMaps.h"
#include "techniques/TightSearch.h"

#include "frame/Filter.h"

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
  ShadowMapArray mMaps;
  SatBuilder mSat;
  TightSearch mTightSearch;
};

}  // namespace penumbra
