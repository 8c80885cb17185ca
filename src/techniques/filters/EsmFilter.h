#pragma once
// esm: exponential shadow maps — exp(c (2z − 1)) in one 32-bit float channel, a mip chain,
// trilinear + anisotropic filtering over the pixel footprint, V = E[p] / p(t) (docs/esm.md).
// The maps, their mips and binding are the exp-warp family's (ExpWarpFilter.h).
#include "techniques/filters/ExpWarpFilter.h"

namespace penumbra {

class EsmFilter final : public ExpWarpFilter {
public:
  EsmFilter();
  std::string_view id() const override { return "esm"; }
  std::string_view description() const override {
    return "exponential shadow maps: exp(c (2z - 1)) in one channel, mip chain, trilinear + anisotropic, V = "
           "E[exp(2c (z - t))]";
  }
  void computeVisibility(FrameContext& frame) override;

private:
  ExpWarpMaps::Warp warp(const FrameContext& frame) const override;
};

}  // namespace penumbra
