#pragma once
// PixelBounds (frame/Projection.h) measured on the GPU: passes/pixel_bounds.comp.glsl over the
// surfaces the visibility pass will read (a world-position or a depth texture, and the geometric
// normals), keeping the covered pixels that face the frame's light; a read back of 6 floats per
// slice. The caller binds the frame block and the surfaces (`bind`) before each pass; nothing runs
// unless a projection asks.
#include "frame/FrameContext.h"
#include "gl/Objects.h"

#include "frame/Projection.h"

#include <functional>
#include <optional>

namespace penumbra {

class PixelBoundsReducer final : public PixelBounds {
public:
  /// `bind` makes the frame block (PN_UBO_FRAME: camera, light, screen) and the surfaces
  /// (PN_TEX_GBUF_POSITION, PN_TEX_GBUF_GEONORMAL) current for the pass; `unbind` undoes the
  /// surfaces' binding afterwards. Each pass is timed as "projection".
  PixelBoundsReducer(ShaderLibrary& shaders, ShaderDefines surfaceDefines, glm::ivec2 screen, const Camera& camera,
                     PassTimer& timer, std::function<void()> bind, std::function<void()> unbind);
  glm::vec2 depthRange() override;
  std::vector<Aabb> sliceBounds(const glm::mat4& spaceFromWorld, std::span<const float> sliceNearM,
                                std::span<const float> sliceFarM) override;
  /// How many passes ran (0 for a projection that asked for nothing).
  int passes() const { return mPasses; }

private:
  ShaderLibrary& mShaders;
  ShaderDefines mSurfaceDefines;  // how the surfaces are read (surfaceDefines)
  glm::ivec2 mScreen;
  glm::mat4 mViewFromWorld;
  PassTimer& mTimer;
  std::function<void()> mBind, mUnbind;
  int mPasses = 0;
  std::optional<glm::vec2> mDepthRange;
};

}  // namespace penumbra
