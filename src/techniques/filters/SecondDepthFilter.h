#pragma once
// second-depth: the midpoint of the two nearest surfaces, compared without bias (second_depth.glsl).
#include "gl/Objects.h"
#include "frame/ShadowMaps.h"

#include "frame/Filter.h"

namespace penumbra {

class SecondDepthFilter final : public Filter {
public:
  SecondDepthFilter();
  std::string_view id() const override { return "second-depth"; }
  std::string_view description() const override {
    return "second-depth shadow map: midpoint of the first two surfaces (depth peeling), no bias; needs watertight casters";
  }
  void renderShadowMaps(FrameContext& frame) override;
  void computeVisibility(FrameContext& frame) override;
  std::vector<DebugImage> debugImages() const override;

private:
  ShadowMapArray mFirst;   // nearest surface; colour: its depth slope per texel
  ShadowMapArray mSecond;  // nearest surface behind the first
  gl::Texture mMidpoint;   // R32F array: the map that is compared
};

}  // namespace penumbra
