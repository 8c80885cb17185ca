#include "frame/MinDepthPyramid.h"

#include "shader/ShaderLibrary.h"
#include "shared/Bindings.h"

#include <penumbra/Error.h>

#include <algorithm>
#include <bit>

namespace penumbra {

bool MinDepthPyramid::hasMinFilter() {
  return epoxy_has_gl_extension("GL_ARB_texture_filter_minmax") || epoxy_has_gl_extension("GL_EXT_texture_filter_minmax");
}

void MinDepthPyramid::build(ShaderLibrary& shaders, const gl::Texture& map, bool minFilter, int maxLevels) {
  PN_CHECK(map.desc().target == GL_TEXTURE_2D_ARRAY, "MinDepthPyramid: the map must be a 2D array texture");
  const int w = (map.width() + 1) / 2, h = (map.height() + 1) / 2, layers = map.layers();
  const int allLevels = std::bit_width(static_cast<unsigned>(std::max(w, h)));  // down to 1×1
  const int levels = maxLevels > 0 ? std::min(maxLevels, allLevels) : allLevels;
  if (!mPyramid || mPyramid.width() != w || mPyramid.height() != h || mPyramid.layers() != layers || mPyramid.levels() != levels) {
    mPyramid = gl::Texture("min-depth pyramid", {GL_TEXTURE_2D_ARRAY, GL_R32F, w, h, layers, levels});
    mPyramid.setSampling(GL_NEAREST_MIPMAP_NEAREST, GL_NEAREST);
  }
  ProgramDesc d;
  d.label = "min-depth pyramid level";
  d.compute = {"passes/min_depth.comp.glsl"};
  const gl::Program& program = shaders.program(d);
  program.use();
  const bool filterMin = minFilter && hasMinFilter();
  if (filterMin && !mMinSampler) {
    // Bilinear within the level that textureLod names (nearest level), clamped: at the corner of
    // four texels every one has a non-zero weight, so the filter returns their minimum.
    gl::SamplerDesc desc{GL_LINEAR_MIPMAP_NEAREST, GL_LINEAR, GL_CLAMP_TO_EDGE, false};
    desc.reduction = GL_MIN;
    mMinSampler = gl::Sampler("min-depth pyramid min filter", desc);
  }
  glProgramUniform1i(program.id(), PN_LOC_SWITCH, filterMin ? 1 : 0);
  if (filterMin) mMinSampler.bindUnit(PN_TEX_FILTER0);
  constexpr GLuint kGroup = 8;  // local size of min_depth.comp.glsl
  for (int level = 0; level < levels; ++level) {
    // Level 0 reads the map's level 0; level k reads the pyramid's level k - 1.
    (level == 0 ? map : mPyramid).bindUnit(PN_TEX_FILTER0);
    glProgramUniform1i(program.id(), PN_LOC_LEVEL, level == 0 ? 0 : level - 1);
    mPyramid.bindImage(PN_IMG_AUX0, GL_WRITE_ONLY, level);
    const GLuint lw = static_cast<GLuint>(std::max(w >> level, 1)), lh = static_cast<GLuint>(std::max(h >> level, 1));
    glDispatchCompute((lw + kGroup - 1) / kGroup, (lh + kGroup - 1) / kGroup, static_cast<GLuint>(layers));
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
  }
  if (filterMin) gl::Sampler::unbindUnit(PN_TEX_FILTER0);
}

}  // namespace penumbra
