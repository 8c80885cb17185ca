#pragma once
// msm-soft: moment soft shadows — a summed-area table of four depth moments, moment-based blocker
// search and Hamburger filtering over a PCSS-sized box, both O(1) (docs/msm-soft.md). The depth,
// the table and its binding are the moment family's (MomentFilter.h).
#include "techniques/TightSearch.h"
#include "techniques/filters/MomentFilter.h"

namespace penumbra {

class MsmSoftFilter final : public MomentFilter {
public:
  MsmSoftFilter();
  std::string_view id() const override { return "msm-soft"; }
  std::string_view description() const override {
    return "moment soft shadows: 4-moment SAT, moment-based blocker search, Hamburger bound over the penumbra";
  }
  /// The table, then the tight search's min-depth pyramid.
  void prefilter(FrameContext& frame) override;
  void computeVisibility(FrameContext& frame) override;

private:
  MomentMaps::Moments moments(const FrameContext& frame) const override;
  TightSearch mTightSearch;
};

}  // namespace penumbra
