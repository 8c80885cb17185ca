// A plain copy of level 0 of a texture array into a twin, one imageLoad and one imageStore per
// texel and nothing else: the bandwidth floor that the bench's micro-benchmarks set the prefilter
// builders against (report/MicroBenchmarks.cpp). COPY_FORMAT: rg32f, rgba32f or rgba32ui
// (COPY_UINT 1 for the integer one).
#include "shared/Bindings.h"

layout(local_size_x = 8, local_size_y = 8) in;
#if COPY_UINT
layout(binding = PN_IMG_AUX0, COPY_FORMAT) uniform readonly uimage2DArray i_in;
layout(binding = PN_IMG_AUX1, COPY_FORMAT) uniform writeonly uimage2DArray i_out;
#else
layout(binding = PN_IMG_AUX0, COPY_FORMAT) uniform readonly image2DArray i_in;
layout(binding = PN_IMG_AUX1, COPY_FORMAT) uniform writeonly image2DArray i_out;
#endif

void main() {
  ivec3 p = ivec3(gl_GlobalInvocationID);
  if (any(greaterThanEqual(p.xy, imageSize(i_in).xy))) return;
  imageStore(i_out, p, imageLoad(i_in, p));
}
