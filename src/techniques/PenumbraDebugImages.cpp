#include "techniques/PenumbraDebugImages.h"

#include "frame/FrameContext.h"
#include "shared/PenumbraDebug.h"

namespace penumbra {

void PenumbraDebugImages::bind(const FrameContext& frame) {
  if (frame.pointsMode()) return;
  const glm::ivec2 size = frame.screen();
  if (!mBlockerDepth || mBlockerDepth.width() != size.x || mBlockerDepth.height() != size.y) {
    mBlockerDepth = gl::Texture("blocker depth (linear light depth)", {GL_TEXTURE_2D, GL_R32F, size.x, size.y, 1, 1});
    mPenumbraWidth = gl::Texture("penumbra width (m)", {GL_TEXTURE_2D, GL_R32F, size.x, size.y, 1, 1});
    mBlockerDepth.setSampling(GL_NEAREST, GL_NEAREST);
    mPenumbraWidth.setSampling(GL_NEAREST, GL_NEAREST);
  }
  const float none = PN_PENUMBRA_DEBUG_NONE;
  glClearTexImage(mBlockerDepth.id(), 0, GL_RED, GL_FLOAT, &none);
  glClearTexImage(mPenumbraWidth.id(), 0, GL_RED, GL_FLOAT, &none);
  mBlockerDepth.bindImage(PN_IMG_BLOCKER_DEPTH, GL_WRITE_ONLY);
  mPenumbraWidth.bindImage(PN_IMG_PENUMBRA_WIDTH, GL_WRITE_ONLY);
}

std::vector<DebugImage> PenumbraDebugImages::debugImages() const {
  return {{"blocker-depth", &mBlockerDepth, "mean blocker depth, linear light depth in [0, 1]; −1 = no blocker found",
           PN_PENUMBRA_DEBUG_NONE},
          {"penumbra-width-m", &mPenumbraWidth, "penumbra width on the receiver (m); −1 = no blocker found",
           PN_PENUMBRA_DEBUG_NONE}};
}

}  // namespace penumbra
