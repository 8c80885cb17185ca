// A plain copy of level 0 of a texture array into a twin, one imageLoad and one imageStore per
// texel and nothing else: the bandwidth floor that the bench's micro-benchmarks set the prefilter
// builders against (bench/MicroBenchmarks.cpp). COPY_FORMAT: rg32f or rgba32f. COPY_BUFFER 1 instead copies a storage buffer of uvec4 (a
// summed-area table, common/sat.glsl) into another, one load and one store per element; its groups
// form rows of gl_NumWorkGroups.x (one row of groups could not hold a 2048² table: at most 65535).
#include "shared/Bindings.h"

#if COPY_BUFFER
layout(local_size_x = 64) in;
layout(std430, binding = PN_SSBO_AUX) readonly buffer CopyIn { uvec4 b_in[]; };
layout(std430, binding = PN_SSBO_SAT) writeonly buffer CopyOut { uvec4 b_out[]; };

void main() {
  uint i = gl_GlobalInvocationID.y * gl_NumWorkGroups.x * gl_WorkGroupSize.x + gl_GlobalInvocationID.x;
  if (i < uint(b_in.length())) b_out[i] = b_in[i];
}
#else
layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = PN_IMG_AUX0, COPY_FORMAT) uniform readonly image2DArray i_in;
layout(binding = PN_IMG_AUX1, COPY_FORMAT) uniform writeonly image2DArray i_out;

void main() {
  ivec3 p = ivec3(gl_GlobalInvocationID);
  if (any(greaterThanEqual(p.xy, imageSize(i_in).xy))) return;
  imageStore(i_out, p, imageLoad(i_in, p));
}
#endif
