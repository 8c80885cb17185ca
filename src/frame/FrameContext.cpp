#include "frame/FrameContext.h"

#include "shared/Bindings.h"
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
  bool orthographic = true;
  for (const ShadowView& v : mFrusta.views) orthographic = orthographic && !v.perspective && !v.warped;
  if (fragment == kDepthOnlyFragment && orthographic) d.defines.set("PN_LINEAR_RASTER_DEPTH");
  ShadowPrograms p;
  p.masked = &mShaders.program(d);
  d.label += " (opaque)";
  d.defines.set("PN_OPAQUE_CASTERS");
  p.opaque = &mShaders.program(d);
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
  return d;
}

const gl::Program& FrameContext::visibilityProgram(std::string_view filterFile, const ShaderDefines& defines) {
  ProgramDesc d;
  d.label = "visibility " + std::string(filterFile);
  d.compute = {std::string(filterFile), "passes/visibility.comp.glsl"};
  d.defines = frameDefines();
  d.defines.merge(defines);
  if (mSurface == SurfaceSource::Depth && !mPoints) d.defines.set("PN_SURFACE_FROM_DEPTH");
  if (mPoints) {
    d.label += " (points)";
    d.defines.set("PN_VISIBILITY_POINTS");
  }
  return mShaders.program(d);
}

const gl::Program& FrameContext::visibilityProgram(std::string_view filterFile, const Parameterized& params,
                                                  const ShaderDefines& defines) {
  ShaderDefines all;
  for (const auto& [name, value] : params.compileTimeConstants()) all.set(std::string(name), value);
  return visibilityProgram(filterFile, all.merge(defines));
}

const gl::Program& FrameContext::screenProgram(std::string_view file, const Parameterized& params) {
  PN_CHECK(!mPoints, "a screen pass has no screen in points mode");
  ProgramDesc d;
  d.label = "screen " + std::string(file);
  d.compute = {std::string(file)};
  d.defines = frameDefines();
  if (mSurface == SurfaceSource::Depth) d.defines.set("PN_SURFACE_FROM_DEPTH");
  for (const auto& [name, value] : params.compileTimeConstants()) d.defines.set(std::string(name), value);
  return mShaders.program(d);
}

void FrameContext::renderViews(ShadowMapArray& maps, const ShadowPrograms& programs, const glm::vec4& clearColor) {
  // Clip z in [0, 1] is the window depth: what PN_LINEAR_RASTER_DEPTH's clip z (the linear light
  // depth) needs; with gl_FragDepth written it does not matter. The caller's mode comes back.
  GLint depthMode = GL_ZERO_TO_ONE, origin = GL_LOWER_LEFT;
  glGetIntegerv(GL_CLIP_DEPTH_MODE, &depthMode);
  glGetIntegerv(GL_CLIP_ORIGIN, &origin);
  glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  glEnable(GL_DEPTH_CLAMP);
  glDisable(GL_CULL_FACE);
  glViewport(0, 0, maps.size(), maps.size());
  const float clearDepth = 1.0f;
  for (int v = 0; v < maps.layers() && v < viewCount(); ++v) {
    gl::Framebuffer& fb = maps.framebuffer(v);
    glBindFramebuffer(GL_FRAMEBUFFER, fb.id());
    glClearNamedFramebufferfv(fb.id(), GL_DEPTH, 0, &clearDepth);
    if (maps.color()) glClearNamedFramebufferfv(fb.id(), GL_COLOR, 0, &clearColor.x);
    glProgramUniform1i(programs.opaque->id(), PN_LOC_VIEW, v);
    glProgramUniform1i(programs.masked->id(), PN_LOC_VIEW, v);
    mCasters.draw(programs.opaque->id(), programs.masked->id());
  }
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glDisable(GL_DEPTH_CLAMP);
  glClipControl(static_cast<GLenum>(origin), static_cast<GLenum>(depthMode));
}

void FrameContext::setFilterBlockBytes(const void* data, size_t bytes) {
  PN_CHECK(bytes <= mFilterBlock.size(), "filter uniform block too large");
  mFilterBlock.upload(data, bytes);
  mFilterBlock.bindBase(GL_UNIFORM_BUFFER, PN_UBO_FILTER);
}

void FrameContext::dispatchScreen(const gl::Program& program, bool readVisibility) const {
  if (mPoints) {
    mPoints->bindBase(GL_SHADER_STORAGE_BUFFER, PN_SSBO_POINTS);
    mPointVisibility->bindBase(GL_SHADER_STORAGE_BUFFER, PN_SSBO_POINT_VISIBILITY);
    dispatch2D(program, PN_POINTS_GRID_WIDTH, (mPointCount + PN_POINTS_GRID_WIDTH - 1) / PN_POINTS_GRID_WIDTH, PN_SCREEN_GROUP);
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
