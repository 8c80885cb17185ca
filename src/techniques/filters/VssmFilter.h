#pragma once
// vssm: variance soft shadow maps — O(1) blocker search and filtering from a summed-area table
// of (z, z²) (or vsm's mip chain), penumbra by similar triangles as PCSS (docs/vssm.md). The maps,
// the table or the mips and their binding are the moment family's (MomentFilter.h).
#include "techniques/PenumbraDebugImages.h"
#include "techniques/TightSearch.h"
#include "techniques/filters/MomentFilter.h"

namespace penumbra {

class VssmFilter final : public MomentFilter {
public:
  VssmFilter();
  std::string_view id() const override { return "vssm"; }
  std::string_view description() const override {
    return "variance soft shadows: O(1) blocker search + Chebyshev filter from a (z, z^2) SAT or mip chain";
  }
  /// The table or the mips, then the tight search's min-depth pyramid.
  void prefilter(FrameContext& frame) override;
  void computeVisibility(FrameContext& frame) override;
  /// The depth map or moments, then "blocker-depth" and "penumbra-width-m" (PenumbraDebugImages.h).
  std::vector<DebugImage> debugImages() const override;

private:
  MomentMaps::Moments moments(const FrameContext& frame) const override;
  PenumbraDebugImages mPenumbraDebug;
  TightSearch mTightSearch;
};

}  // namespace penumbra
