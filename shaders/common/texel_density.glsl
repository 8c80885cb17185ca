#pragma once
// The aliasing measure: how many screen pixels one shadow-map texel covers at a G-buffer pixel.
// With J = ∂(map texel coordinates)/∂(screen pixel), a texel covers 1/|det J| pixels (an area
// ratio): > 1 means under-sampled (one texel smeared over several pixels: blocky edges), < 1
// over-sampled. It is the square of the classic aliasing ratio d_i = d_s · (r_s cos α_i)/(r_i cos α_s)
// (Stamminger & Drettakis, Perspective Shadow Maps, 2002), measured instead of modelled. A compute
// pass has no dFdx, so J comes from the neighbouring G-buffer positions (finite differences),
// evaluated in the pixel's own cascade (a clipmap's level: virtualLevelFor).
#include "common/shadow.glsl"

// A surface seen edge-on by the light maps a texel onto a line: cap the ratio there.
const float kMaxPixelsPerTexel = 1e6;

// Continuous texel coordinates of ws in the map of `view` (warps included).
vec2 shadowTexelCoord(int view, vec3 ws) {
  vec4 c = u_shadow.views[view].clipFromWorld * vec4(ws, 1.0);
  return (c.xy / c.w * 0.5 + 0.5) * shadowMapSize();
}

// World offset of one pixel step along `step` on p's surface: of the two neighbours, the covered
// one nearer to p (the other may lie across a silhouette). False when neither is covered.
bool neighbourOffset(sampler2D positions, ivec2 px, ivec2 step, vec3 p, out vec3 offset) {
  ivec2 size = textureSize(positions, 0);
  float best = 3.4e38;
  offset = vec3(0.0);
  for (int side = -1; side <= 1; side += 2) {
    ivec2 q = px + side * step;
    if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size))) continue;
    vec4 n = texelFetch(positions, q, 0);
    if (n.w < 0.5) continue;
    vec3 d = (n.xyz - p) * float(side);
    if (length(d) < best) {
      best = length(d);
      offset = d;
    }
  }
  return best < 3.4e38;
}

// Screen pixels per shadow-map texel at pixel px of a G-buffer position texture; -1 where there
// is no geometry (or no neighbour to difference with).
float screenPixelsPerTexel(sampler2D positions, ivec2 px) {
  vec4 p = texelFetch(positions, px, 0);
  vec3 dx, dy;
  if (p.w < 0.5 || !neighbourOffset(positions, px, ivec2(1, 0), p.xyz, dx) ||
      !neighbourOffset(positions, px, ivec2(0, 1), p.xyz, dy))
    return -1.0;
#ifdef PN_VIRTUAL_PAGES
  int view = virtualLevelFor(p.xyz, cross(dx, dy));  // the level the visibility pass reads there
#else
  int view = shadowViewAtDepth(cameraViewDepth(p.xyz));
#endif
  vec2 t = shadowTexelCoord(view, p.xyz);
  vec2 jx = shadowTexelCoord(view, p.xyz + dx) - t;
  vec2 jy = shadowTexelCoord(view, p.xyz + dy) - t;
  float texelsPerPixel = abs(jx.x * jy.y - jx.y * jy.x);
  return 1.0 / max(texelsPerPixel, 1.0 / kMaxPixelsPerTexel);
}
