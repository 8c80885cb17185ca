#pragma once
// evsm-soft: exponential variance soft shadows — vssm's O(1) blocker search and filter on evsm's
// four warped moments, read from their mip chain; penumbra by similar triangles as PCSS
// (docs/evsm-soft.md). The maps, their mips and binding are the exp-warp family's
// (ExpWarpFilter.h).
#include "techniques/PenumbraDebugImages.h"
#include "techniques/TightSearch.h"
#include "techniques/filters/ExpWarpFilter.h"

namespace penumbra {

class EvsmSoftFilter final : public ExpWarpFilter {
public:
  EvsmSoftFilter();
  std::string_view id() const override { return "evsm-soft"; }
  std::string_view description() const override {
    return "exponential variance soft shadows: O(1) blocker search (negative warp) + evsm bound over the penumbra, "
           "from the 4-component mip chain";
  }
  /// The mip chain, then the tight search's min-depth pyramid.
  void prefilter(FrameContext& frame) override;
  void computeVisibility(FrameContext& frame) override;
  /// The moments, then "blocker-depth" and "penumbra-width-m" (PenumbraDebugImages.h).
  std::vector<DebugImage> debugImages() const override;

private:
  ExpWarpMaps::Warp warp(const FrameContext& frame) const override;
  PenumbraDebugImages mPenumbraDebug;
  TightSearch mTightSearch;
};

}  // namespace penumbra
