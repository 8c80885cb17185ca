#pragma once
// Contact shadows (docs/contact.md): a short march toward the light through the camera's depth
// buffer, after any filter's visibility pass, restores the last centimetres where a caster meets
// its receiver, which every shadow map loses to its bias and its texels. Not a filter: one
// parameter group ("contact.*") any filter can take. V becomes min(V_filter, t / distance) for
// an occluder found t metres along a march of contact.distanceM.
#include <penumbra/Params.h>

namespace penumbra {

class FrameContext;

class ContactShadows {
public:
  /// The "contact.*" parameters (one group of the add-ons, Registry.h's addOnGroups).
  static std::span<const ParamDesc> params();
  /// True when contact.shadows is on in `addOns` (a Parameterized over the add-on groups).
  static bool enabled(const Parameterized& addOns);
  /// Marches every pixel of the frame's surfaces and lowers the visibility image where the
  /// march passes behind the depth buffer (within the thickness). The surfaces and the frame
  /// block must be bound, the visibility written (the core calls it after the filter).
  static void apply(FrameContext& frame, const Parameterized& addOns);
};

}  // namespace penumbra
