#pragma once
// The aliasing axis: where the light's view(s) are placed and how they are warped. A projection
// holds no GPU storage: an instance is its parameter values (a light's, made from its technique:
// makeProjection) and a pure function of them. Pure C++ (no GL), so every projection is
// unit-testable on the CPU.
#include <penumbra/Camera.h>
#include <penumbra/Light.h>
#include <penumbra/Params.h>
#include <penumbra/Scene.h>
#include <penumbra/ShadowViews.h>

#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace penumbra {

class Projection : public Parameterized {
public:
  using Parameterized::Parameterized;
  virtual std::string_view id() const = 0;
  virtual std::string_view description() const = 0;
  /// Empty when this projection can place views for `light`; otherwise the reason, shown to the
  /// user (a pair that cannot work is refused, never rendered wrong).
  virtual std::string incompatibility(const Light& light) const {
    (void)light;
    return {};
  }
  /// The light's view(s) for this camera. `aspect` = width / height of the image; `mapSize` =
  /// texels per side of each map (fits add margins and snap in whole texels).
  virtual LightFrusta computeFrusta(const Camera& camera, float aspect, const Light& light,
                                    const SceneExtent& scene, int mapSize) const = 0;
};

}  // namespace penumbra
