#pragma once
// The tight blocker search shared by the filters that search for blockers (pcss, vssm,
// msm-soft; common/penumbra.glsl: blockerSearchRegionUv): each declares the parameter from
// tightSearchParam, builds the map's min-depth pyramid in its prefilter step and, for the
// visibility dispatch, turns the search on with bind. Off, the search covers the near plane's
// footprint and nothing is built.
#include "frame/MinDepthPyramid.h"

#include <penumbra/Params.h>

#include <string_view>

namespace penumbra {

class FrameContext;
class ShaderDefines;

/// "<filter>.tightSearch", off/on, default on.
constexpr ParamDesc tightSearchParam(std::string_view key) {
  return {key, "Tight search",
          "on: the blocker search covers the light's footprint at the nearest surface inside the near-plane region (a "
          "min-depth pyramid of the map), not on the near plane; off: the near plane's footprint, where a small blocker "
          "in a large region is lost", "",
          1.0f, 0.0f, 1.0f, 1.0f, kOffOn};
}

class TightSearch {
public:
  /// Prefilter step: rebuilds the pyramid of `map` (linear depth in channel r) when `on`. A paged
  /// map (FrameContext::paged) is a pool of tiles: its pyramid holds the levels inside one tile
  /// (a page's own pyramid, up to one texel a page; common/shadow.glsl: pagedMinDepthOverBox)
  /// and is rebuilt only in a frame that drew a page or with a new pool.
  void build(FrameContext& frame, bool on, const gl::Texture& map);
  /// Before the visibility dispatch: when `on` and built, sets PN_TIGHT_SEARCH and binds the pyramid at
  /// PN_TEX_MIN_DEPTH, where common/penumbra.glsl reads it.
  void bind(bool on, ShaderDefines& defines) const;

private:
  MinDepthPyramid mPyramid;
  bool mBuilt = false;
  GLuint mPool = 0;  // the pool the pyramid was last built over (paged maps)
};

}  // namespace penumbra
