// The pixel-bounds reduction (frame/PixelBoundsReducer): every covered pixel that faces the light
// (the pixels the visibility pass will look up) is taken to u_bounds.spaceFromWorld and added to
// the box of each camera-depth slice that holds its depth. A workgroup reduces its 64 pixels in
// shared memory, then one invocation per slice and bound merges them into the storage block with
// one atomic each: floats as order-keeping uints (pixelBoundsKey), so unsigned min/max is float
// min/max. The surfaces are read as the visibility pass reads them (surfaceDefines: a depth
// texture, normals rebuilt from positions, an orthographic camera).
#include "common/visibility.glsl"
#include "shared/PixelBounds.h"

layout(local_size_x = PN_SCREEN_GROUP, local_size_y = PN_SCREEN_GROUP) in;
layout(std140, binding = PN_UBO_FILTER) uniform PixelBoundsBlock { PixelBoundsUniforms u_bounds; };
layout(std430, binding = PN_SSBO_AUX) buffer BoundsBlock { uint o_bounds[]; };

const int kGroupSize = PN_SCREEN_GROUP * PN_SCREEN_GROUP;
shared uint s_keys[kGroupSize][PN_PIXEL_BOUNDS_WORDS];

// A float as a uint whose unsigned order is the float's order (negative floats flipped whole,
// positive ones with the sign bit set).
uint pixelBoundsKey(float f) {
  uint u = floatBitsToUint(f);
  return (u & 0x80000000u) != 0u ? ~u : u | 0x80000000u;
}

const uint kEmptyMin = 0xFFFFFFFFu;  // no pixel yet: larger than every key
const uint kEmptyMax = 0u;

float sliceBound(vec4 bounds[2], int i) { return bounds[i / 4][i % 4]; }

void main() {
  ivec2 px = ivec2(gl_GlobalInvocationID.xy);
  int local = int(gl_LocalInvocationIndex);
  bool inside = all(lessThan(px, u_frame.screen.xy));
  vec3 p = vec3(0.0);
  float depth = 0.0;
  bool counted = false;
  if (inside) {
    vec4 pos = surfacePosition(px);
    if (pos.w > 0.5) {
      vec3 n = surfaceGeoNormal(px, pos.xyz);
      counted = dot(n, toLight(pos.xyz)) > 0.0;
      p = (u_bounds.spaceFromWorld * vec4(pos.xyz, 1.0)).xyz;
      depth = cameraViewDepth(pos.xyz);
    }
  }
  for (int slice = 0; slice < u_bounds.info.x; ++slice) {
    bool in_ = counted && depth >= sliceBound(u_bounds.sliceNear, slice) && depth <= sliceBound(u_bounds.sliceFar, slice);
    for (int a = 0; a < 3; ++a) {
      s_keys[local][a] = in_ ? pixelBoundsKey(p[a]) : kEmptyMin;
      s_keys[local][3 + a] = in_ ? pixelBoundsKey(p[a]) : kEmptyMax;
    }
    barrier();
    for (int stride = kGroupSize / 2; stride > 0; stride /= 2) {
      if (local < stride)
        for (int w = 0; w < PN_PIXEL_BOUNDS_WORDS; ++w)
          s_keys[local][w] = w < 3 ? min(s_keys[local][w], s_keys[local + stride][w]) : max(s_keys[local][w], s_keys[local + stride][w]);
      barrier();
    }
    if (local < PN_PIXEL_BOUNDS_WORDS) {
      uint key = s_keys[0][local];
      uint at = uint(slice * PN_PIXEL_BOUNDS_WORDS + local);
      if (local < 3 && key != kEmptyMin) atomicMin(o_bounds[at], key);
      if (local >= 3 && key != kEmptyMax) atomicMax(o_bounds[at], key);
    }
    barrier();
  }
}
