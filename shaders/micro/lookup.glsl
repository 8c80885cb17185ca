// The minimal lookup kernels (bench/VisibilityBaselines.cpp): per pixel, what a filter's
// visibility cannot do without — read the G-buffer position, apply one matrix, do the filter's
// taps and its closing arithmetic, store V — and nothing else: no view selection or cascade blend,
// no N·L, no bias geometry (one constant bias), no edge handling beyond clamping. The bench times
// each next to the real visibility pass of its filter on the same G-buffer and map; their ratio
// is the pass's overhead over its own arithmetic (docs/bench.md). LOOKUP_KIND: a PN_LOOKUP_*
// (micro/lookup.shared.h); LOOKUP_SIDE: the box's taps per side (the Poisson disk's: its square
// root); LOOKUP_FOOTPRINT: the moments' tap is the pixel's footprint; LOOKUP_RAYS and LOOKUP_STEPS:
// the march's rays and steps per ray.
#include "shared/Bindings.h"
#include "micro/lookup.shared.h"

layout(std140, binding = PN_UBO_FILTER) uniform LookupBlock { LookupUniforms u_lookup; };
layout(location = 0) out float o_visibility;  // drawn, as the visibility pass is (frame/ScreenTarget.h)

// Functions only, besides the G-buffer's samplers (common/visibility.glsl, through footprint.glsl:
// the kernel reads s_gbufPosition, and s_gbufGeoNormal for the footprint) and sat.glsl's read-only
// table (bound only for the SAT kind); the frame and shadow blocks they declare are not read.
// Included whatever the kind: the include expander honours #pragma once, not #if.
#include "common/footprint.glsl"
#include "common/moments.glsl"
#include "common/sampling.glsl"
#include "common/sat.glsl"

#if LOOKUP_KIND == PN_LOOKUP_SAT
#elif LOOKUP_KIND == PN_LOOKUP_BOX && defined(PN_HARDWARE_COMPARE)
layout(binding = PN_TEX_FILTER0) uniform sampler2DArrayShadow s_map;
#else
layout(binding = PN_TEX_FILTER0) uniform sampler2DArray s_map;
#endif

#if LOOKUP_KIND == PN_LOOKUP_COMPARE || LOOKUP_KIND == PN_LOOKUP_POISSON || LOOKUP_KIND == PN_LOOKUP_MARCH || \
    (LOOKUP_KIND == PN_LOOKUP_BOX && !defined(PN_HARDWARE_COMPARE))
float fetchCompare(vec2 uv, float depth) {
  ivec2 size = textureSize(s_map, 0).xy;
  ivec2 texel = clamp(ivec2(uv * vec2(size)), ivec2(0), size - 1);
  return depth <= texelFetch(s_map, ivec3(texel, 0), 0).r ? 1.0 : 0.0;
}
#endif

#if LOOKUP_KIND == PN_LOOKUP_MOMENTS2 || LOOKUP_KIND == PN_LOOKUP_MOMENTS4
#ifdef LOOKUP_FOOTPRINT
// The map-uv step of one pixel along rayStep on the plane through ws with normal n: the camera ray
// through the neighbouring pixel met with that plane (common/footprint.glsl's ray differentials).
vec2 footprintStep(vec3 ws, vec3 n, vec2 uv, vec3 rayStep) {
  vec3 o = u_lookup.cameraPosition.xyz;
  vec3 d = (ws - o) / dot(ws - o, u_lookup.cameraForward.xyz) + rayStep;
  float dn = dot(d, n);
  float t = abs(dn) > 1e-6 ? dot(ws - o, n) / dn : -1.0;
  vec4 c = u_lookup.mapFromWorld * vec4(t > 0.0 ? o + t * d : ws, 1.0);
  return c.xy / c.w - uv;
}

// The moments under the pixel's footprint, as vsm and msm read them.
vec4 footprintMoments(vec2 uv, ivec2 px, vec3 ws) {
  vec3 n = normalize(texelFetch(s_gbufGeoNormal, px, 0).xyz);
  vec2 dx = footprintStep(ws, n, uv, u_lookup.rayStepX.xyz);
  vec2 dy = footprintStep(ws, n, uv, u_lookup.rayStepY.xyz);
  float mapSize = float(u_lookup.mapSize.x);
  limitFootprint(mapSize, dx, dy);
  widenFootprint(u_lookup.params.y / mapSize, dx, dy);
  return textureFootprint(s_map, vec3(uv, 0.0), dx, dy, u_lookup.mapSize.z);
}
#endif

