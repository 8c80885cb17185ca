#include "frame/FrameContext.h"

#include "frame/VirtualPages.h"

#include <algorithm>
#include <iterator>

#include "base/Hash.h"
#include "shared/Bindings.h"
#include "shared/Shadow.h"
#include "shared/Enums.h"
#include "shared/VisibilityPoints.h"

#include <penumbra/Error.h>

namespace penumbra {

FrameContext::ShadowPrograms FrameContext::shadowProgram(std::string_view fragment, const ShaderDefines& defines) {
  ProgramDesc d;
  d.label = "shadow pass " + std::string(fragment);
  d.vertex = {"passes/geometry.vert.glsl"};
  d.fragment = {std::string(fragment)};
  d.defines = defines;
  if (mPages) d.defines.set("PN_PAGED_SHADOW_PASS");
  bool orthographic = true;
  for (const ShadowView& v : mFrusta.views) orthographic = orthographic && !v.perspective && !v.warped;
  if (fragment == kDepthOnlyFragment && orthographic) d.defines.set("PN_LINEAR_RASTER_DEPTH");
  ShadowPrograms p;
  p.masked = &mShaders.program(d);
  ProgramDesc opaque = d;
  opaque.label += " (opaque)";
  opaque.defines.set("PN_OPAQUE_CASTERS");
  p.opaque = &mShaders.program(opaque);
  if (mDitherTranslucent) {
    for (ProgramDesc* desc : {&d, &opaque}) {
      desc->label += " (dithered)";
      desc->defines.set("PN_DITHER_TRANSLUCENT");
    }
    p.ditherMasked = &mShaders.program(d);
    p.ditherOpaque = &mShaders.program(opaque);
  }
  return p;
}

int shaderLightKind(const Light& light) {
  switch (light.type) {
    case LightType::Spot: return PN_LIGHT_SPOT;
    case LightType::Point: return PN_LIGHT_POINT;
    case LightType::Directional: break;
  }
  return PN_LIGHT_SUN;
}

ShaderDefines FrameContext::frameDefines() const {
  ShaderDefines d;
  d.set("PN_SHADOW_VIEWS", viewCount());
  d.set("PN_LIGHT_KIND", shaderLightKind(mLight));
  // Perspective and warped are two facts (psm's view of a spot light is both); each is compiled
  // in when every view agrees on it.
  bool allPerspective = true, nonePerspective = true, allWarped = true, noneWarped = true;
  for (const ShadowView& v : mFrusta.views) {
    (v.perspective ? nonePerspective : allPerspective) = false;
    (v.warped ? noneWarped : allWarped) = false;
  }
  if (allPerspective != nonePerspective) d.set("PN_VIEWS_PERSPECTIVE", allPerspective ? 1 : 0);
  if (allWarped != noneWarped) d.set("PN_VIEWS_WARPED", allWarped ? 1 : 0);
  d.set("PN_CASCADE_BLEND", viewCount() > 1 && mFrusta.blendBandM > 0.0f ? 1 : 0);
  if (mPages) d.merge(mPages->defines());
  if (mColourVisibility) d.set("PN_VISIBILITY_RGB");
  return d;
}

ShaderDefines surfaceDefines(const SurfaceFacts& surface) {
  ShaderDefines d;
  if (surface.source == SurfaceSource::Depth) d.set("PN_SURFACE_FROM_DEPTH");
  if (surface.normalsFromPositions) d.set("PN_NORMALS_FROM_POSITIONS");
  if (surface.orthographicCamera) d.set("PN_CAMERA_ORTHOGRAPHIC");
  return d;
}

ShaderDefines FrameContext::surfaceDefines() const { return penumbra::surfaceDefines(mSurface); }

const gl::Program& FrameContext::visibilityProgram(std::string_view filterFile, const ShaderDefines& defines) {
  ProgramDesc d;
  d.label = "visibility " + std::string(filterFile);
  const std::vector<std::string> sources = {std::string(filterFile), "passes/visibility.glsl"};
  d.defines = frameDefines();
  for (const auto& [name, value] : mParams.compileTimeConstants()) d.defines.set(std::string(name), value);
  d.defines.merge(defines);
  if (mPoints) {
    // A point list brings its own positions and normals; only the camera's kind still matters.
    if (mSurface.orthographicCamera) d.defines.set("PN_CAMERA_ORTHOGRAPHIC");
    d.label += " (points)";
    d.defines.set("PN_VISIBILITY_POINTS");
    d.compute = sources;
    return mShaders.program(d);
  }
  d.defines.merge(surfaceDefines());
  d.fragment = sources;
  return mShaders.program(fullScreenProgram(d));
}

const gl::Program& FrameContext::screenProgram(std::string_view file, const Parameterized& params) {
  PN_CHECK(!mPoints, "a screen pass has no screen in points mode");
  ProgramDesc d;
  d.label = "screen " + std::string(file);
  d.compute = {std::string(file)};
  d.defines = frameDefines();
  d.defines.merge(surfaceDefines());
  for (const auto& [name, value] : params.compileTimeConstants()) d.defines.set(std::string(name), value);
  return mShaders.program(d);
}

namespace {

constexpr GLenum kSamplerTypes[] = {GL_SAMPLER_2D, GL_SAMPLER_3D, GL_SAMPLER_CUBE, GL_SAMPLER_2D_SHADOW, GL_SAMPLER_2D_ARRAY,
                                    GL_SAMPLER_2D_ARRAY_SHADOW, GL_SAMPLER_CUBE_MAP_ARRAY, GL_INT_SAMPLER_2D, GL_INT_SAMPLER_2D_ARRAY,
                                    GL_UNSIGNED_INT_SAMPLER_2D, GL_UNSIGNED_INT_SAMPLER_2D_ARRAY};

/// What a shadow pass reads besides the views and the casters, found in the linked program.
struct PassReads {
  bool filterBlock = false;    ///< the filter's uniform block (exp_warp's warp constants)
  bool otherTextures = false;  ///< a texture other than the casters' alpha (depth_peel's first layer)
};

PassReads passReads(GLuint program) {
  PassReads r;
  GLint blocks = 0, uniforms = 0;
  glGetProgramInterfaceiv(program, GL_UNIFORM_BLOCK, GL_ACTIVE_RESOURCES, &blocks);
  for (GLint i = 0; i < blocks; ++i) {
    const GLenum prop = GL_BUFFER_BINDING;
    GLint binding = -1;
    glGetProgramResourceiv(program, GL_UNIFORM_BLOCK, static_cast<GLuint>(i), 1, &prop, 1, nullptr, &binding);
    r.filterBlock = r.filterBlock || binding == PN_UBO_FILTER;
  }
  glGetProgramInterfaceiv(program, GL_UNIFORM, GL_ACTIVE_RESOURCES, &uniforms);
  for (GLint i = 0; i < uniforms; ++i) {
    const GLenum props[] = {GL_TYPE, GL_LOCATION};
    GLint values[2] = {0, -1};
    glGetProgramResourceiv(program, GL_UNIFORM, static_cast<GLuint>(i), 2, props, 2, nullptr, values);
    if (values[1] < 0 || std::find(std::begin(kSamplerTypes), std::end(kSamplerTypes), static_cast<GLenum>(values[0])) == std::end(kSamplerTypes))
      continue;
    GLint unit = -1;
    glGetUniformiv(program, values[1], &unit);
    r.otherTextures = r.otherTextures || unit != PN_TEX_BASECOLOR;
  }
  return r;
}

/// The state every shadow pass draws its maps with, for its lifetime: clip z in [0, 1] is the
/// window depth (what PN_LINEAR_RASTER_DEPTH's clip z, the linear light depth, needs; with
/// gl_FragDepth written it does not matter), depth test LESS with writes, depth clamping, no
/// culling, the map's viewport. The caller's clip control comes back after.
class ShadowPassState {
public:
  explicit ShadowPassState(int mapSize) {
    glGetIntegerv(GL_CLIP_DEPTH_MODE, &mDepthMode);
    glGetIntegerv(GL_CLIP_ORIGIN, &mOrigin);
    glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glEnable(GL_DEPTH_CLAMP);
    glDisable(GL_CULL_FACE);
    glViewport(0, 0, mapSize, mapSize);
  }
  ~ShadowPassState() {
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glDisable(GL_DEPTH_CLAMP);
    glClipControl(static_cast<GLenum>(mOrigin), static_cast<GLenum>(mDepthMode));
  }
  ShadowPassState(const ShadowPassState&) = delete;
  ShadowPassState& operator=(const ShadowPassState&) = delete;

private:
  GLint mDepthMode = GL_ZERO_TO_ONE, mOrigin = GL_LOWER_LEFT;
};

/// The views of the bound shadow block, as the shadow passes read them (for cache keys).
gpu::ShadowUniforms boundShadowViews() {
  gpu::ShadowUniforms views{};
  GLint shadowBlock = 0;
  glGetIntegeri_v(GL_UNIFORM_BUFFER_BINDING, PN_UBO_SHADOW, &shadowBlock);
  glGetNamedBufferSubData(static_cast<GLuint>(shadowBlock), 0, sizeof(views), &views);
  return views;
}

/// A cached layer's key: what every layer shares (`common`) and its own view as the shadow pass
/// reads it, its matrix and depth plane (not the split distances, which only the visibility pass
/// reads). Never 0, which means "nothing cached".
uint64_t layerKey(const Hasher& common, const gpu::ShadowUniforms& views, int v) {
  Hasher h = common;
  h.value(views.views[v].clipFromWorld);
  h.value(views.views[v].depthPlane);
  return h.digest() | 1u;
}

}  // namespace

void FrameContext::ensureMaps(ShadowMapArray& maps, const std::string& label) {
  if (mPages) maps.ensure(label + " (page pool)", mPages->poolSide(), mPages->poolLayers());
  else maps.ensure(label, mMapSize, viewCount());
}

void FrameContext::renderViews(ShadowMapArray& maps, const ShadowPrograms& programs, const glm::vec4& clearColor) {
  const ShadowPassState state(maps.size());
  const float clearDepth = 1.0f;
  // A pass that samples another map (depth peeling) depends on what the dynamic casters drew
  // there: it is never cached.
  const PassReads reads[] = {passReads(programs.opaque->id()), passReads(programs.masked->id())};
  if (mPages) {
    // Pages are cached by their own rules (VirtualPages): what each depends on besides its place.
    PN_CHECK(!maps.color() && !reads[0].otherTextures && !reads[1].otherTextures && !reads[0].filterBlock && !reads[1].filterBlock,
             "a paged map is drawn by the depth-only shadow pass");
    Hasher pass;
    for (const GLuint id : {programs.opaque->id(), programs.masked->id()}) pass.value(id);
    pass.value(clearColor);
    pass.value(mCasters.staticKey());
    pass.value(static_cast<int>(mTranslucentCasters));
    // Dithered translucent casters: every caster through the dithered pass (pages draw their
    // casters in one call).
    const bool dither = programs.ditherOpaque != nullptr;
    mPages->render(*this, maps, (dither ? programs.ditherOpaque : programs.opaque)->id(),
                   (dither ? programs.ditherMasked : programs.masked)->id(), mCasters, pass.digest());
    return;
  }
  // Dithered translucent casters change with the frame's sampling index: such maps are drawn anew.
  const bool cached = mMapCache && !reads[0].otherTextures && !reads[1].otherTextures && !mDitherTranslucent;
  // What every layer's content depends on besides its own view: the shadow pass's programs (and
  // the filter block where they read it), the clear colour, the map size and the static casters.
  Hasher common;
  gpu::ShadowUniforms views{};
  if (cached) {
    if (reads[0].filterBlock || reads[1].filterBlock) {
      std::vector<uint8_t> filterBytes(mFilterBlock.size());
      mFilterBlock.download(filterBytes.data(), filterBytes.size());
      common.bytes(filterBytes.data(), filterBytes.size());
    }
    for (const GLuint id : {programs.opaque->id(), programs.masked->id()}) common.value(id);
    common.value(clearColor);
    common.value(maps.size());
    common.value(mCasters.staticKey());
    if (mTranslucentCasters != CasterSet::Translucent::AsOpaque) common.value(static_cast<int>(mTranslucentCasters));
    views = boundShadowViews();
  }
  for (int v = 0; v < maps.layers() && v < viewCount(); ++v) {
    if (static_cast<size_t>(v) < mKeptViews.size() && mKeptViews[static_cast<size_t>(v)] && maps.drawn(v)) continue;
    maps.markDrawn(v);
    gl::Framebuffer& fb = maps.framebuffer(v);
    glBindFramebuffer(GL_FRAMEBUFFER, fb.id());
    for (const gl::Program* p : {programs.opaque, programs.masked, programs.ditherOpaque, programs.ditherMasked})
      if (p != nullptr) glProgramUniform1i(p->id(), PN_LOC_VIEW, v);
    uint64_t key = 0;
    if (cached) {
      key = layerKey(common, views, v);
      if (maps.restoreCached(v, key)) {
        ++mMapCache->restored;
        mCasters.draw(programs.opaque->id(), programs.masked->id(), CasterSet::Which::Dynamic, mTranslucentCasters);
        continue;
      }
    }
    glClearNamedFramebufferfv(fb.id(), GL_DEPTH, 0, &clearDepth);
    if (maps.color()) glClearNamedFramebufferfv(fb.id(), GL_COLOR, 0, &clearColor.x);
    if (!cached) {
      if (programs.ditherOpaque != nullptr) {  // the opaque casters plain, the translucent ones dithered
        mCasters.draw(programs.opaque->id(), programs.masked->id(), CasterSet::Which::All, CasterSet::Translucent::Skip);
        mCasters.draw(programs.ditherOpaque->id(), programs.ditherMasked->id(), CasterSet::Which::All, CasterSet::Translucent::Only);
      } else {
        mCasters.draw(programs.opaque->id(), programs.masked->id(), CasterSet::Which::All, mTranslucentCasters);
      }
      continue;
    }
    mCasters.draw(programs.opaque->id(), programs.masked->id(), CasterSet::Which::Static, mTranslucentCasters);
    maps.storeCached(v, key);
    ++mMapCache->rendered;
    mCasters.draw(programs.opaque->id(), programs.masked->id(), CasterSet::Which::Dynamic, mTranslucentCasters);
  }
}

namespace {

/// Per view of `maps` (its framebuffer bound, `setView(v)` called): with a map cache, a layer
/// stored under the same key (`common`, the view's matrix and depth plane) is restored and only
/// `draw(Which::Dynamic)` drawn over it; otherwise it is cleared and drawn, the static casters
/// first and stored, then the dynamic ones. Without a cache every caster is drawn.
template <class SetView, class Draw>
void drawCachedLayers(ShadowMapArray& maps, int viewCount, MapCacheState* cache, const Hasher& common, const glm::vec4& clearColor,
                      const SetView& setView, const Draw& draw) {
  const float clearDepth = 1.0f;
  const gpu::ShadowUniforms views = cache ? boundShadowViews() : gpu::ShadowUniforms{};
  for (int v = 0; v < maps.layers() && v < viewCount; ++v) {
    maps.markDrawn(v);
    gl::Framebuffer& fb = maps.framebuffer(v);
    glBindFramebuffer(GL_FRAMEBUFFER, fb.id());
    setView(v);
    uint64_t key = 0;
    if (cache) {
      key = layerKey(common, views, v);
      if (maps.restoreCached(v, key)) {
        ++cache->restored;
        draw(CasterSet::Which::Dynamic);
        continue;
      }
    }
    glClearNamedFramebufferfv(fb.id(), GL_DEPTH, 0, &clearDepth);
    glClearNamedFramebufferfv(fb.id(), GL_COLOR, 0, &clearColor.x);
    if (!cache) {
      draw(CasterSet::Which::All);
      continue;
    }
    draw(CasterSet::Which::Static);
    maps.storeCached(v, key);
    ++cache->rendered;
    draw(CasterSet::Which::Dynamic);
  }
}

}  // namespace

void FrameContext::renderTranslucentViews(ShadowMapArray& maps, const ShadowPrograms& opaque, const ShadowPrograms& translucent) {
  const ShadowPassState state(maps.size());
  Hasher common;
  for (const ShadowPrograms* p : {&opaque, &translucent})
    for (const gl::Program* program : {p->opaque, p->masked}) common.value(program->id());
  common.value(maps.size());
  common.value(mCasters.staticKey());
  const auto setView = [&](int v) {
    for (const ShadowPrograms* p : {&opaque, &translucent}) {
      glProgramUniform1i(p->opaque->id(), PN_LOC_VIEW, v);
      glProgramUniform1i(p->masked->id(), PN_LOC_VIEW, v);
    }
  };
  const auto draw = [&](CasterSet::Which which) {
    glDepthMask(GL_TRUE);
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    mCasters.draw(opaque.opaque->id(), opaque.masked->id(), which, CasterSet::Translucent::Skip);
    glDepthMask(GL_FALSE);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glEnable(GL_BLEND);
    glBlendEquationSeparate(GL_FUNC_ADD, GL_MIN);          // colour: a product; alpha: the nearest depth
    glBlendFuncSeparate(GL_ZERO, GL_SRC_COLOR, GL_ONE, GL_ONE);  // MIN ignores the alpha factors
    mCasters.draw(translucent.opaque->id(), translucent.masked->id(), which, CasterSet::Translucent::Only);
    glDisable(GL_BLEND);
    glBlendEquation(GL_FUNC_ADD);
    glBlendFunc(GL_ONE, GL_ZERO);
    glDepthMask(GL_TRUE);
  };
  drawCachedLayers(maps, viewCount(), mMapCache, common, glm::vec4(1.0f), setView, draw);
}

void FrameContext::sumTranslucentViews(ShadowMapArray& maps, const ShadowPrograms& program) {
  const ShadowPassState state(maps.size());
  Hasher common;
  for (const gl::Program* p : {program.opaque, program.masked}) common.value(p->id());
  common.value(maps.size());
  common.value(mCasters.staticKey());
  const auto setView = [&](int v) {
    glProgramUniform1i(program.opaque->id(), PN_LOC_VIEW, v);
    glProgramUniform1i(program.masked->id(), PN_LOC_VIEW, v);
  };
  const auto draw = [&](CasterSet::Which which) {
    glDisable(GL_DEPTH_TEST);
    glDepthMask(GL_FALSE);
    glEnable(GL_BLEND);
    glBlendEquation(GL_FUNC_ADD);
    glBlendFunc(GL_ONE, GL_ONE);
    mCasters.draw(program.opaque->id(), program.masked->id(), which, CasterSet::Translucent::Only);
    glDisable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ZERO);
    glDepthMask(GL_TRUE);
    glEnable(GL_DEPTH_TEST);
  };
  drawCachedLayers(maps, viewCount(), mMapCache, common, glm::vec4(0.0f), setView, draw);
}

