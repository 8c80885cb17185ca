#pragma once
// The parameters shared by evsm and evsm-soft (exp_warp.shared.h, ExpWarpMaps.h), declared once
// for both, the exponents in force once the storage's limit is applied, and the warp those give.
#include "techniques/filters/ExpWarpMaps.h"
#include "techniques/filters/exp_warp.shared.h"

#include <penumbra/Params.h>

#include <glm/vec4.hpp>

#include <algorithm>
#include <string_view>

namespace penumbra {

// The help texts below quote the exponent limits of exp_warp.shared.h.
static_assert(PN_EXP_WARP_MAX_LOG_FLOAT32 / 2.0f == 43.0f && PN_EXP_WARP_MAX_LOG_FLOAT16 / 2.0f == 5.5f,
              "update the limits quoted in the help texts");

/// "<filter>.storage": float32 (default) or float16.
constexpr ParamDesc expWarpStorageParam(std::string_view key) {
  return {key, "Storage",
          "float32: 32-bit float moments, exponents up to 43; float16: half the memory, exponents clamped to 5.5 "
          "(e^11, the second moment at the far plane, is the largest power of e a half holds)", "",
          0.0f, 0.0f, 1.0f, 1.0f, kExpWarpStorageNames};
}

/// The default c+, 20, half of what Filament and MJP's sample use in float32. Measured on
/// llvmpipe (docs/evsm.md): fence behind the wall, umbra leak % 0.377 at 10, 0.048 at 20, 0.024
/// at 40 (vsm 2.394): bleeding is gone by 20. Above it the positive warp turns a region's depth
/// spread on a receiver tilted in light space into variance e^(4c+ Δz): at 40, evsm with 2
/// components lit 6 of 124 shadowed floor probes by boxes' feet to V 0.21–0.29, and evsm-soft's
/// penumbra-sized boxes on pen read RMSE 0.0117 (0.0105 at 20).
inline constexpr float kDefaultPositiveExponent = 20.0f;

/// "<filter>.positiveExponent": c+ of p = exp(c+ (2z − 1)), default kDefaultPositiveExponent.
constexpr ParamDesc positiveExponentParam(std::string_view key) {
  return {key, "Positive exponent",
          "c+ of the positive warp exp(c+ (2z - 1)) of linear depth z: larger cuts more light bleeding between "
          "occluders; clamped to 43 (float32) or 5.5 (float16) so that the stored p² stays finite", "factor",
          kDefaultPositiveExponent, 1.0f, PN_EXP_WARP_MAX_LOG_FLOAT32 / 2.0f, 0.0f};
}

/// "<filter>.negativeExponent": c− of n = −exp(−c− (2z − 1)), default 5.
constexpr ParamDesc negativeExponentParam(std::string_view key) {
  return {key, "Negative exponent",
          "c- of the negative warp -exp(-c- (2z - 1)) (components=4): it bounds the receivers the positive warp "
          "leaves lit near a far occluder; clamped to 43 (float32) or 5.5 (float16)", "factor",
          5.0f, 1.0f, PN_EXP_WARP_MAX_LOG_FLOAT32 / 2.0f, 0.0f};
}

/// An evsm exponent (a parameter within the float32 range) clamped to what `storage` holds for
/// a warp's first two powers.
inline float clampWarpExponent(float exponent, ExpWarpStorage storage) {
  return std::min(exponent, maxWarpExponent(storage, 2));
}

/// The warp of a filter that bounds with Chebyshev (evsm, evsm-soft): `components` 2 (the
/// positive warp) or 4 (both), each exponent clamped to what `storage` holds.
inline ExpWarpMaps::Warp chebyshevWarp(int components, ExpWarpStorage storage, float positiveExponent,
                                       float negativeExponent) {
  ExpWarpMaps::Warp w;
  w.components = components;
  w.storage = storage;
  w.positive = clampWarpExponent(positiveExponent, storage);
  w.negative = components == 4 ? clampWarpExponent(negativeExponent, storage) : 0.0f;
  return w;
}

/// The warp as evsm's and evsm-soft's blocks take it: (c+, c−, the storage's relative variance
/// floor, components).
inline glm::vec4 chebyshevWarpUniform(const ExpWarpMaps::Warp& w) {
  return {w.positive, w.negative, minRelativeWarpVariance(w.storage), static_cast<float>(w.components)};
}

}  // namespace penumbra
