#pragma once
// vsm: variance shadow maps — (z, z²) in 32-bit floats, a mip chain, trilinear + anisotropic
// filtering over the pixel footprint, Chebyshev's one-tailed bound (docs/vsm.md). The maps are
// the moment family's (MomentMaps.h).
#include "frame/Filter.h"
#include "techniques/filters/MomentMaps.h"

namespace penumbra {

class VsmFilter final : public Filter {
public:
  VsmFilter();
  std::string_view id() const override { return "vsm"; }
  std::string_view description() const override {
    return "variance shadow maps: (z, z^2) mip chain, trilinear + anisotropic, Chebyshev bound";
  }
  void renderShadowMaps(FrameContext& frame) override;
  void prefilter(FrameContext& frame) override;
  void computeVisibility(FrameContext& frame) override;
  std::vector<DebugImage> debugImages() const override;

private:
  MomentMaps mMaps;
};

}  // namespace penumbra
