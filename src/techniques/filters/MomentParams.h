#pragma once
// The parameters of the four-moment filters (msm, msm-soft), declared once for both: the moment
// bias (common/moments.glsl: biasMoments and the solve's minimum α; common/shadow.glsl:
// texelDepthVariance turns texels² into stored depth) and the receiver's depth bias.
#include <penumbra/Params.h>

#include <string_view>

namespace penumbra {

/// "<filter>.bias": the moment bias α in texels², default 10.
constexpr ParamDesc momentBiasParam(std::string_view key) {
  return {key, "Moment bias",
          "moment bias α in texels² (α = this × (a texel's world size / the view's depth range)², at least the "
          "storage's minimum): the moments are mixed with those of a spread distribution, b' = (1-α) b + α·0.5; keeps "
          "the solve stable and flat receivers lit, lightens shadows by up to α/2", "texels²",
          10.0f, 0.0f, 1000.0f, 0.0f};
}

/// "<filter>.depthBias": the receiver's depth moved toward the light, default 0.
constexpr ParamDesc momentDepthBiasParam(std::string_view key) {
  return {key, "Depth bias",
          "the receiver depth is moved toward the light by this much, in linear depth units (fraction of the map's depth range)",
          "depth range", 0.0f, 0.0f, 0.05f, 0.0f};
}

}  // namespace penumbra
