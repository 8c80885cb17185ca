// The world bounds of the surfaces the camera sees (the core's measured receivers, when the
// engine's receivers are not complete: ShadowReceivers). Each workgroup reduces its pixels'
// positions to a min and a max in shared memory; one invocation then folds them into six
// integers with atomics: a float's bits turned so that unsigned order is the floats' order
// (negatives flipped whole, positives with the sign bit set).
#include "common/visibility.glsl"

layout(local_size_x = PN_SCREEN_GROUP, local_size_y = PN_SCREEN_GROUP) in;
layout(std430, binding = PN_SSBO_AUX) buffer BoundsBlock { uint u_bounds[6]; };  // lo xyz, hi xyz

const int kGroupSize = PN_SCREEN_GROUP * PN_SCREEN_GROUP;
shared vec3 s_lo[kGroupSize];
shared vec3 s_hi[kGroupSize];

uint ordered(float f) {
  uint bits = floatBitsToUint(f);
  return (bits & 0x80000000u) != 0u ? ~bits : bits | 0x80000000u;
}

void main() {
  ivec2 px = ivec2(gl_GlobalInvocationID.xy);
  uint i = gl_LocalInvocationIndex;
  const float kNone = 3.4e38;  // an empty box: lo above every position, hi below
  s_lo[i] = vec3(kNone);
  s_hi[i] = vec3(-kNone);
  if (all(lessThan(px, u_frame.screen.xy))) {
    vec4 pos = surfacePosition(px);
    if (pos.w > 0.5 && all(lessThan(abs(pos.xyz), vec3(kNone)))) {
      s_lo[i] = pos.xyz;
      s_hi[i] = pos.xyz;
    }
  }
  barrier();
  for (uint stride = uint(kGroupSize) / 2u; stride > 0u; stride /= 2u) {
    if (i < stride) {
      s_lo[i] = min(s_lo[i], s_lo[i + stride]);
      s_hi[i] = max(s_hi[i], s_hi[i + stride]);
    }
    barrier();
  }
  if (i != 0u || s_lo[0].x > s_hi[0].x) return;
  for (int a = 0; a < 3; ++a) {
    atomicMin(u_bounds[a], ordered(s_lo[0][a]));
    atomicMax(u_bounds[3 + a], ordered(s_hi[0][a]));
  }
}
