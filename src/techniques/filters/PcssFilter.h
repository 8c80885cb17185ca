#pragma once
// pcss: percentage-closer soft shadows — blocker search, penumbra estimate, PCF (pcss.glsl).
#include "frame/ShadowMaps.h"
#include "techniques/PenumbraDebugImages.h"
#include "techniques/TightSearch.h"
#include "techniques/filters/PcfFilter.h"

#include "frame/Filter.h"

namespace penumbra {

class PcssFilter final : public Filter {
public:
  PcssFilter();
  bool readsPagedMaps() const override { return true; }
  std::string_view id() const override { return "pcss"; }
  std::string_view description() const override {
    return "percentage-closer soft shadows: blocker search, penumbra width from the light size, PCF of that width";
  }
  void renderShadowMaps(FrameContext& frame) override;
  void prefilter(FrameContext& frame) override;
  void computeVisibility(FrameContext& frame) override;
  /// "shadow-map", then "blocker-depth" and "penumbra-width-m" (PenumbraDebugImages.h).
  std::vector<DebugImage> debugImages() const override;

private:
  ShadowMapArray mMaps;
  ComparisonSampler mCompare;
  PenumbraDebugImages mPenumbraDebug;
  TightSearch mTightSearch;
};

}  // namespace penumbra
