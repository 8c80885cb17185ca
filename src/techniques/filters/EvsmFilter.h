#pragma once
// evsm: exponential variance shadow maps — the moments of a positive (and negative) exponential
// warp of depth in 32- or 16-bit floats, a mip chain, trilinear + anisotropic filtering over the
// pixel footprint, Chebyshev's bound on each warp (docs/evsm.md). The maps, their mips and
// binding are the exp-warp family's (ExpWarpFilter.h).
#include "techniques/filters/ExpWarpFilter.h"

namespace penumbra {

class EvsmFilter final : public ExpWarpFilter {
public:
  EvsmFilter();
  std::string_view id() const override { return "evsm"; }
  std::string_view description() const override {
    return "exponential variance shadow maps: moments of exp(c+ (2z - 1)) (and -exp(-c- (2z - 1))), mip chain, "
           "trilinear + anisotropic, Chebyshev bound per warp";
  }
  void computeVisibility(FrameContext& frame) override;

private:
  ExpWarpMaps::Warp warp(const FrameContext& frame) const override;
};

}  // namespace penumbra
