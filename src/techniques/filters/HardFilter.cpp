#include "techniques/filters/HardFilter.h"

#include "frame/FrameContext.h"
#include "techniques/filters/hard.shared.h"
#include "shared/Bindings.h"

namespace penumbra {
namespace {

constexpr std::string_view kBiasModes[] = {"none", "constant", "slope", "normal", "plane"};
static_assert(PN_BIAS_NONE == 0 && PN_BIAS_CONSTANT == 1 && PN_BIAS_SLOPE == 2 && PN_BIAS_NORMAL == 3 && PN_BIAS_PLANE == 4,
              "kBiasModes follows the PN_BIAS_* order");

constexpr ParamDesc kParams[] = {
    {"hard.bias", "Bias", "how self-shadowing (acne) is avoided: none, constant, slope (constant + slope-scaled), normal (offset along the normal + constant) or plane (the receiver's own plane at the texel's centre, moved back along its normal by hard.planeBiasTexels)", "",
     PN_BIAS_PLANE, 0, 4, 1, kBiasModes, "PN_HARD_BIAS"},
    {"hard.constantBias", "Constant bias", "depth offset in linear light-depth units (fraction of the map's depth range)", "depth range",
     0.0002f, 0.0f, 0.05f, 0.0f},
    {"hard.slopeBias", "Slope bias", "slope-scaled offset: multiples of texel size × tan(angle to the light)", "texel·tanθ",
     1.0f, 0.0f, 16.0f, 0.0f},
    {"hard.normalOffsetTexels", "Normal offset", "receiver moved along its normal by this many shadow-map texels", "texels",
     1.0f, 0.0f, 16.0f, 0.0f},
    {"hard.planeBiasTexels", "Plane bias", "plane mode: the receiver's plane at its texel's centre, moved back along its normal by this many texels of world size plus that centre's distance from the receiver in texels", "texels",
     1.0f, 0.0f, 16.0f, 0.0f},
};

}  // namespace

HardFilter::HardFilter() : Filter(kParams) {}

void HardFilter::renderShadowMaps(FrameContext& frame) {
  frame.ensureMaps(mMaps, "hard shadow map");
  frame.renderViews(mMaps, frame.shadowProgram());
}

void HardFilter::computeVisibility(FrameContext& frame) {
  gpu::HardUniforms u{};
  u.bias = glm::vec4(frame.param("hard.constantBias"), frame.param("hard.slopeBias"), frame.param("hard.normalOffsetTexels"),
                     frame.param("hard.planeBiasTexels"));
  frame.setFilterBlock(u);
  mMaps.depth().bindUnit(PN_TEX_FILTER0);
  frame.dispatchScreen(frame.visibilityProgram("techniques/filters/hard.glsl"));
}

std::vector<DebugImage> HardFilter::debugImages() const { return {{std::string(kShadowMapImage), &mMaps.depth(), kShadowMapMeaning}}; }

}  // namespace penumbra
