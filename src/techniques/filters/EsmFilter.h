#pragma once
// esm: exponential shadow maps — exp(c (2z − 1)) in one 32-bit float channel, a mip chain,
// trilinear + anisotropic filtering over the pixel footprint, V = E[p] / p(t) (docs/esm.md).
#include "techniques/filters/ExpWarpMaps.h"

#include "frame/Filter.h"

namespace penumbra {

class EsmFilter final : public Filter {
public:
  EsmFilter();
  std::string_view id() const override { return "esm"; }
  std::string_view description() const override {
    return "exponential shadow maps: exp(c (2z - 1)) in one channel, mip chain, trilinear + anisotropic, V = "
           "E[exp(2c (z - t))]";
  }
  void renderShadowMaps(FrameContext& frame) override;
  void prefilter(FrameContext& frame) override;
  void computeVisibility(FrameContext& frame) override;
  std::vector<DebugImage> debugImages() const override;

private:
  ExpWarpMaps mMaps;
};

}  // namespace penumbra
