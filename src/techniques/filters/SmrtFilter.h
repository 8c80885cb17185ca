#pragma once
// smrt: shadow-map ray tracing — rays toward the light's area marched through the map (smrt.glsl).
#include "frame/ShadowMaps.h"
#include "techniques/TightSearch.h"

#include "frame/Filter.h"

namespace penumbra {

class SmrtFilter final : public Filter {
public:
  SmrtFilter();
  bool readsPagedMaps() const override { return true; }
  std::string_view id() const override { return "smrt"; }
  std::string_view description() const override {
    return "shadow-map ray tracing: rays toward points of the light's area, marched through the map with a thickness test";
  }
  void renderShadowMaps(FrameContext& frame) override;
  /// The map's min-depth pyramid: where each pixel's march ends, and which pixels need none.
  void prefilter(FrameContext& frame) override;
  void computeVisibility(FrameContext& frame) override;
  std::vector<DebugImage> debugImages() const override;

private:
  /// The spatial filter's two passes (smrt_filter.glsl), over the visibility layer just written.
  void filterSpatially(FrameContext& frame);

  ShadowMapArray mMaps;
  TightSearch mNearest;
  gl::Texture mMeans;  ///< R32F, the screen's size: V averaged along the shadow's edges
};

}  // namespace penumbra
