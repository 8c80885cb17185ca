// Summed-area table build (SatBuilder): a two-level scan over horizontal bands of SAT_BAND rows.
// S(x, y) = C(x, y0) + B(x, y), where C(x, y0) is the table's value just above the band (the sum
// of every texel above the band with x' <= x) and B the band's own 2D prefix sum. Three dispatches:
//   SAT_PASS 0, one thread per SAT_PER_THREAD columns and band: the band's column totals (reads the
//     map once);
//   SAT_PASS 1, one thread per column: an exclusive scan of those totals down the bands, in place,
//     so each band gets, per column, the sum of the texels above it (its "top carry");
//   SAT_PASS 2, one work group per band and view: SAT_THREADS threads, each owning SAT_PER_THREAD
//     adjacent columns of a chunk of SAT_THREADS * SAT_PER_THREAD columns, walk the band in blocks
//     of SAT_ROWS rows. Per block: (a) each thread adds the rows to its running column sums
//     (seeded with the top carry), scans them serially along the row and keeps those partial sums; (b) SAT_ROWS threads scan one row's SAT_THREADS segment totals each
//     (exclusive, from the row's carry out of earlier chunks) in shared memory; (c) each thread
//     stores S = its segment's offset + its partial sums. Everything is linear in the texel count
//     (work-efficient); 2 barriers per block (the segment totals are double-buffered).
// Passes 0 and 2 read the map in 2x2 texel gathers (one fetch per 4 texels; on llvmpipe the build
// went from 1.4-1.8x to 1.4-1.5x a copy), so SAT_BAND, SAT_ROWS and SAT_PER_THREAD are even (SatBuilder asserts it).
// Traffic per texel: the map is read by pass 0 and pass 2 (4 B each), the table written once (16 B
// per pair), the carries 4 * 16 B per pair per SAT_BAND texels. The table is a storage buffer
// (common/sat.glsl gives its layout): a plain store, where an RGBA32UI imageStore measured more
// than the rest of the pass on llvmpipe, whose storage-buffer and shared-memory accesses are a loop
// over the SIMD lanes, one scalar per 32-bit word (64-bit words measured slower): pass 2's table
// stores are 0.7 of a copy's time of the same map, (b) 0.14 (SatBuilder.cpp's ScanShape). Sums are
// exact 64-bit fixed point (sat.glsl). SAT_PAIRS: moment pairs per texel (1: z, z^2; 2: z..z^4),
// table layer view * SAT_PAIRS + p.
#extension GL_ARB_gpu_shader_int64 : enable
#ifdef GL_ARB_gpu_shader_int64
#define PN_NATIVE_INT64 1  // 64-bit additions in hardware words where the driver has them
#endif
#define PN_SAT_WRITER 1  // this shader declares the table buffer itself, write-only
#include "shared/Bindings.h"
#include "common/sat.glsl"

layout(local_size_x = SAT_THREADS) in;
layout(binding = PN_TEX_FILTER0) uniform sampler2DArray s_depth;
layout(std430, binding = PN_SSBO_SAT) writeonly buffer SatTable { uvec4 b_sat[]; };
// Per view, band, column and pair: the band's column total (pass 0), then its top carry (pass 1).
layout(std430, binding = PN_SSBO_AUX) buffer SatCarry { uvec4 b_carry[]; };

// Running sums of one moment pair: native 64-bit words where the driver has them, else
// (lo, hi, lo, hi) 32-bit words with carries. Stored (carries, table) as (lo, hi, lo, hi).
#ifdef PN_NATIVE_INT64
#define Sum u64vec2
Sum sumZero() { return u64vec2(0ul); }
Sum sumAdd(Sum a, Sum b) { return a + b; }
uvec4 sumWords(Sum s) { return uvec4(unpackUint2x32(s.x), unpackUint2x32(s.y)); }
Sum sumOfWords(uvec4 w) { return u64vec2(packUint2x32(w.xy), packUint2x32(w.zw)); }
#else
#define Sum uvec4
Sum sumZero() { return uvec4(0u); }
Sum sumAdd(Sum a, Sum b) { return add64x2(a, b); }
uvec4 sumWords(Sum s) { return s; }
Sum sumOfWords(uvec4 w) { return w; }
#endif

