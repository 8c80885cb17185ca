#include "techniques/translucent/TranslucentShadows.h"

#include "frame/FrameContext.h"
#include "techniques/translucent/translucent.shared.h"
#include "shared/Bindings.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace penumbra {
namespace {

// translucent.method's choices, by value (core/ShadowsImpl.h's ditherTranslucent reads 1 as stochastic).
constexpr std::string_view kMethods[] = {"map", "stochastic"};

constexpr ParamDesc kParams[] = {
    {"translucent.shadows", "Translucent shadows",
     "on: translucent casters tint the light instead of blocking it: the filter's maps hold the opaque casters, a second "
     "map per view the product of the translucent casters' transmittances in front of them, and V (RGB) is the filter's "
     "V times that product where the receiver lies behind them", "",
     0.0f, 0.0f, 1.0f, 1.0f, kOffOn},
    {"translucent.method", "Method",
     "map: the transmittance map tints V (colour); stochastic: the translucent casters are dithered into the filter's own "
     "maps, each texel kept with the probability of the caster's opacity 1 - mean(T), a pattern the frame's sampling index "
     "turns, resolved by the filter's taps and temporal.accumulate (V one channel: no hue)", "", 0.0f, 0.0f, 1.0f, 1.0f, kMethods},
    {"translucent.mapScale", "Map scale", "side of the transmittance map as a share of the light's map size (0.5: a quarter of "
     "its texels): its cost and memory scale with the square", "× map size", 0.5f, 0.125f, 1.0f, 0.0f},
    {"translucent.radiusTexels", "Tint radius", "the tint is averaged over a box of (2r + 1)² texels of the transmittance map "
     "(0 = one texel: a hard-edged tint)", "texels", 1.0f, 0.0f, 4.0f, 1.0f, {}, "PN_TRANSLUCENT_RADIUS"},
    {"translucent.planeBiasTexels", "Plane bias", "a receiver is behind a translucent surface when its plane at the texel's "
     "centre, moved back along its normal by this many texels of world size (as hard.planeBiasTexels), is farther than it", "texels",
     1.0f, 0.0f, 16.0f, 0.0f},
};

}  // namespace

std::span<const ParamDesc> TranslucentShadows::params() { return kParams; }

bool TranslucentShadows::enabled(const Parameterized& addOns) { return addOns.paramInt("translucent.shadows") != 0; }

void TranslucentShadows::renderMaps(FrameContext& frame, const Parameterized& addOns) {
  constexpr int kMinSide = 16;
  const int side = std::max(kMinSide, static_cast<int>(std::lround(static_cast<float>(frame.mapSize()) * addOns.param("translucent.mapScale"))));
  mMaps.ensure("translucent transmittance map", side, frame.viewCount(), GL_RGBA32F);
  frame.renderTranslucentViews(mMaps, frame.shadowProgram(), frame.shadowProgram("techniques/translucent/translucent_map.frag.glsl"));
}

void TranslucentShadows::apply(FrameContext& frame, const Parameterized& addOns) {
  gpu::TranslucentUniforms u{};
  u.params = glm::vec4(0.0f, addOns.param("translucent.planeBiasTexels"), 0.0f, 0.0f);
  frame.setFilterBlock(u);
  mMaps.color().bindUnit(PN_TEX_FILTER0);
  ShaderDefines defines;
  defines.set("PN_TRANSLUCENT_RADIUS", addOns.paramInt("translucent.radiusTexels"));
  frame.multiplyVisibility(frame.visibilityProgram("techniques/translucent/translucent_tint.glsl", defines));
}

std::vector<DebugImage> TranslucentShadows::debugImages() const {
  if (!mMaps.color()) return {};
  return {{"transmittance-map", &mMaps.color(),
           "rgb: product of the translucent casters' transmittances in front of the nearest opaque caster (1 = none); "
           "alpha: linear light depth of the nearest translucent one"}};
}

}  // namespace penumbra
