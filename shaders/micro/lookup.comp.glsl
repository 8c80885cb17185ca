// The minimal lookup kernels (report/VisibilityBaselines.cpp): per pixel, what a filter's
// visibility cannot do without — read the G-buffer position, apply one matrix, do the filter's
// taps and its closing arithmetic, store V — and nothing else: no view selection or cascade blend,
// no N·L, no bias geometry (one constant bias), no edge handling beyond clamping. The bench times
// each next to the real visibility pass of its filter on the same G-buffer and map; their ratio
// is the pass's overhead over its own arithmetic (docs/bench.md). LOOKUP_KIND: a PN_LOOKUP_*
// (micro/lookup.shared.h); LOOKUP_SIDE: the box's taps per side.
#include "shared/Bindings.h"
#include "micro/lookup.shared.h"

layout(local_size_x = PN_SCREEN_GROUP, local_size_y = PN_SCREEN_GROUP) in;
layout(std140, binding = PN_UBO_FILTER) uniform LookupBlock { LookupUniforms u_lookup; };
layout(binding = PN_TEX_GBUF_POSITION) uniform sampler2D s_position;
layout(binding = PN_IMG_VISIBILITY, r32f) uniform writeonly image2D i_visibility;

// Functions only, besides sat.glsl's read-only table (bound only for the SAT kind). Included
// whatever the kind: the include expander honours #pragma once, not #if.
#include "common/moments.glsl"
#include "common/sat.glsl"

#if LOOKUP_KIND == PN_LOOKUP_SAT
#elif LOOKUP_KIND == PN_LOOKUP_BOX && defined(PN_HARDWARE_COMPARE)
layout(binding = PN_TEX_FILTER0) uniform sampler2DArrayShadow s_map;
#else
layout(binding = PN_TEX_FILTER0) uniform sampler2DArray s_map;
#endif

#if LOOKUP_KIND == PN_LOOKUP_COMPARE || (LOOKUP_KIND == PN_LOOKUP_BOX && !defined(PN_HARDWARE_COMPARE))
float fetchCompare(vec2 uv, float depth) {
  ivec2 size = textureSize(s_map, 0).xy;
  ivec2 texel = clamp(ivec2(uv * vec2(size)), ivec2(0), size - 1);
  return depth <= texelFetch(s_map, ivec3(texel, 0), 0).r ? 1.0 : 0.0;
}
#endif

float lookup(vec2 uv, float depth) {
  float biased = depth - u_lookup.params.x;
#if LOOKUP_KIND == PN_LOOKUP_COMPARE
  return fetchCompare(uv, biased);
#elif LOOKUP_KIND == PN_LOOKUP_BOX
  float lit = 0.0;
  for (int j = 0; j < LOOKUP_SIDE; ++j)
    for (int i = 0; i < LOOKUP_SIDE; ++i) {
      vec2 tap = uv + (vec2(i, j) - 0.5 * float(LOOKUP_SIDE - 1)) * u_lookup.params.y;
#ifdef PN_HARDWARE_COMPARE
      lit += texture(s_map, vec4(tap, 0.0, biased));
#else
      lit += fetchCompare(tap, biased);
#endif
    }
  return lit / float(LOOKUP_SIDE * LOOKUP_SIDE);
#elif LOOKUP_KIND == PN_LOOKUP_MOMENTS2
  vec2 mv = meanVariance(textureLod(s_map, vec3(uv, 0.0), u_lookup.params.z).rg, u_lookup.params.w);
  return chebyshevUpperBound(mv.x, mv.y, depth);
#elif LOOKUP_KIND == PN_LOOKUP_MOMENTS4
  vec4 b = biasMoments(textureLod(s_map, vec3(uv, 0.0), u_lookup.params.z), u_lookup.params.w);
  return 1.0 - hamburgerShadowIntensity(b, depth);
#else
  ivec2 size = u_lookup.mapSize.xy;
  vec2 lo, hi;
  satCentredBox(size, uv * vec2(size), vec2(u_lookup.params.z), lo, hi);
  vec2 mv = satMeanVariance(satBoxMean(size, lo, hi, 0));
  return chebyshevUpperBound(mv.x, max(mv.y, u_lookup.params.w), depth);
#endif
}

void main() {
  ivec2 px = ivec2(gl_GlobalInvocationID.xy);
  ivec2 screen = textureSize(s_position, 0);
  if (any(greaterThanEqual(px, screen))) return;
  vec4 ws = texelFetch(s_position, px, 0);
  float v = 1.0;
  if (ws.w > 0.5) {
    vec4 c = u_lookup.mapFromWorld * vec4(ws.xyz, 1.0);
    v = lookup(c.xy / c.w, c.z);
  }
  imageStore(i_visibility, px, vec4(v));
}