// The fixed-point moments z^(2p+1), z^(2p+2) of one texel.
void momentsOf(float depth, out Sum v[SAT_PAIRS]) {
  uint z = depthToFixed(depth), zk = z;
  for (int p = 0; p < SAT_PAIRS; ++p) {
    uint zk1 = fixedMul(zk, z);
#ifdef PN_NATIVE_INT64
    v[p] = u64vec2(zk, zk1);
#else
    v[p] = uvec4(zk, 0u, zk1, 0u);
#endif
    zk = fixedMul(zk1, z);
  }
}

// Depths of the 2 x SAT_PER_THREAD texels at columns xs.., rows y, y + 1 (0 outside the map), by
// 2x2 gathers: one fetch per four texels.
void loadRowPair(ivec2 size, int view, int xs, int y, out float d[2][SAT_PER_THREAD]) {
  for (int c = 0; c < SAT_PER_THREAD; c += 2) {
    // The texel corner shared by (xs+c, y) .. (xs+c+1, y+1); gather order: (0,1) (1,1) (1,0) (0,0).
    vec4 g = textureGather(s_depth, vec3(vec2(xs + c + 1, y + 1) / vec2(size), float(view)));
    d[0][c] = g.w;
    d[0][c + 1] = g.z;
    d[1][c] = g.x;
    d[1][c + 1] = g.y;
  }
  for (int r = 0; r < 2; ++r)
    for (int c = 0; c < SAT_PER_THREAD; ++c)
      if (xs + c >= size.x || y + r >= size.y) d[r][c] = 0.0;
}

int bandCount(ivec2 size) { return (size.y + SAT_BAND - 1) / SAT_BAND; }
int carryIndex(ivec2 size, int view, int band, int x, int p) {
  return ((view * bandCount(size) + band) * size.x + x) * SAT_PAIRS + p;
}

#if SAT_PASS == 0
void main() {
  ivec2 size = textureSize(s_depth, 0).xy;
  int xs = int(gl_GlobalInvocationID.x) * SAT_PER_THREAD, band = int(gl_WorkGroupID.y), view = int(gl_WorkGroupID.z);
  if (xs >= size.x) return;  // no barriers in this pass
  Sum sum[SAT_PER_THREAD][SAT_PAIRS];
  for (int c = 0; c < SAT_PER_THREAD; ++c)
    for (int p = 0; p < SAT_PAIRS; ++p) sum[c][p] = sumZero();
  for (int y = band * SAT_BAND; y < min(band * SAT_BAND + SAT_BAND, size.y); y += 2) {
    float depths[2][SAT_PER_THREAD];
    loadRowPair(size, view, xs, y, depths);  // SAT_BAND is even: both rows are this band's
    for (int r = 0; r < 2; ++r)
      for (int c = 0; c < SAT_PER_THREAD; ++c) {
        Sum v[SAT_PAIRS];
        momentsOf(depths[r][c], v);
        for (int p = 0; p < SAT_PAIRS; ++p) sum[c][p] = sumAdd(sum[c][p], v[p]);
      }
  }
  for (int c = 0; c < SAT_PER_THREAD && xs + c < size.x; ++c)
    for (int p = 0; p < SAT_PAIRS; ++p) b_carry[carryIndex(size, view, band, xs + c, p)] = sumWords(sum[c][p]);
}

#elif SAT_PASS == 1
void main() {
  ivec2 size = textureSize(s_depth, 0).xy;
  int x = int(gl_GlobalInvocationID.x), view = int(gl_WorkGroupID.z);
  if (x >= size.x) return;
  for (int p = 0; p < SAT_PAIRS; ++p) {
    Sum above = sumZero();
    for (int band = 0; band < bandCount(size); ++band) {
      int i = carryIndex(size, view, band, x, p);
      Sum total = sumOfWords(b_carry[i]);
      b_carry[i] = sumWords(above);
      above = sumAdd(above, total);
    }
  }
}

