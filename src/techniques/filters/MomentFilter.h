#pragma once
// The moment family (vsm, vssm, msm, msm-soft): what its four filters share, written once. Each
// draws the depth moments its source needs (MomentMaps: a mip chain of 2 or 4 moments, or the
// depth and a summed-area table of its powers), prefilters them, binds them for its visibility
// pass and shows the shadow map and the moments. A member gives its moment count and source (from
// its parameters), its uniform block and its visibility pass; its own math lives in that pass
// (vsm.glsl, vssm.glsl, msm.glsl, msm_soft.glsl over common/chebyshev.glsl, common/moments.glsl
// and common/sat.glsl).
#include "frame/Filter.h"
#include "shader/ShaderLibrary.h"
#include "techniques/filters/MomentMaps.h"

#include <span>
#include <string_view>
#include <vector>

namespace penumbra {

class MomentFilter : public Filter {
public:
  /// Draws this frame's moments() into maps labelled "<id> moments" (mips) or "<id> depth" (table).
  void renderShadowMaps(FrameContext& frame) override;
  /// The mip chain or the table. A member that prefilters more calls this first.
  void prefilter(FrameContext& frame) override;
  /// The shadow map, and the moments where they are drawn. A member with more appends to these.
  std::vector<DebugImage> debugImages() const override;

protected:
  /// `momentsMeaning` says what the moments image holds (source mips).
  MomentFilter(std::span<const ParamDesc> params, std::string_view momentsMeaning)
      : Filter(params), mMomentsMeaning(momentsMeaning) {}
  /// This frame's moments, from the member's parameters.
  virtual MomentMaps::Moments moments(const FrameContext& frame) const = 0;
  /// Binds the moments or the table and runs the member's visibility pass `filterFile` (its
  /// uniform block already set).
  void dispatchVisibility(FrameContext& frame, std::string_view filterFile, const ShaderDefines& defines = {}) const;
  const MomentMaps& maps() const { return mMaps; }

private:
  std::string_view mMomentsMeaning;
  MomentMaps mMaps;
};

}  // namespace penumbra
