#pragma once
// Mip chains of moment maps (vsm, msm, vssm with source=mip): the driver's box-filter
// downsampling (glGenerateTextureMipmap; moments average linearly, so a box chain is exactly a
// chain of region means) and the sampling state that reads them as filtered regions.
#include "gl/Objects.h"

namespace penumbra {

class MipBuilder {
public:
  /// Rebuilds levels 1.. of every layer of `texture` from level 0.
  static void build(const gl::Texture& texture);
  /// Trilinear filtering with up to `maxAnisotropy` (1 = isotropic) taps along the footprint's
  /// long axis, clamped to what the driver offers (1 without anisotropic filtering). Returns the
  /// value applied.
  static float setTrilinearAnisotropic(const gl::Texture& texture, float maxAnisotropy);
  /// The driver's largest anisotropy (1 when anisotropic filtering is not available).
  static float maxSupportedAnisotropy();
};

}  // namespace penumbra
