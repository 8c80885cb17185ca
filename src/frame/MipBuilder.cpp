#include "frame/MipBuilder.h"

#include <penumbra/Error.h>

namespace penumbra {

void MipBuilder::build(const gl::Texture& texture) {
  PN_CHECK(texture.levels() > 1, "MipBuilder::build: the texture has no mip levels");
  glGenerateTextureMipmap(texture.id());
}

void MipBuilder::setTrilinear(const gl::Texture& texture) {
  glTextureParameteri(texture.id(), GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
  glTextureParameteri(texture.id(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  // Core in 4.6; the ARB/EXT anisotropic extensions share the enum in 4.5.
  if (epoxy_gl_version() >= 46 || epoxy_has_gl_extension("GL_ARB_texture_filter_anisotropic") ||
      epoxy_has_gl_extension("GL_EXT_texture_filter_anisotropic"))
    glTextureParameterf(texture.id(), GL_TEXTURE_MAX_ANISOTROPY, 1.0f);
}

}  // namespace penumbra
