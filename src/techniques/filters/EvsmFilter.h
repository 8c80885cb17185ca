#pragma once
// evsm: exponential variance shadow maps — the moments of a positive (and negative) exponential
// warp of depth in 32- or 16-bit floats, a mip chain, trilinear + anisotropic filtering over the
// pixel footprint, Chebyshev's bound on each warp (docs/evsm.md).
#include "techniques/filters/ExpWarpMaps.h"

#include "frame/Filter.h"

namespace penumbra {

class EvsmFilter final : public Filter {
public:
  EvsmFilter();
  std::string_view id() const override { return "evsm"; }
  std::string_view description() const override {
    return "exponential variance shadow maps: moments of exp(c+ (2z - 1)) (and -exp(-c- (2z - 1))), mip chain, "
           "trilinear + anisotropic, Chebyshev bound per warp";
  }
  void renderShadowMaps(FrameContext& frame) override;
  void prefilter(FrameContext& frame) override;
  void computeVisibility(FrameContext& frame) override;
  std::vector<DebugImage> debugImages() const override;

private:
  ExpWarpMaps mMaps;
};

}  // namespace penumbra
