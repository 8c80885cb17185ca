#include "frame/FrameContext.h"

#include "shared/Bindings.h"
#include "shared/Enums.h"
#include "shared/VisibilityPoints.h"

#include <penumbra/Error.h>

namespace penumbra {

const gl::Program& FrameContext::shadowProgram(std::string_view fragment, const ShaderDefines& defines) {
  ProgramDesc d;
  d.label = "shadow pass " + std::string(fragment);
  d.vertex = {"passes/geometry.vert.glsl"};
  d.fragment = {std::string(fragment)};
  d.defines = defines;
  return mShaders.program(d);
}

ShaderDefines FrameContext::frameDefines() const {
  ShaderDefines d;
  d.set("PN_SHADOW_VIEWS", viewCount());
  d.set("PN_LIGHT_KIND", mLight.type == LightType::Spot ? PN_LIGHT_SPOT : PN_LIGHT_SUN);
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

void FrameContext::renderViews(ShadowMapArray& maps, const gl::Program& program, const glm::vec4& clearColor) {
  program.use();
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
    drawCasters(program, v);
  }
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glDisable(GL_DEPTH_CLAMP);
}

void FrameContext::drawCasters(const gl::Program& program, int view) const {
  glProgramUniform1i(program.id(), PN_LOC_VIEW, view);
  mCasters.draw(program.id());
}

void FrameContext::setFilterBlockBytes(const void* data, size_t bytes) {
  PN_CHECK(bytes <= mFilterBlock.size(), "filter uniform block too large");
  mFilterBlock.upload(data, bytes);
  mFilterBlock.bindBase(GL_UNIFORM_BUFFER, PN_UBO_FILTER);
}

void FrameContext::dispatchScreen(const gl::Program& program) const {
  if (mPoints) {
    mPoints->bindBase(GL_SHADER_STORAGE_BUFFER, PN_SSBO_POINTS);
    mPointVisibility->bindBase(GL_SHADER_STORAGE_BUFFER, PN_SSBO_POINT_VISIBILITY);
    dispatch2D(program, PN_POINTS_GRID_WIDTH, (mPointCount + PN_POINTS_GRID_WIDTH - 1) / PN_POINTS_GRID_WIDTH, PN_SCREEN_GROUP);
    return;
  }
  PN_ASSERT(mVisibility != nullptr);
  mVisibility->bindImage(PN_IMG_VISIBILITY, GL_WRITE_ONLY);
  dispatch2D(program, mScreen.x, mScreen.y, PN_SCREEN_GROUP);
}

void FrameContext::dispatch2D(const gl::Program& program, int width, int height, int group) {
  program.use();
  glDispatchCompute(static_cast<GLuint>((width + group - 1) / group), static_cast<GLuint>((height + group - 1) / group), 1);
  glMemoryBarrier(GL_ALL_BARRIER_BITS);
}

}  // namespace penumbra
