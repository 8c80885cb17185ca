#include "techniques/TightSearch.h"

#include "frame/FrameContext.h"
#include "frame/VirtualPages.h"
#include "shared/Bindings.h"

#include <bit>

namespace penumbra {

void TightSearch::build(FrameContext& frame, bool on, const gl::Texture& map) {
  if (!on) {
    mBuilt = false;
    return;
  }
  if (const VirtualPages* pages = frame.pages()) {
    // Tiles sit on a grid of whole pages, so the levels up to one texel a tile never mix two
    // pages; a frame that drew no page leaves every tile, and so the pyramid, as it was.
    if (mBuilt && mPool == map.id() && pages->stats().drawn == 0) return;
    mPyramid.build(frame.shaders(), map, true, std::bit_width(static_cast<unsigned>(pages->pageSize())) - 1);
    mPool = map.id();
  } else {
    mPyramid.build(frame.shaders(), map);
    mPool = 0;
  }
  mBuilt = true;
}

void TightSearch::bind(bool on, ShaderDefines& defines) const {
  if (!on || !mBuilt) return;
  defines.set("PN_TIGHT_SEARCH");
  mPyramid.pyramid().bindUnit(PN_TEX_MIN_DEPTH);
}

}  // namespace penumbra
