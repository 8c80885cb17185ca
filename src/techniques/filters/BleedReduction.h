#pragma once
// The light-bleeding reduction parameter of the Chebyshev filters (vsm, vssm, evsm, evsm-soft;
// common/chebyshev.glsl: reduceLightBleeding), declared once for all of them.
#include <penumbra/Params.h>

#include <string_view>

namespace penumbra {

/// "<filter>.bleedReduction": visibilities below it become 0, the rest is rescaled; default 0 (off).
constexpr ParamDesc bleedReductionParam(std::string_view key) {
  return {key, "Bleed reduction",
          "light-bleeding reduction: visibilities below this are cut to 0 and the rest rescaled (0 = off)", "V", 0.0f, 0.0f,
          0.95f, 0.0f};
}

}  // namespace penumbra
