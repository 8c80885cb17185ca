#pragma once
// Shadows through translucent casters (docs/translucent.md): a coloured transmittance map per
// light. Not a filter: one parameter group ("translucent.*") any filter can take. With it on
// (and some caster translucent, CasterMesh::transmittance), the filter's own maps hold the
// opaque casters only, and a second map per view holds, for each texel, the product of the
// transmittances of the translucent casters in front of the nearest opaque one (multiplicative
// blending, depth-tested against the opaque depth) and the nearest translucent depth (MIN
// blending). After the filter's visibility pass, V is multiplied, per channel, by the product
// read where the receiver lies behind that nearest translucent surface (the depth comparison,
// biased as `hard`'s plane bias, decides "behind"), averaged over a box of texels.
#include "frame/ShadowMaps.h"

#include "frame/Filter.h"

#include <penumbra/Params.h>

#include <span>
#include <vector>

namespace penumbra {

class FrameContext;

class TranslucentShadows {
public:
  /// The "translucent.*" parameters (one group of the add-ons, Registry.h's addOnGroups).
  static std::span<const ParamDesc> params();
  /// True when translucent.shadows is on in `addOns` (a Parameterized over the add-on groups).
  static bool enabled(const Parameterized& addOns);

  /// Draws the light's transmittance maps, one per view of the frame, translucent.mapScale of
  /// the light's map size per side (timed with the shadow pass).
  void renderMaps(FrameContext& frame, const Parameterized& addOns);
  /// Multiplies the light's visibility layer (RGB) by the translucent casters' product in front
  /// of each pixel. After the filter's visibility pass; the surfaces and blocks are bound.
  void apply(FrameContext& frame, const Parameterized& addOns);
  /// The transmittance maps, for the viewer and --dump (none before the first frame).
  std::vector<DebugImage> debugImages() const;
  /// Frees the maps (the add-on was turned off).
  void release() { mMaps = {}; }

private:
  ShadowMapArray mMaps;
};

}  // namespace penumbra
