#include "techniques/contact/ContactShadows.h"

#include "frame/FrameContext.h"
#include "techniques/contact/contact.shared.h"

namespace penumbra {
namespace {

constexpr ParamDesc kParams[] = {
    {"contact.shadows", "Contact shadows",
     "on: after the filter, a short march toward the light through the depth buffer darkens where a caster sits closer "
     "than the shadow map resolves (V = min of both; the march's V fades from 0 at the contact to 1 at its end)", "",
     0.0f, 0.0f, 1.0f, 1.0f, kOffOn},
    {"contact.distanceM", "Distance", "length of the march toward the light, in metres: the contact detail it can restore", "m",
     0.1f, 0.01f, 10.0f, 0.0f},
    {"contact.steps", "Steps", "depth-buffer samples along the march (a caster thinner than distance/steps can be stepped over)", "steps",
     16.0f, 1.0f, 64.0f, 1.0f, {}, "PN_CONTACT_STEPS"},
    {"contact.thicknessM", "Thickness", "how deep behind the depth buffer a sample still counts as inside a caster, in metres "
     "(the depth buffer holds only front surfaces: everything behind them is assumed this thick)", "m",
     0.05f, 0.001f, 10.0f, 0.0f},
    {"contact.startOffsetM", "Start offset", "the march starts this far off the receiver along its normal, in metres, out of "
     "the receiver's own depth-buffer surface", "m", 0.01f, 0.0f, 1.0f, 0.0f},
    {"contact.tolerance", "Depth tolerance", "a sample must lie behind the depth buffer by more than this fraction of its "
     "camera distance to count (the depth buffer's own steps on tilted surfaces)", "of distance", 0.002f, 0.0f, 0.1f, 0.0f},
};

}  // namespace

std::span<const ParamDesc> ContactShadows::params() { return kParams; }

bool ContactShadows::enabled(const Parameterized& addOns) { return addOns.paramInt("contact.shadows") != 0; }

void ContactShadows::apply(FrameContext& frame, const Parameterized& addOns) {
  gpu::ContactUniforms u{};
  u.march = glm::vec4(addOns.param("contact.distanceM"), addOns.param("contact.thicknessM"), addOns.param("contact.startOffsetM"),
                      addOns.param("contact.tolerance"));
  frame.setFilterBlock(u);
  frame.dispatchScreen(frame.screenProgram("techniques/contact/contact_shadows.glsl", addOns), true);
}

}  // namespace penumbra
