#pragma once
// Summed-area tables of depth moments (vssm, msm-soft): a two-level scan over horizontal bands of
// rows in three compute dispatches (band column totals, their scan down the bands, then each band
// scanned in 2D from its carried-in sums: passes/sat_scan.comp.glsl), in exact 64-bit fixed point
// (common/sat.glsl states the precision strategy). Any box mean of z, z² (and z³, z⁴) is then four
// corner reads: O(1) whatever the box's size.
#include "gl/Objects.h"

namespace penumbra {

class ShaderLibrary;

class SatBuilder {
public:
  /// Builds the tables of the first `momentCount` (2 or 4) powers of the linear depth found in
  /// channel r of every layer of `depth` (a 2D array texture: a depth map or a float map).
  void build(ShaderLibrary& shaders, const gl::Texture& depth, int momentCount);
  /// RGBA32UI 2D array, layer view·pairs() + k: moments 2k+1, 2k+2 as 64-bit (lo, hi) words.
  const gl::Texture& table() const { return mTable; }
  int pairs() const { return mPairs; }
  /// Bytes a build must move per texel of a map `height` texels tall (a lower bound: every byte
  /// read or written once): the map read by two passes (4 B each), the table written (16 B per
  /// pair), the band carries written, scanned and read (4 · 16 B per pair per band column).
  static double trafficBytesPerTexel(int momentCount, int height);

private:
  gl::Texture mTable;
  gl::Buffer mCarry;  // per view, band, column and pair: a band's column total, then its top carry
  int mPairs = 0;
};

}  // namespace penumbra
