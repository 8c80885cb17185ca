#pragma once
// The moment family (vsm, vssm, msm, msm-soft): the maps its filters share, written once. Region
// means of depth moments come from one of two sources:
//  mips: the moments themselves (passes/moments.frag.glsl: (z, z² + the slope's variance) or
//    (z, z², z³, z⁴), optionally in msm's 16-bit basis) in a full mip chain, cleared to the far
//    plane's moments, read trilinearly at PN_TEX_FILTER0 (vsm, vssm with source=mip, msm);
//  sat: the linear depth alone and a summed-area table of its powers in exact fixed point
//    (SatBuilder, read by common/sat.glsl) (vssm with source=sat, msm-soft).
// A member gives its moment count and source; its own math lives in its visibility pass.
#include "frame/Filter.h"
#include "frame/SatBuilder.h"
#include "frame/ShadowMaps.h"

#include <string_view>
#include <vector>

namespace penumbra {

class FrameContext;

class MomentMaps {
public:
  enum class Source { Mips, Sat };
  struct Moments {
    int count = 2;               ///< 2: (z, z²); 4: (z, z², z³, z⁴)
    Source source = Source::Mips;
    bool quantized = false;      ///< 4 moments from mips only: msm's optimised 16-bit basis (RGBA16)
  };
  /// Draws every view's maps for `moments` (the mips' level 0, or the depth the table is built from).
  void render(FrameContext& frame, std::string_view label, const Moments& moments);
  /// Builds the mip chain or the summed-area table from what render() drew.
  void prefilter(FrameContext& frame);
  /// Binds the source where the visibility pass reads it: the moments, trilinear, at
  /// PN_TEX_FILTER0, or the table at PN_SSBO_SAT.
  void bind() const;
  /// The texture whose channel r holds the linear light depth (a min-depth pyramid's input): the
  /// depth with a table, the moments (z first) with mips.
  const gl::Texture& linearDepth() const;
  /// The shadow map, and the moments (`momentsMeaning`) when they are drawn (source mips).
  std::vector<DebugImage> debugImages(std::string_view momentsMeaning) const;

private:
  Moments mMoments;
  ShadowMapArray mMaps;
  SatBuilder mSat;
};

}  // namespace penumbra
