#pragma once
// hard: one comparison per pixel with a chosen bias; the baseline every other filter softens.
#include "frame/ShadowMaps.h"

#include "frame/Filter.h"

namespace penumbra {

class HardFilter final : public Filter {
public:
  HardFilter();
  bool readsPagedMaps() const override { return true; }
  std::string_view id() const override { return "hard"; }
  std::string_view description() const override {
    return "one depth comparison per pixel; bias none | constant | slope-scaled | normal offset";
  }
  void renderShadowMaps(FrameContext& frame) override;
  void computeVisibility(FrameContext& frame) override;
  std::vector<DebugImage> debugImages() const override;

private:
  ShadowMapArray mMaps;
};

}  // namespace penumbra
