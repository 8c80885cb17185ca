#pragma once
// evsm-soft: exponential variance soft shadows — vssm's O(1) blocker search and filter on evsm's
// four warped moments, read from their mip chain; penumbra by similar triangles as PCSS
// (docs/evsm-soft.md).
#include "techniques/PenumbraDebugImages.h"
#include "techniques/TightSearch.h"
#include "techniques/filters/ExpWarpMaps.h"

#include "frame/Filter.h"

namespace penumbra {

class EvsmSoftFilter final : public Filter {
public:
  EvsmSoftFilter();
  std::string_view id() const override { return "evsm-soft"; }
  std::string_view description() const override {
    return "exponential variance soft shadows: O(1) blocker search (negative warp) + evsm bound over the penumbra, "
           "from the 4-component mip chain";
  }
  void renderShadowMaps(FrameContext& frame) override;
  void prefilter(FrameContext& frame) override;
  void computeVisibility(FrameContext& frame) override;
  /// The moments, then "blocker-depth" and "penumbra-width-m" (PenumbraDebugImages.h).
  std::vector<DebugImage> debugImages() const override;

private:
  ExpWarpMaps mMaps;
  PenumbraDebugImages mPenumbraDebug;
  TightSearch mTightSearch;
};

}  // namespace penumbra
