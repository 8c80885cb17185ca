#pragma once
// vsm: variance shadow maps — (z, z²) in 32-bit floats, a mip chain, trilinear + anisotropic
// filtering over the pixel footprint, Chebyshev's one-tailed bound (docs/vsm.md). The maps, their
// mips and binding are the moment family's (MomentFilter.h).
#include "techniques/filters/MomentFilter.h"

namespace penumbra {

class VsmFilter final : public MomentFilter {
public:
  VsmFilter();
  std::string_view id() const override { return "vsm"; }
  std::string_view description() const override {
    return "variance shadow maps: (z, z^2) mip chain, trilinear + anisotropic, Chebyshev bound";
  }
  void computeVisibility(FrameContext& frame) override;

private:
  MomentMaps::Moments moments(const FrameContext& frame) const override;
};

}  // namespace penumbra
