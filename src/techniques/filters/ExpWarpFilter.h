#pragma once
// The exp-warp family (esm, evsm, evsm-soft): what its three filters share, written once. Each
// draws exponentially warped maps of its own warp (ExpWarpMaps: the shadow pass, the storage),
// prefilters them with a mip chain, reads them trilinearly at PN_TEX_FILTER0 and shows the
// shadow map and the moments. A member gives its warp (from its parameters), its uniform block
// and its visibility pass; its own math lives in that pass (esm.glsl, evsm.glsl, evsm_soft.glsl
// over common/exp_warp.glsl).
#include "frame/Filter.h"
#include "shader/ShaderLibrary.h"
#include "techniques/filters/ExpWarpMaps.h"

#include <span>
#include <string_view>
#include <vector>

namespace penumbra {

class ExpWarpFilter : public Filter {
public:
  /// Draws the maps of this frame's warp().
  void renderShadowMaps(FrameContext& frame) final;
  /// Rebuilds the mip chain. A member that prefilters more calls this first.
  void prefilter(FrameContext& frame) override;
  /// The shadow map and the moments. A member with more images appends to these.
  std::vector<DebugImage> debugImages() const override;

protected:
  /// `mapLabel` names the maps' GL objects; `momentsMeaning` says what the moments image holds.
  ExpWarpFilter(std::span<const ParamDesc> params, std::string_view mapLabel, std::string_view momentsMeaning)
      : Filter(params), mMapLabel(mapLabel), mMomentsMeaning(momentsMeaning) {}
  /// This frame's warp, from the member's parameters (its exponents within the storage's limit).
  virtual ExpWarpMaps::Warp warp(const FrameContext& frame) const = 0;
  /// Binds the moments for filtering and runs the member's visibility pass `filterFile` (its
  /// uniform block already set).
  void dispatchVisibility(FrameContext& frame, std::string_view filterFile, const ShaderDefines& defines = {}) const;
  const ExpWarpMaps& maps() const { return mMaps; }

private:
  std::string_view mMapLabel, mMomentsMeaning;
  ExpWarpMaps mMaps;
};

}  // namespace penumbra
