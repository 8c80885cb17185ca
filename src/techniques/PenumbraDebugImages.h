#pragma once
// The "blocker-depth" and "penumbra-width-m" debug images of the filters that estimate a
// penumbra from an average blocker depth (pcss, vssm): two screen-sized R32F textures that the
// filter's visibility shader fills through common/penumbra_debug.glsl. Values and the "none"
// sentinel are described in shared/PenumbraDebug.h.
#include "gl/Objects.h"

#include "frame/Filter.h"

#include <glm/glm.hpp>
#include <vector>

namespace penumbra {

class FrameContext;

class PenumbraDebugImages {
public:
  /// Before the filter's visibility dispatch: (re)creates the images when the screen size
  /// changed (no GL object otherwise), clears them to PN_PENUMBRA_DEBUG_NONE and binds them at
  /// PN_IMG_BLOCKER_DEPTH / PN_IMG_PENUMBRA_WIDTH. Does nothing in points mode, so
  /// Renderer::visibilityAt keeps the last frame's images.
  void bind(const FrameContext& frame);
  /// "blocker-depth" (linear light depth in [0,1]) and "penumbra-width-m" (metres on the
  /// receiver); both -1 where no blocker was found or the pixel was not searched.
  std::vector<DebugImage> debugImages() const;

private:
  gl::Texture mBlockerDepth, mPenumbraWidth;
};

}  // namespace penumbra