void FrameContext::multiplyVisibility(const gl::Program& program) const {
  PN_CHECK(!mPoints && !program.isCompute() && mVisibilityTarget != nullptr, "multiplyVisibility: a fragment pass over the screen");
  mVisibilityTarget->draw(program, mScreen, ScreenTarget::Write::Multiply);
}

void FrameContext::setFilterBlockBytes(const void* data, size_t bytes) {
  PN_CHECK(bytes <= mFilterBlock.size(), "filter uniform block too large");
  mFilterBlock.upload(data, bytes);
  mFilterBlock.bindBase(GL_UNIFORM_BUFFER, PN_UBO_FILTER);
}

void FrameContext::dispatchScreen(const gl::Program& program, bool readVisibility) const {
  if (mPages) mPages->bind();
  if (mPoints) {
    mPoints->bindBase(GL_SHADER_STORAGE_BUFFER, PN_SSBO_POINTS);
    mPointVisibility->bindBase(GL_SHADER_STORAGE_BUFFER, PN_SSBO_POINT_VISIBILITY);
    dispatch2D(program, PN_POINTS_GRID_WIDTH, (mPointCount + PN_POINTS_GRID_WIDTH - 1) / PN_POINTS_GRID_WIDTH, PN_SCREEN_GROUP);
    return;
  }
  if (!program.isCompute()) {
    PN_CHECK(!readVisibility && mVisibilityTarget != nullptr, "a fragment pass only writes the visibility");
    mVisibilityTarget->draw(program, mScreen);
    return;
  }
  PN_ASSERT(mVisibility != nullptr);
  mVisibility->bindImageLayer(PN_IMG_VISIBILITY, readVisibility ? GL_READ_WRITE : GL_WRITE_ONLY, mVisibilityLayer);
  dispatch2D(program, mScreen.x, mScreen.y, PN_SCREEN_GROUP);
}

void FrameContext::dispatch2D(const gl::Program& program, int width, int height, int group) {
  program.use();
  glDispatchCompute(static_cast<GLuint>((width + group - 1) / group), static_cast<GLuint>((height + group - 1) / group), 1);
  glMemoryBarrier(GL_ALL_BARRIER_BITS);
}

}  // namespace penumbra
