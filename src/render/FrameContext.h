#pragma once
// What a Filter may use during a frame: the scene, the light's views, the shader library, the
// caster draw, the G-buffer-bound full-screen dispatch and its own uniform block. Filters never
// touch the renderer's internals; the renderer never asks which filter it runs.
#include "gl/Objects.h"
#include "render/PassTimer.h"
#include "render/ShadowMaps.h"
#include "shader/ShaderLibrary.h"

#include <penumbra/Projection.h>
#include <penumbra/Scene.h>

#include <glm/glm.hpp>
#include <string_view>

namespace penumbra {

class GpuScene;

class FrameContext {
public:
  FrameContext(const Scene& scene, const LightFrusta& frusta, int mapSize, glm::ivec2 screen,
               ShaderLibrary& shaders, const GpuScene& gpuScene, gl::Buffer& filterBlock, PassTimer& timer,
               const gl::Texture* visibility)
      : mScene(scene), mFrusta(frusta), mMapSize(mapSize), mScreen(screen), mShaders(shaders),
        mGpuScene(gpuScene), mFilterBlock(filterBlock), mTimer(timer), mVisibility(visibility) {}

  const Scene& scene() const { return mScene; }
  const Light& light() const { return mScene.light(); }
  const LightFrusta& frusta() const { return mFrusta; }
  int viewCount() const { return static_cast<int>(mFrusta.views.size()); }
  int mapSize() const { return mMapSize; }
  glm::ivec2 screen() const { return mScreen; }
  ShaderLibrary& shaders() { return mShaders; }
  PassTimer& timer() { return mTimer; }

  const gl::Program& program(const ProgramDesc& desc) { return mShaders.program(desc); }
  /// Shadow-pass program: passes/geometry.vert.glsl + `fragment` (default: linear depth only).
  const gl::Program& shadowProgram(std::string_view fragment = "passes/shadow_depth.frag.glsl",
                                   const ShaderDefines& defines = {});
  /// Visibility program: the filter's GLSL file (defining shadowVisibility) + the pass's main.
  const gl::Program& visibilityProgram(std::string_view filterFile, const ShaderDefines& defines = {});

  /// Renders every view into its layer of `maps` with `program`: depth cleared to 1 (far),
  /// colour cleared to `clearColor`; depth test LESS, depth clamp on (casters in front of the
  /// near plane still cast), no culling (thin and open casters cast from both sides).
  void renderViews(ShadowMapArray& maps, const gl::Program& program, const glm::vec4& clearColor = glm::vec4(1.0f));
  /// Draws every shadow caster into the bound framebuffer for shadow view `view`.
  void drawCasters(const gl::Program& program, int view) const;

  /// Uploads the filter's uniform block (bound at PN_UBO_FILTER for the rest of the frame).
  template <class T> void setFilterBlock(const T& block) { setFilterBlockBytes(&block, sizeof(T)); }
  void setFilterBlockBytes(const void* data, size_t bytes);

  /// Binds the G-buffer and the visibility image, then runs `program` once per pixel.
  /// In points mode (setPoints), runs it once per point instead (see visibilityProgram).
  void dispatchScreen(const gl::Program& program) const;

  /// Points mode, used by Renderer::visibilityAt: visibilityProgram() compiles the pass with
  /// PN_VISIBILITY_POINTS (positions from `points`, a PointBlock of shared/VisibilityPoints.h,
  /// V into `visibility`, one float per point) and dispatchScreen() runs over the points. A
  /// filter needs no code for it as long as its visibility goes through those two calls.
  void setPoints(const gl::Buffer* points, const gl::Buffer* visibility, int count) {
    mPoints = points;
    mPointVisibility = visibility;
    mPointCount = count;
  }
  /// True in points mode: there is no screen, so per-pixel debug outputs are left alone.
  bool pointsMode() const { return mPoints != nullptr; }
  /// Runs `program` over a width × height grid in groups of `group`².
  static void dispatch2D(const gl::Program& program, int width, int height, int group);

private:
  const Scene& mScene;
  const LightFrusta& mFrusta;
  int mMapSize;
  glm::ivec2 mScreen;
  ShaderLibrary& mShaders;
  const GpuScene& mGpuScene;
  gl::Buffer& mFilterBlock;
  PassTimer& mTimer;
  const gl::Texture* mVisibility;
  const gl::Buffer* mPoints = nullptr;
  const gl::Buffer* mPointVisibility = nullptr;
  int mPointCount = 0;
};

}  // namespace penumbra
