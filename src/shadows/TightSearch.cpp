#include "shadows/TightSearch.h"

#include "frame/FrameContext.h"
#include "shared/Bindings.h"

namespace penumbra {

void TightSearch::build(FrameContext& frame, bool on, const gl::Texture& map) {
  // A paged map's storage is a pool of pages in no spatial order: no pyramid is built over it.
  mBuilt = on && !frame.paged();
  if (mBuilt) mPyramid.build(frame.shaders(), map);
}

void TightSearch::bind(bool on, ShaderDefines& defines) const {
  if (!on || !mBuilt) return;
  defines.set("PN_TIGHT_SEARCH");
  mPyramid.pyramid().bindUnit(PN_TEX_MIN_DEPTH);
}

}  // namespace penumbra
