#pragma once
// msm: moment shadow maps — four depth moments (32-bit float or 16-bit quantised), a mip chain,
// the Hamburger 4MSM lower bound (docs/msm.md). With msm.translucent on, translucent casters are
// left out of those moments and summed into two more maps, weighted by their absorbance
// (docs/translucent.md): V = V(opaque) × exp(−absorbance × the reconstructed share in front).
// The opaque casters' maps, their mips and binding are the moment family's (MomentFilter.h).
#include "frame/ShadowMaps.h"
#include "techniques/filters/MomentFilter.h"

namespace penumbra {

class MsmFilter final : public MomentFilter {
public:
  MsmFilter();
  std::string_view id() const override { return "msm"; }
  std::string_view description() const override {
    return "moment shadow maps: 4 moments (float32 or 16-bit quantised) in a mip chain, Hamburger 4MSM bound";
  }
  /// The opaque casters' moments, then (msm.translucent) the translucent casters' two maps.
  void renderShadowMaps(FrameContext& frame) override;
  void prefilter(FrameContext& frame) override;
  void computeVisibility(FrameContext& frame) override;
  /// The shadow map and the moments, then the translucent casters' maps while they are drawn.
  std::vector<DebugImage> debugImages() const override;
  std::string_view translucentCasters() const override;
  bool shadowsThroughTranslucent(const Parameterized& values) const override;

private:
  MomentMaps::Moments moments(const FrameContext& frame) const override;
  /// msm.translucent: per view, the absorbance-weighted moments of the translucent casters'
  /// depths and their per-channel absorbance (the two summed maps); empty while it is off.
  ShadowMapArray mTranslucentMoments, mAbsorbance;
};

}  // namespace penumbra