// The moments' one filtered tap.
vec4 filteredMoments(vec2 uv, ivec2 px, vec3 ws) {
#ifdef LOOKUP_FOOTPRINT
  return footprintMoments(uv, px, ws);
#else
  return textureLod(s_map, vec3(uv, 0.0), u_lookup.params.z);
#endif
}
#endif

#if LOOKUP_KIND == PN_LOOKUP_MARCH
// smrt's taps, every pixel: LOOKUP_RAYS rays toward the sun's disk (smrt's sunflower, turned per
// pixel as smrt turns it), each LOOKUP_STEPS fetch-and-compares spaced by smrt's smoothstep from
// the receiver to the near plane (depth 0); a ray is blocked at its first step behind the map's
// surface by more than the bias. No probe, no pyramid, no thickness or crossing test.
float marchedShare(ivec2 px, vec3 ws) {
  vec3 l = u_lookup.light.xyz;
  vec3 t1 = normalize(cross(l, abs(l.y) < 0.9 ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 0.0, 0.0)));
  vec3 t2 = cross(l, t1);
  mat2 turn = pixelRotation(px, 0);
  mat4 m = u_lookup.mapFromWorld;
  vec3 depthPerM = vec3(m[0][2], m[1][2], m[2][2]);
  float depth = dot(depthPerM, ws) + m[3][2];
  int open = 0;
  for (int r = 0; r < LOOKUP_RAYS; ++r) {
    vec2 unit = turn * sunflowerDiskTap(r, LOOKUP_RAYS);
    vec3 dir = l + u_lookup.light.w * (unit.x * t1 + unit.y * t2);
    float tEnd = depth / max(-dot(depthPerM, dir), 1e-6);
    bool blocked = false;
    for (int i = 1; i <= LOOKUP_STEPS && !blocked; ++i) {
      vec4 c = m * vec4(ws + dir * (smoothstep(0.0, 1.0, float(i) / float(LOOKUP_STEPS)) * tEnd), 1.0);
      blocked = fetchCompare(c.xy / c.w, c.z - u_lookup.params.x) == 0.0;
    }
    open += blocked ? 0 : 1;
  }
  return float(open) / float(LOOKUP_RAYS);
}
#endif

float lookup(vec2 uv, float depth, ivec2 px, vec3 ws) {
  float biased = depth - u_lookup.params.x;
#if LOOKUP_KIND == PN_LOOKUP_COMPARE
  return fetchCompare(uv, biased);
#elif LOOKUP_KIND == PN_LOOKUP_BOX
  float lit = 0.0;
  for (int j = 0; j < LOOKUP_SIDE; ++j)
    for (int i = 0; i < LOOKUP_SIDE; ++i) {
      vec2 tap = uv + (vec2(i, j) - 0.5 * float(LOOKUP_SIDE - 1)) * u_lookup.params.y;
#ifdef PN_HARDWARE_COMPARE
      lit += textureGrad(s_map, vec4(tap, 0.0, biased), vec2(0.0), vec2(0.0));  // no mips: the magnified 2x2
#else
      lit += fetchCompare(tap, biased);
#endif
    }
  return lit / float(LOOKUP_SIDE * LOOKUP_SIDE);
#elif LOOKUP_KIND == PN_LOOKUP_POISSON
  mat2 turn = pixelRotation(px, 0) * u_lookup.params.y;  // frame 0: what the filter turns by when nothing accumulates
  float lit = 0.0;
  for (int i = 0; i < LOOKUP_SIDE * LOOKUP_SIDE; ++i) lit += fetchCompare(uv + turn * kPoissonDisk[i], biased);
  return lit / float(LOOKUP_SIDE * LOOKUP_SIDE);
#elif LOOKUP_KIND == PN_LOOKUP_MARCH
  return marchedShare(px, ws);
#elif LOOKUP_KIND == PN_LOOKUP_MOMENTS2
  vec2 mv = meanVariance(filteredMoments(uv, px, ws).rg, u_lookup.params.w);
  return chebyshevUpperBound(mv.x, mv.y, depth);
#elif LOOKUP_KIND == PN_LOOKUP_MOMENTS4
  vec4 b = biasMoments(filteredMoments(uv, px, ws), u_lookup.params.w);
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
  ivec2 px = ivec2(gl_FragCoord.xy);
  vec4 ws = texelFetch(s_gbufPosition, px, 0);
  float v = 1.0;
  if (ws.w > 0.5) {
    vec4 c = u_lookup.mapFromWorld * vec4(ws.xyz, 1.0);
    v = lookup(c.xy / c.w, c.z, px, ws.xyz);
  }
  o_visibility = v;
}
