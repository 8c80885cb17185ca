#pragma once
// The parameters of a filter that reads a mip chain over the pixel's footprint (vsm and msm:
// common/footprint.glsl's momentsOverFootprint), declared once for both. The footprint switch
// shapes the lookup's code and reaches it as PN_FOOTPRINT_PIXEL; the tap count stays a uniform
// (compiled in, the loop was unrolled to its maximum and cost vsm and msm x1.4-1.7).
#include <penumbra/Params.h>

#include <string_view>

namespace penumbra {

/// "<filter>.filterTexels": the minimum filter width in texels, default 2.
constexpr ParamDesc footprintWidthParam(std::string_view key) {
  return {key, "Filter width",
          "minimum filter width in shadow-map texels (the pixel footprint is widened to it): the softness", "texels", 2.0f, 1.0f,
          64.0f, 0.0f};
}

/// "<filter>.footprint": filter over the pixel's footprint (on, default) or a fixed box.
constexpr ParamDesc footprintParam(std::string_view key) {
  return {key, "Pixel footprint",
          "on: filter over the pixel's footprint in the map (mip chain, anisotropic taps; antialiased, "
          "view-dependent); off: a fixed box of the filter's filterTexels texels, the same from every camera", "",
          1.0f, 0.0f, 1.0f, 1.0f, kOffOn, "PN_FOOTPRINT_PIXEL"};
}

/// "<filter>.anisotropy": the most trilinear taps along the footprint's long axis, default 8.
constexpr ParamDesc footprintAnisotropyParam(std::string_view key) {
  return {key, "Anisotropy", "maximum trilinear taps along the footprint's long axis (1 = trilinear only)", "taps", 8.0f, 1.0f,
          16.0f, 1.0f};
}

}  // namespace penumbra
