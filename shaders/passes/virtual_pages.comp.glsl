// Page marking for a paged projection (frame/VirtualPages): every covered pixel that faces the
// light (the pixels the visibility pass will look up) marks, at the level its footprint asks for
// (virtualLevelFor, the visibility pass's own choice), the pages its texel and a margin of
// u_pages.lod.w texels around it fall in, and the page holding it at every coarser level. A
// page's flag is set once (atomicOr); the invocation that set it appends the page to the list the
// CPU reads back, so the list holds each needed page once. Surfaces are read as the visibility pass reads them (surfaceDefines).
#include "common/visibility.glsl"

layout(local_size_x = PN_SCREEN_GROUP, local_size_y = PN_SCREEN_GROUP) in;
layout(std430, binding = PN_SSBO_PAGE_FLAGS) buffer PageFlags { uint o_flags[]; };
layout(std430, binding = PN_SSBO_PAGE_LIST) buffer PageList {
  uint o_count;
  uint o_pages[];  // (view · PN_PAGES_PER_SIDE + y) · PN_PAGES_PER_SIDE + x
};

void markPage(int level, ivec2 page) {
  uint index = uint((level * PN_PAGES_PER_SIDE + page.y) * PN_PAGES_PER_SIDE + page.x);
  if (atomicOr(o_flags[index], 1u) == 0u) o_pages[atomicAdd(o_count, 1u)] = index;
}

void main() {
  ivec2 px = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(px, u_frame.screen.xy))) return;
  vec4 pos = surfacePosition(px);
  if (pos.w < 0.5) return;
  vec3 n = normalize(surfaceGeoNormal(px, pos.xyz));
  if (dot(n, toLight(pos.xyz)) <= 0.0) return;
  // The visibility pass computes the same level value in another stage, whose rounding may differ
  // in the last bits: a pixel on the line between two levels marks both.
  const float kLevelTolerance = 1e-3;
  float value = virtualLevelValue(pos.xyz, n);
  int levels[2] = int[2](virtualLevelAt(pos.xyz, value - kLevelTolerance), virtualLevelAt(pos.xyz, value + kLevelTolerance));
  const float size = float(PN_PAGE_SIZE * PN_PAGES_PER_SIDE);
  for (int i = 0; i < 2; ++i) {
    if (i == 1 && levels[1] == levels[0]) break;
    vec3 coord = shadowCoord(levels[i], pos.xyz);
    if (!insideViewMap(levels[i], coord)) continue;
    ivec2 last = ivec2(int(size * viewUvExtent(levels[i])) - 1);  // the view's corner of the level
    ivec2 lo = clamp(ivec2(floor(coord.xy * size - u_pages.lod.w)), ivec2(0), last) / PN_PAGE_SIZE;
    ivec2 hi = clamp(ivec2(floor(coord.xy * size + u_pages.lod.w)), ivec2(0), last) / PN_PAGE_SIZE;
    for (int y = lo.y; y <= hi.y; ++y)
      for (int x = lo.x; x <= hi.x; ++x) markPage(levels[i], ivec2(x, y));
  }
  // The page that holds the point at every coarser level too: a read past the marked pages (a
  // kernel's or a ray's far taps, a blocker search, the min-depth bounds) falls back to the first
  // coarser level that holds it, and this keeps one resident around every point a pixel sees. Each
  // level's pages are twice as wide as the last's, so the chain adds about a third to the pages.
  for (int l = max(levels[0], levels[1]) + 1; l <= virtualLastView(levels[0]); ++l) {
    vec3 coord = shadowCoord(l, pos.xyz);
    if (insideViewMap(l, coord)) markPage(l, ivec2(floor(coord.xy * size)) / PN_PAGE_SIZE);
  }
}