#else
// (b)'s data: per block row, each thread's segment total, then its exclusive offset. Two buffers,
// alternating from block to block: a block's (a) writes the buffer that the block before last read
// in (c), two barriers ago, so (c) needs no barrier after it.
shared Sum s_segments[2][SAT_PAIRS][SAT_ROWS][SAT_THREADS];
// Per band row: the row's sum over the chunks already done (columns x' < the chunk's start).
shared Sum s_rowCarry[SAT_PAIRS][SAT_BAND];

void main() {
  ivec2 size = textureSize(s_depth, 0).xy;
  int tid = int(gl_LocalInvocationID.x), band = int(gl_WorkGroupID.y), view = int(gl_WorkGroupID.z);
  int y0 = band * SAT_BAND;
  for (int i = tid; i < SAT_PAIRS * SAT_BAND; i += SAT_THREADS) s_rowCarry[i / SAT_BAND][i % SAT_BAND] = sumZero();
  int block = 0;  // blocks done so far: the parity picks the s_segments buffer
  for (int x0 = 0; x0 < size.x; x0 += SAT_THREADS * SAT_PER_THREAD) {
    int xs = x0 + tid * SAT_PER_THREAD;  // this thread's first column
    Sum column[SAT_PER_THREAD][SAT_PAIRS];  // sum over rows y' <= the current row (whole map)
    for (int c = 0; c < SAT_PER_THREAD; ++c)
      for (int p = 0; p < SAT_PAIRS; ++p)
        column[c][p] = xs + c < size.x ? sumOfWords(b_carry[carryIndex(size, view, band, xs + c, p)]) : sumZero();
    for (int r0 = 0; r0 < SAT_BAND; r0 += SAT_ROWS, ++block) {
      int slot = block & 1;
      // (a) Segment totals of SAT_ROWS rows.
      Sum partial[SAT_ROWS][SAT_PER_THREAD][SAT_PAIRS];
      float depths[2][SAT_PER_THREAD];
      for (int r = 0; r < SAT_ROWS; ++r) {
        int y = y0 + r0 + r;
        if ((r & 1) == 0) loadRowPair(size, view, xs, y, depths);
        Sum run[SAT_PAIRS];
        for (int p = 0; p < SAT_PAIRS; ++p) run[p] = sumZero();
        for (int c = 0; c < SAT_PER_THREAD; ++c) {
          Sum v[SAT_PAIRS];
          momentsOf(depths[r & 1][c], v);
          for (int p = 0; p < SAT_PAIRS; ++p) {
            column[c][p] = sumAdd(column[c][p], v[p]);
            run[p] = sumAdd(run[p], column[c][p]);
            partial[r][c][p] = run[p];
          }
        }
        for (int p = 0; p < SAT_PAIRS; ++p) s_segments[slot][p][r][tid] = run[p];
      }
      barrier();
      // (b) One thread per row: exclusive scan of the row's segment totals, from its carry.
      if (tid < SAT_ROWS) {
        for (int p = 0; p < SAT_PAIRS; ++p) {
          Sum offset = s_rowCarry[p][r0 + tid];
          for (int t = 0; t < SAT_THREADS; ++t) {
            Sum total = s_segments[slot][p][tid][t];
            s_segments[slot][p][tid][t] = offset;
            offset = sumAdd(offset, total);
          }
          s_rowCarry[p][r0 + tid] = offset;
        }
      }
      barrier();
      // (c) Each stored S is the segment's offset plus (a)'s running sum.
      for (int r = 0; r < SAT_ROWS; ++r) {
        int y = y0 + r0 + r;
        for (int p = 0; p < SAT_PAIRS; ++p) {
          Sum offset = s_segments[slot][p][r][tid];
          int row = satIndex(size, view * SAT_PAIRS + p, ivec2(xs, y));
          for (int c = 0; c < SAT_PER_THREAD; ++c)
            if (xs + c < size.x && y < size.y) b_sat[row + c] = sumWords(sumAdd(offset, partial[r][c][p]));
        }
      }
    }
  }
}
#endif
