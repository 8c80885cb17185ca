#pragma once
// uniform: one shadow map fitted to the receivers the camera can see and the casters that can
// shadow them. Orthographic for the sun, perspective for spot lights; near/far tight.
// Its texel density is uniform in light space, so near the camera (in large views) one texel
// covers many pixels: the aliasing that csm/psm/tsm/lispsm reduce.
#include "frame/Projection.h"

namespace penumbra {

class UniformProjection final : public Projection {
public:
  UniformProjection();
  std::string_view id() const override { return "uniform"; }
  std::string_view description() const override {
    return "one map fitted to the visible receivers and their casters (ortho sun, perspective spot)";
  }
  LightFrusta computeFrusta(const Camera& camera, float aspect, const Light& light, const SceneExtent& scene,
                            int mapSize) const override;
};

}  // namespace penumbra
