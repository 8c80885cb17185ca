#include "render/MipBuilder.h"

#include <penumbra/Error.h>

#include <algorithm>

namespace penumbra {

void MipBuilder::build(const gl::Texture& texture) {
  PN_CHECK(texture.levels() > 1, "MipBuilder::build: the texture has no mip levels");
  glGenerateTextureMipmap(texture.id());
}

float MipBuilder::maxSupportedAnisotropy() {
  // Core in OpenGL 4.6; the ARB and EXT extensions share the enums in 4.5.
  if (!epoxy_has_gl_extension("GL_ARB_texture_filter_anisotropic") &&
      !epoxy_has_gl_extension("GL_EXT_texture_filter_anisotropic") && epoxy_gl_version() < 46)
    return 1.0f;
  GLfloat maxAniso = 1.0f;
  glGetFloatv(GL_MAX_TEXTURE_MAX_ANISOTROPY, &maxAniso);
  return std::max(maxAniso, 1.0f);
}

float MipBuilder::setTrilinearAnisotropic(const gl::Texture& texture, float maxAnisotropy) {
  glTextureParameteri(texture.id(), GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
  glTextureParameteri(texture.id(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  const float supported = maxSupportedAnisotropy();
  const float applied = std::clamp(maxAnisotropy, 1.0f, supported);
  if (supported > 1.0f) glTextureParameterf(texture.id(), GL_TEXTURE_MAX_ANISOTROPY, applied);
  return applied;
}

}  // namespace penumbra
