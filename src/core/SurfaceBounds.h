#pragma once
// The world bounds of the surfaces the camera sees this frame, measured on the GPU and read back
// (24 bytes): what the light's views are also fitted to when the engine's receivers are not
// complete (ShadowReceivers::complete = false), so that no visible surface lies outside the maps.
#include "gl/Objects.h"
#include "shader/ShaderLibrary.h"

#include <penumbra/Math.h>

namespace penumbra::core {

class SurfaceBounds {
public:
  /// Reduces the surfaces bound at PN_TEX_GBUF_POSITION (with the frame block bound) over a
  /// screen × screen grid. `surfaceDefines`: how they are read (FrameContext::surfaceDefines).
  /// Empty when no pixel holds a surface.
  Aabb measure(ShaderLibrary& shaders, glm::ivec2 screen, const ShaderDefines& surfaceDefines);

private:
  gl::Buffer mBounds{"surface bounds", 6 * sizeof(uint32_t)};
};

}  // namespace penumbra::core
