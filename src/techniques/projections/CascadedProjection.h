#pragma once
// csm: cascaded shadow maps. The camera's depth range is cut into 1–8 slices by the practical
// split scheme (a λ-blend of logarithmic and uniform splits; Zhang et al., "Parallel-split shadow
// maps", 2006) and each slice gets its own map of the same resolution, so texel size grows with
// distance roughly as a pixel's footprint does. Stabilised (sun only): each cascade is the
// bounding sphere of its slice, whose size never changes, placed on a texel grid fixed in the
// world, so a moving camera never re-samples the edges (no shimmer); the square around the
// sphere leaves many texels unused.
// Neighbouring cascades overlap by a blend band where the visibility pass mixes the two.
// Artifacts: a resolution step at each split (hidden by the band), N shadow passes.
#include "techniques/projections/LightSpace.h"

#include "frame/Projection.h"

#include <vector>

namespace penumbra {

/// The practical split scheme: cascades + 1 camera depths from nearM to farM, each the blend
/// z_i = λ·n·(f/n)^(i/N) + (1 − λ)·(n + (f − n)·i/N). λ = 0 uniform, 1 logarithmic.
std::vector<float> practicalSplits(float nearM, float farM, int cascades, float lambda);

/// The shadowed far distance rounded up to one of a fixed ladder of values (4 steps per octave),
/// so that splits, and with them the cascades' sizes, stay constant while the camera moves.
float stableFarDistance(float farM);

/// The nearest visible receiver's depth rounded down to a quarter octave (2^(k/4) m), at least
/// the camera's near plane: where stabilised cascades start.
float stableNearDistance(float nearM, float cameraNearM);

/// A sun's orthographic view in the basis viewFromWorld (sunViewMatrix: fixed in the world) of
/// half-size `half` (m, per axis) around `centre` (light-view xy, m), the centre snapped to whole
/// texels of a mapSize map so that the map moves by whole texels only; depth over the whole
/// scene (a range that does not move with the camera keeps the stored depths, and the biases in
/// metres, the same from frame to frame). The same half-size gives the same bits every frame.
ShadowView snappedSunView(const SceneExtent& scene, const glm::mat4& viewFromWorld, const glm::vec2& centre,
                          const glm::vec2& half, int mapSize);

/// One unwarped light view fitted to the slice of the camera frustum between view depths a and b
/// (m): the visible receivers there and the casters that can shadow them (fitLightView); the
/// slice's frustum when it sees no part of the scene, so the map stays valid.
ShadowView fittedCascade(const Camera& camera, float aspect, const Light& light, const SceneExtent& scene, float a, float b,
                         float marginFraction);

class CascadedProjection final : public Projection {
public:
  CascadedProjection();
  std::string_view id() const override { return "csm"; }
  std::string_view description() const override {
    return "cascaded maps over practical splits of the view depth; stabilised, with a blend band";
  }
  /// A point light shines every way: its views are the six cube faces of the uniform projection.
  std::string incompatibility(const Light& light) const override { return pointLightIncompatibility(light); }
  LightFrusta computeFrusta(const Camera& camera, float aspect, const Light& light, const SceneExtent& scene,
                            int mapSize) const override;
};

}  // namespace penumbra
