#pragma once
// The parameters of the O(1) soft filters (vssm, msm-soft, evsm-soft): the clamp of their search
// and filter regions, and how a region is read from a mip chain (common/footprint.glsl's
// boxMeanFromMips), declared once for all of them.
#include <penumbra/Params.h>

#include <string_view>

namespace penumbra {

/// "<filter>.minRadiusTexels": the smallest search and filter radius, default 1 texel.
constexpr ParamDesc softMinRadiusParam(std::string_view key) {
  return {key, "Min radius", "smallest filter radius in texels: anti-aliases the hard edge at contact", "texels", 1.0f, 0.5f,
          16.0f, 0.0f};
}

/// "<filter>.maxRadiusTexels": the largest search and filter radius, default 512 texels.
constexpr ParamDesc softMaxRadiusParam(std::string_view key) {
  return {key, "Max radius", "largest search and filter radius in texels (the cost does not depend on it)", "texels", 512.0f,
          1.0f, 4096.0f, 0.0f};
}

/// "<filter>.mipSplit": sub-boxes per axis of a region read from a mip chain, default 2.
constexpr ParamDesc mipSplitParam(std::string_view key) {
  return {key, "Mip split",
          "a region read from the mip chain is n x n sub-boxes, each one mip level finer per halving: 1 = one "
          "trilinear read of the whole box (its tent weighs twice the box's width), 2 = 2x2, 4 = 4x4 (near the exact "
          "box, 16 reads)", "boxes/side",
          2.0f, 1.0f, 4.0f, 1.0f};
}

/// "<filter>.anisotropy": trilinear taps along a non-square region's long axis, default 4.
constexpr ParamDesc mipBoxAnisotropyParam(std::string_view key) {
  return {key, "Anisotropy", "maximum trilinear taps along a non-square region's long axis (regions read from the mip chain)", "taps",
          4.0f, 1.0f, 16.0f, 1.0f};
}

}  // namespace penumbra
