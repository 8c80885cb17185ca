#pragma once
// Mip chains of moment maps (vsm, msm, vssm with source=mip): the driver's box-filter
// downsampling (glGenerateTextureMipmap; moments average linearly, so a box chain is exactly a
// chain of region means) and the sampling state that reads them as filtered regions.
// Anisotropy is done in the shader (common/footprint.glsl: textureFootprint), not by the
// sampler: identical on every driver.
#include "gl/Objects.h"

namespace penumbra {

class MipBuilder {
public:
  /// Rebuilds levels 1.. of every layer of `texture` from level 0.
  static void build(const gl::Texture& texture);
  /// Trilinear filtering, isotropic (the sampler's anisotropy set to 1).
  static void setTrilinear(const gl::Texture& texture);
};

}  // namespace penumbra
