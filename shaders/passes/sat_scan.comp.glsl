// Summed-area table build (SatBuilder): one dispatch scans every row, a second every column, in
// place. Each work group scans SAT_LINES lines (rows or columns) with SAT_THREADS threads per line,
// in chunks of SAT_THREADS · SAT_PER_THREAD elements:
//   1. each thread loads SAT_PER_THREAD consecutive elements and scans them serially (registers);
//   2. the threads' totals are scanned in shared memory with the work-efficient up-sweep /
//      down-sweep (Blelloch) exclusive scan: 2(T - 1) additions for T threads, 2 log2 T barriers;
//   3. each thread adds its exclusive offset and the running total of earlier chunks and stores.
// Every element is read once and written once per axis. Sums are 64-bit fixed point (sat.glsl).
// Defines: SAT_AXIS 0 = rows, reading linear depth from s_depth and forming the moments; 1 =
// columns, in place on i_sat. SAT_PAIRS: moment pairs per texel (1: z, z^2; 2: z..z^4).
#extension GL_ARB_gpu_shader_int64 : enable
#ifdef GL_ARB_gpu_shader_int64
#define PN_NATIVE_INT64 1  // 64-bit additions in hardware words where the driver has them
#endif
#include "shared/Bindings.h"
#include "common/sat.glsl"

layout(local_size_x = SAT_LINES, local_size_y = SAT_THREADS) in;
layout(binding = PN_TEX_FILTER0) uniform sampler2DArray s_depth;
layout(binding = PN_IMG_AUX0, rgba32ui) uniform uimage2DArray i_sat;

shared uvec4 s_scan[SAT_PAIRS][SAT_THREADS][SAT_LINES];
shared uvec4 s_chunkTotal[SAT_PAIRS][SAT_LINES];

const int kChunk = SAT_THREADS * SAT_PER_THREAD;

ivec3 texelOf(int line, int pos, int layer) {
  return SAT_AXIS == 0 ? ivec3(pos, line, layer) : ivec3(line, pos, layer);
}

void main() {
  ivec2 size = imageSize(i_sat).xy;
  int l = int(gl_LocalInvocationID.x);
  int tid = int(gl_LocalInvocationID.y);
  int line = int(gl_WorkGroupID.x) * SAT_LINES + l;
  int view = int(gl_WorkGroupID.z);
  int lineCount = SAT_AXIS == 0 ? size.y : size.x;
  int lineLength = SAT_AXIS == 0 ? size.x : size.y;
  bool lineValid = line < lineCount;  // no early return: every thread must reach the barriers

  uvec4 carry[SAT_PAIRS];
  for (int p = 0; p < SAT_PAIRS; ++p) carry[p] = uvec4(0u);

  for (int base = 0; base < lineLength; base += kChunk) {
    // 1. Serial inclusive scan of this thread's elements.
    uvec4 prefix[SAT_PER_THREAD][SAT_PAIRS];
    uvec4 run[SAT_PAIRS];
    for (int p = 0; p < SAT_PAIRS; ++p) run[p] = uvec4(0u);
    for (int e = 0; e < SAT_PER_THREAD; ++e) {
      int pos = base + tid * SAT_PER_THREAD + e;
      bool inside = lineValid && pos < lineLength;
#if SAT_AXIS == 0
      uint z = inside ? depthToFixed(texelFetch(s_depth, texelOf(line, pos, view), 0).r) : 0u;
      uint zk = z;  // z^(2p+1) in fixed point
#endif
      for (int p = 0; p < SAT_PAIRS; ++p) {
#if SAT_AXIS == 0
        uint zk1 = fixedMul(zk, z);
        uvec4 v = uvec4(zk, 0u, zk1, 0u);
        zk = fixedMul(zk1, z);
#else
        uvec4 v = inside ? imageLoad(i_sat, texelOf(line, pos, view * SAT_PAIRS + p)) : uvec4(0u);
#endif
        run[p] = add64x2(run[p], v);
        prefix[e][p] = run[p];
      }
    }
    for (int p = 0; p < SAT_PAIRS; ++p) s_scan[p][tid][l] = run[p];
    memoryBarrierShared();
    barrier();

    // 2. Blelloch exclusive scan of the SAT_THREADS totals: up-sweep builds partial sums in a
    // balanced tree, down-sweep distributes them back as exclusive prefixes.
    for (int d = 1; d < SAT_THREADS; d <<= 1) {
      if (((tid + 1) & (2 * d - 1)) == 0)
        for (int p = 0; p < SAT_PAIRS; ++p) s_scan[p][tid][l] = add64x2(s_scan[p][tid][l], s_scan[p][tid - d][l]);
      memoryBarrierShared();
      barrier();
    }
    if (tid == SAT_THREADS - 1) {
      for (int p = 0; p < SAT_PAIRS; ++p) {
        s_chunkTotal[p][l] = s_scan[p][tid][l];
        s_scan[p][tid][l] = uvec4(0u);
      }
    }
    memoryBarrierShared();
    barrier();
    for (int d = SAT_THREADS / 2; d >= 1; d >>= 1) {
      if (((tid + 1) & (2 * d - 1)) == 0) {
        for (int p = 0; p < SAT_PAIRS; ++p) {
          uvec4 left = s_scan[p][tid - d][l];
          s_scan[p][tid - d][l] = s_scan[p][tid][l];
          s_scan[p][tid][l] = add64x2(s_scan[p][tid][l], left);
        }
      }
      memoryBarrierShared();
      barrier();
    }

    // 3. Offsets: earlier chunks (carry) + earlier threads of this chunk.
    for (int p = 0; p < SAT_PAIRS; ++p) {
      uvec4 offset = add64x2(carry[p], s_scan[p][tid][l]);
      for (int e = 0; e < SAT_PER_THREAD; ++e) {
        int pos = base + tid * SAT_PER_THREAD + e;
        if (lineValid && pos < lineLength) imageStore(i_sat, texelOf(line, pos, view * SAT_PAIRS + p), add64x2(offset, prefix[e][p]));
      }
      carry[p] = add64x2(carry[p], s_chunkTotal[p][l]);
    }
    memoryBarrierShared();
    barrier();  // the next chunk overwrites s_scan and s_chunkTotal
  }
}
