#pragma once
// The exponentially warped shadow maps of esm, evsm and evsm-soft (exp_warp.shared.h): the
// storage formats and the exponents each can hold, the warp shadow pass
// (passes/exp_warp.frag.glsl) and the mip chain that prefilters the moments.
#include "frame/ShadowMaps.h"

#include <string_view>

namespace penumbra {

class FrameContext;

/// "<filter>.storage": float32 or float16 moments.
enum class ExpWarpStorage { Float32 = 0, Float16 = 1 };
inline constexpr std::string_view kExpWarpStorageNames[] = {"float32", "float16"};

/// The largest exponent with which powers 1 … `highestPower` of a warp fit `storage`
/// (exp_warp.shared.h: PN_EXP_WARP_MAX_LOG_*).
float maxWarpExponent(ExpWarpStorage storage, int highestPower);
/// The variance floor that `storage`'s rounding needs, relative to the receiver's warp².
float minRelativeWarpVariance(ExpWarpStorage storage);

class ExpWarpMaps {
public:
  struct Warp {
    float positive = 1.0f;  ///< c+, already within maxWarpExponent
    float negative = 0.0f;  ///< c−, already within maxWarpExponent (components = 4 only)
    int components = 1;     ///< 1 (esm: p), 2 (p, p²), 4 (p, p², n, n²)
    ExpWarpStorage storage = ExpWarpStorage::Float32;
  };
  /// Renders the moments of every view into level 0 (cleared to those of the far plane, z = 1).
  /// Binds the pass's ExpWarpUniforms at PN_UBO_FILTER: set the filter's own block afterwards.
  void render(FrameContext& frame, std::string_view label, const Warp& warp);
  /// Rebuilds the mip chain (the prefilter pass).
  void buildMips() const;
  /// Binds the moments, trilinear, at PN_TEX_FILTER0.
  void bindForFiltering() const;
  const gl::Texture& moments() const { return mMaps.color(); }
  /// The linear light depth the pass wrote with the moments (a min-depth pyramid's input).
  const gl::Texture& depth() const { return mMaps.depth(); }

private:
  ShadowMapArray mMaps;
};

}  // namespace penumbra
