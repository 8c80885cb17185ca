#pragma once
// Summed-area tables of depth moments (vssm, msm-soft): a two-level scan over horizontal bands of
// rows in three compute dispatches (band column totals, their scan down the bands, then each band
// scanned in 2D from its carried-in sums: passes/sat_scan.comp.glsl), in exact 64-bit fixed point
// (common/sat.glsl states the precision strategy and the layout). Any box mean of z, z² (and z³,
// z⁴) is then four corner reads: O(1) whatever the box's size. The table is a storage buffer: on
// llvmpipe an RGBA32UI image store cost more than the rest of the build together.
#include "gl/Objects.h"

namespace penumbra {

class ShaderLibrary;

class SatBuilder {
public:
  /// Builds the tables of the first `momentCount` (2 or 4) powers of the linear depth found in
  /// channel r of every layer of `depth` (a 2D array texture: a depth map or a float map).
  void build(ShaderLibrary& shaders, const gl::Texture& depth, int momentCount);
  /// uvec4 per texel and layer (common/sat.glsl's satIndex), layer view·pairs() + k: moments
  /// 2k+1, 2k+2 as 64-bit (lo, hi) words.
  const gl::Buffer& table() const { return mTable; }
  /// Binds the table where common/sat.glsl reads it (PN_SSBO_SAT).
  void bindTable() const;
  int pairs() const { return mPairs; }
  int width() const { return mWidth; }
  int height() const { return mHeight; }
  int layers() const { return mLayers; }  ///< views · pairs()
  /// Bytes a build must move per texel of a map `height` texels tall (a lower bound: every byte
  /// read or written once): the map read by two passes (4 B each), the table written (16 B per
  /// pair), the band carries written, scanned and read (4 · 16 B per pair per band column).
  static double trafficBytesPerTexel(int momentCount, int height);

private:
  gl::Buffer mTable;
  gl::Buffer mCarry;  // per view, band, column and pair: a band's column total, then its top carry
  int mPairs = 0, mWidth = 0, mHeight = 0, mLayers = 0;
};

}  // namespace penumbra
