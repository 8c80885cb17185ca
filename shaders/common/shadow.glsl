#pragma once
// Shadow-map addressing shared by every filter: which view (cascade) covers a point, where the
// point falls in that view's map, its linear light depth, and the world size of one texel there.
// In the visibility pass what the frame is made of is known when the program is built
// (FrameContext::visibilityProgram): PN_SHADOW_VIEWS (the view count), PN_VIEWS_PERSPECTIVE and
// PN_VIEWS_WARPED (0 or 1, when every view agrees; a spot light's psm view is both) and
// PN_CASCADE_BLEND (a blend band between views) are compile-time constants there, so a one-view
// frame selects no view, blends nothing and indexes its view's data with a constant. Other
// passes read the same facts from the shadow block.
#include "common/frame.glsl"

int shadowViewCount() {
#ifdef PN_SHADOW_VIEWS
  return PN_SHADOW_VIEWS;
#else
  return u_shadow.info.x;
#endif
}
float shadowMapSize() { return float(u_shadow.info.y); }

// Linear light-space depth in [0,1] (docs/design.md: shadow maps store linear depth).
float lightDepth(int view, vec3 ws) { return dot(u_shadow.views[view].depthPlane, vec4(ws, 1.0)); }

// Distance (m) from the light along its axis.
float lightDistance(int view, vec3 ws) {
  vec4 r = u_shadow.views[view].range;
  return r.x + lightDepth(view, ws) * (r.y - r.x);
}

bool isPerspectiveView(int view) {
#ifdef PN_VIEWS_PERSPECTIVE
  return PN_VIEWS_PERSPECTIVE != 0;
#else
  return u_shadow.views[view].range.z > 0.5;
#endif
}

// xy: map uv in [0,1]; z: linear depth in [0,1]. A point beyond the view's far plane reads as on
// it: the view holds every caster between it and the light, so what the map stores there (a
// caster, or the far plane's clear value: none) decides, and no receiver the fit left out is
// darkened for lying past the map's depth range.
vec3 shadowCoord(int view, vec3 ws) {
  vec4 c = u_shadow.views[view].clipFromWorld * vec4(ws, 1.0);
  return vec3(c.xy / c.w * 0.5 + 0.5, min(lightDepth(view, ws), 1.0));
}

// psm/tsm: clipFromWorld carries a projective warp, so a texel's size depends on where it is.
bool isWarpedView(int view) {
#ifdef PN_VIEWS_WARPED
  return PN_VIEWS_WARPED != 0;
#else
  return u_shadow.views[view].extent.w > 0.5;
#endif
}

// Gradients (per world metre) of the map's u and v at ws: uv = 0.5 + 0.5·clip.xy / clip.w.
void shadowUvGradients(int view, vec3 ws, out vec3 gradU, out vec3 gradV) {
  mat4 m = u_shadow.views[view].clipFromWorld;
  vec4 c = m * vec4(ws, 1.0);
  vec3 rowX = vec3(m[0][0], m[1][0], m[2][0]);
  vec3 rowY = vec3(m[0][1], m[1][1], m[2][1]);
  vec3 rowW = vec3(m[0][3], m[1][3], m[2][3]);
  gradU = 0.5 * (rowX * c.w - c.x * rowW) / (c.w * c.w);
  gradV = 0.5 * (rowY * c.w - c.y * rowW) / (c.w * c.w);
}

// Metres that one uv unit of the map spans at ws along its x and y axes, measured across the
// light's rays (the plane a texel is cut from): the lengths of a texel's two edges there (× map
// size). Unwarped views: the extent (× distance for a perspective view). Warped views: from
// the derivatives of clipFromWorld; their texels are sheared, so the edge along u is the
// column of the inverse Jacobian, |∇v⊥| / |det|, not 1 / |∇u| (the spacing of u's iso-lines,
// which is shorter and would leave slope biases a texel short).
vec2 shadowMetresPerUv(int view, vec3 ws) {
  if (!isWarpedView(view)) {
    vec2 extent = u_shadow.views[view].extent.xy;
    return isPerspectiveView(view) ? extent * lightDistance(view, ws) : extent;
  }
  vec3 gradU, gradV;
  shadowUvGradients(view, ws, gradU, gradV);
  vec3 l = toLight(ws);
  gradU -= dot(gradU, l) * l;
  gradV -= dot(gradV, l) * l;
  const float kMinDeterminant = 1e-12;  // uv² per m²; keeps a degenerate warp finite
  float det = max(abs(dot(cross(gradU, gradV), l)), kMinDeterminant);
  return vec2(length(gradV), length(gradU)) / det;
}

// World-space size (m) of one shadow-map texel at ws (the larger side of a non-square texel).
float shadowTexelWorldSize(int view, vec3 ws) {
  vec2 metres = shadowMetresPerUv(view, ws);
  return max(metres.x, metres.y) / shadowMapSize();
}

// Metres of light-axis distance per unit of stored depth.
float depthRangeM(int view) { return u_shadow.views[view].range.y - u_shadow.views[view].range.x; }

// A variance of stored depth (linear depth² units) from one stated in texels²: `texelsSquared`
// times the square of one texel's world size at ws (across the rays), taken as a distance along
// the light's axis and divided by the view's depth range. Variance
// floors are stated this way, like slope-scaled biases, so that one default serves a view 2 m
// deep and a cascade 700 m deep: a floor in stored-depth units is a few millimetres in the first
// and metres in the second, enough to wash out the shadow of a bench.
float texelDepthVariance(int view, vec3 ws, float texelsSquared) {
  float texelDepth = shadowTexelWorldSize(view, ws) / depthRangeM(view);
  return texelsSquared * texelDepth * texelDepth;
}

// Camera view depth (m) of a world point: what cascades are split by.
float cameraViewDepth(vec3 ws) { return -(u_frame.viewFromWorld * vec4(ws, 1.0)).z; }

// The view (cascade) whose split contains this camera depth; the last one otherwise.
int shadowViewAtDepth(float viewDepth) {
  int n = shadowViewCount();
  for (int i = 0; i < n - 1; ++i)
    if (viewDepth <= u_shadow.views[i].range.w) return i;
  return n - 1;
}

// A point light's cube face for the direction d from the light (+X, −X, +Y, −Y, +Z, −Z: the
// order of UniformProjection's faces): its dominant axis.
int cubeFace(vec3 d) {
  vec3 a = abs(d);
  if (a.x >= a.y && a.x >= a.z) return d.x > 0.0 ? 0 : 1;
  if (a.y >= a.z) return d.y > 0.0 ? 2 : 3;
  return d.z > 0.0 ? 4 : 5;
}

bool insideMap(vec3 coord) { return all(greaterThanEqual(coord.xy, vec2(0.0))) && all(lessThanEqual(coord.xy, vec2(1.0))); }

#ifdef PN_VIRTUAL_PAGES
// A paged projection (`virtual`, docs/virtual.md): each view is one level of a clipmap around the
// camera (a sun's; a spot's levels are mips of one perspective view, level l the view over the
// corner [0, 2^-l]² of its virtual square; a point light's six cube faces are each such a view in
// mips, face after face: view = face · levels + level), a virtual map of PN_PAGES_PER_SIDE² pages
// of PN_PAGE_SIZE² texels whose extent doubles from level to level; only the pages this frame's
// pixels need are drawn, into tiles of a pool (the filter's map: PN_POOL_TILES_PER_SIDE² tiles a
// layer), and a page table (a layer per view) says which tile holds each page. Filters address
// the virtual map as any other (mapTexel, shadowMapSize, the view's clipFromWorld) and read it
// through fetchMapDepth.
#include "shared/VirtualPages.h"
layout(std140, binding = PN_UBO_PAGES) uniform PagesBlock { PagesUniforms u_pages; };
layout(binding = PN_TEX_PAGE_TABLE) uniform usampler2DArray s_pageTable;

// Below this cosine a surface seen or lit edge-on counts as at this angle (its footprint is finite).
const float kMinLevelCosine = 0.02;

// Levels of each of the light's virtual maps: the views, or a point light's views over its six faces.
int virtualLevels() { return int(u_pages.shape.y); }

// Level 0's view of the virtual map that holds ws: a point light's face in ws's direction, else 0.
int virtualFirstView(vec3 ws) { return isPointLight() ? cubeFace(ws - u_frame.light.position.xyz) * virtualLevels() : 0; }

// The coarsest level's view of the map `view` belongs to.
int virtualLastView(int view) { return view - view % virtualLevels() + virtualLevels() - 1; }

// The share of the map's uv square per axis that view `view` covers: all of it, but a perspective
// virtual map's level l holds its view in the corner [0, 2^-l]² (VirtualProjection): a read past
// that corner is past the view's edge, as one past a whole map's edge.
float viewUvExtent(int view) { return isPerspectiveView(view) ? exp2(-float(view % virtualLevels())) : 1.0; }

// The width (m) of a camera pixel at ws, across its ray: a pixel at angle φ off the camera's axis
// subtends k²·cos³φ steradians (k: the width per metre on the axis), so at distance d it is
// d·k·cos^1.5 φ wide (its square's side).
float virtualPixelWidthM(vec3 ws) {
#ifdef PN_CAMERA_ORTHOGRAPHIC
  return u_pages.lod.y;
#else
  float d = max(distance(ws, u_frame.cameraPosition.xyz), 1e-6);
  float cosOffAxis = clamp(cameraViewDepth(ws) / d, 0.0, 1.0);
  return d * u_pages.lod.y * cosOffAxis * sqrt(cosOffAxis);
#endif
}

// The level a pixel at ws on a surface of normal n asks for, before rounding: the finest level
// whose texels, seen from the camera, each cover at most one pixel is its floor. The pixel's
// footprint on its surface (width² / cos of the camera's angle to it) projected along the light's
// rays onto the map's plane (× cos of the light's angle) holds w²·ratio m², and a texel of level
// l is t_l = t_0·2^l wide: log2(w·√ratio / t_0), moved by the level bias. The ratio is capped at
// 1 (never coarser than the pixel's width): a camera grazing the surface stretches its footprint
// along the view only, and the texels must still resolve its width across. There, past the cap,
// each doubling of the ratio asks for one level finer, up to u_pages.shape.x levels: the thin
// shadows of poles and wires on a street seen far off span a pixel or two across, and a texel as
// wide as the pixel breaks them into dashes; a surface seen face on keeps the pixel's width (its
// pages cost the most, as it fills the screen near the camera). A light grazing the surface makes
// the texels finer too. n = vec3(0): no surface known (the pixel faces camera and light alike).
float virtualLevelValue(vec3 ws, vec3 n) {
  float ratio = 1.0;
  if (dot(n, n) > 0.0) {
    vec3 nn = normalize(n);
#ifdef PN_CAMERA_ORTHOGRAPHIC
    vec3 toEye = vec3(u_frame.viewFromWorld[0][2], u_frame.viewFromWorld[1][2], u_frame.viewFromWorld[2][2]);
#else
    vec3 toEye = normalize(u_frame.cameraPosition.xyz - ws);
#endif
    ratio = max(abs(dot(nn, toLight(ws))), kMinLevelCosine) / max(abs(dot(nn, toEye)), kMinLevelCosine);
  }
  float grazing = min(log2(max(ratio, 1.0)), u_pages.shape.x);
  // A spot's (a point light's face's) level 0 texel grows with the distance to the light:
  // u_pages.lod.x is its log2 at 1 m.
  int first = virtualFirstView(ws);
  float texel0 = u_pages.lod.x + (isPerspectiveView(first) ? log2(max(lightDistance(first, ws), 1e-6)) : 0.0);
  return log2(virtualPixelWidthM(ws)) + 0.5 * log2(min(ratio, 1.0)) - grazing - texel0 + u_pages.lod.z;
}

// The level read for a level value: its floor among the levels a pixel reads, or the first coarser
// level whose square holds ws (a point far off, or seen at a grazing angle).
int virtualLevelAt(vec3 ws, float value) {
  int l = int(clamp(floor(value), 0.0, u_pages.shape.z - 1.0));
  // A spot's levels are mips of one view: each holds every point of the view, and a point off the
  // view is off its every level (its uv in a coarser level lands in that level's unused pages).
  // A point light's are its face's.
  if (isPerspectiveView(0)) return virtualFirstView(ws) + l;
  while (l < shadowViewCount() - 1 && !insideMap(shadowCoord(l, ws))) ++l;
  return l;
}

int virtualLevelFor(vec3 ws, vec3 n) { return virtualLevelAt(ws, virtualLevelValue(ws, n)); }

// A point's map uv in level `to` from its uv in level `from`. The levels share the light's
// rotation and depth plane (their views look from the world's origin): clip.xy = k·(light-space
// xy) + t with k = 2 / extent, t the view's translation.
vec2 virtualUvInLevel(vec2 uv, int from, int to) {
  // A spot's levels are mips of one view, level l in the corner [0, 2^-l]² (VirtualProjection);
  // from and to are levels of one view (a point light's face).
  if (isPerspectiveView(from)) return uv * exp2(float(from - to));
  vec2 kFrom = 2.0 / u_shadow.views[from].extent.xy, kTo = 2.0 / u_shadow.views[to].extent.xy;
  vec2 tFrom = u_shadow.views[from].clipFromWorld[3].xy, tTo = u_shadow.views[to].clipFromWorld[3].xy;
  return ((uv * 2.0 - 1.0 - tFrom) * (kTo / kFrom) + tTo) * 0.5 + 0.5;
}

// Where the page holding texel t of level l lies in the pool: its tile's first texel and layer.
// False when t is off the level's map or its page is not resident.
bool pageInPool(ivec2 t, int l, out ivec3 pool0) {
  const int size = PN_PAGE_SIZE * PN_PAGES_PER_SIDE;
  pool0 = ivec3(0);
  if (any(lessThan(t, ivec2(0))) || any(greaterThanEqual(t, ivec2(size)))) return false;
  uint entry = texelFetch(s_pageTable, ivec3(t / PN_PAGE_SIZE, l), 0).r;
  if (entry == 0u) return false;
  int tile = int(entry - 1u);
  const int perLayer = PN_POOL_TILES_PER_SIDE * PN_POOL_TILES_PER_SIDE;
  pool0 = ivec3(ivec2(tile % PN_POOL_TILES_PER_SIDE, (tile % perLayer) / PN_POOL_TILES_PER_SIDE) * PN_PAGE_SIZE, tile / perLayer);
  return true;
}

// The depth at texel `texel` of level `level`, read from `pool` through the page table. A page
// that is not resident (not needed by this frame's pixels, or the pool was full) is served by the
// first coarser level that holds the point in a resident page; none does: the far plane (1).
float pagedDepth(sampler2DArray pool, ivec2 texel, int level) {
  const int size = PN_PAGE_SIZE * PN_PAGES_PER_SIDE;
  vec2 uv = (vec2(texel) + 0.5) / float(size);
  for (int l = level; l <= virtualLastView(level); ++l) {
    ivec2 t = l == level ? texel : ivec2(floor(virtualUvInLevel(uv, level, l) * float(size)));
    ivec3 pool0;
    if (!pageInPool(t, l, pool0)) continue;
    return texelFetch(pool, ivec3(pool0.xy + t % PN_PAGE_SIZE, pool0.z), 0).r;
  }
  return 1.0;
}

// The smallest depth over cell `cell` (2^(k+1) texels a side) of level `level`'s virtual map, from
// the pool's min-depth pyramid (MinDepthPyramid over the pool: its level k holds a tile's k-th
// level, as tiles sit on a grid of whole pages). A page that is not resident is served by the
// first coarser level that holds the cell in a resident page: the levels' corners sit on their
// page grids, so the cell of a coarser level at the same k (twice as wide) holds the finer one.
// No level holds it: 0, the near plane (nothing is known there; a bound must not be above it).
float pagedCellMinDepth(sampler2DArray pyramid, ivec2 cell, int k, int level) {
  const int size = PN_PAGE_SIZE * PN_PAGES_PER_SIDE;
  int cellTexels = 2 << k;
  vec2 uv = (vec2(cell) + 0.5) * float(cellTexels) / float(size);
  for (int l = level; l <= virtualLastView(level); ++l) {
    ivec2 c = l == level ? cell : ivec2(floor(virtualUvInLevel(uv, level, l) * float(size) / float(cellTexels)));
    ivec2 t = c * cellTexels;
    ivec3 pool0;
    if (!pageInPool(t, l, pool0)) continue;
    return texelFetch(pyramid, ivec3((pool0.xy + t % PN_PAGE_SIZE) / cellTexels, pool0.z), k).r;
  }
  return 0.0;
}

// The smallest depth over the box of half-size radiusUv around uv of level `level` (at most four
// cells of the pool's pyramid, common/penumbra.glsl: minDepthOverBox for whole maps). A box wider
// than a page is looked up in the first coarser level where it is not: each level halves it in
// texels, and its texels store the surfaces nearest the light at their centres, as the finer
// level's do.
float pagedMinDepthOverBox(sampler2DArray pyramid, int level, vec2 uv, vec2 radiusUv) {
  const float size = float(PN_PAGE_SIZE * PN_PAGES_PER_SIDE);
  const int maxK = findMSB(PN_PAGE_SIZE) - 1;  // a cell of 2^(maxK+1) texels is a page
  float width = max(2.0 * max(radiusUv.x, radiusUv.y) * size, 1.0);
  int l = min(level + max(int(ceil(log2(width / float(PN_PAGE_SIZE)))), 0), virtualLastView(level));
  float scale = exp2(float(level - l));
  vec2 centre = virtualUvInLevel(uv, level, l);
  vec2 lo = (centre - radiusUv * scale) * size, hi = (centre + radiusUv * scale) * size;
  // A perspective view's box is kept on the view, as a whole map's (minDepthOverBox): every level
  // holds the same view, and past its corner none knows anything (a box reaching past a point
  // light's face read the near plane there, and smrt's rays toward night's lamps, marched all the
  // way to it in 12 steps, passed between the posts' surfaces: umbra leak 1.7 %).
  if (isPerspectiveView(l)) {
    float last = size * viewUvExtent(l) - 1.0;
    lo = clamp(lo, vec2(0.0), vec2(last));
    hi = clamp(hi, vec2(0.0), vec2(last));
  }
  int k = clamp(int(ceil(log2(max(max(hi.x - lo.x, hi.y - lo.y), 1.0)))) - 1, 0, maxK);
  float cellTexels = exp2(float(k + 1));
  ivec2 a = ivec2(floor(lo / cellTexels));
  ivec2 b = clamp(ivec2(floor(hi / cellTexels)), a, a + 1);
  float m = 1.0;
  for (int y = a.y; y <= b.y; ++y)
    for (int x = a.x; x <= b.x; ++x) m = min(m, pagedCellMinDepth(pyramid, ivec2(x, y), k, l));
  return m;
}
#else
float viewUvExtent(int view) { return 1.0; }
#endif

// Whether coord lies on view `view`'s part of its map (insideMap for a whole map's view).
bool insideViewMap(int view, vec3 coord) { return insideMap(vec3(coord.xy / viewUvExtent(view), coord.z)); }

// A point light's view of the cube face in ws's direction at the level of `view` (a paged cube's
// faces are in mips; a whole map's face is one view).
int cubeFaceView(vec3 ws, int view) {
#ifdef PN_VIRTUAL_PAGES
  return cubeFace(ws - u_frame.light.position.xyz) * virtualLevels() + view % virtualLevels();
#else
  return cubeFace(ws - u_frame.light.position.xyz);
#endif
}

// The depth map's texels per side: a paged map's virtual size, else the texture's.
ivec2 mapTexels(sampler2DArray map) {
#ifdef PN_VIRTUAL_PAGES
  return ivec2(PN_PAGE_SIZE * PN_PAGES_PER_SIDE);
#else
  return textureSize(map, 0).xy;
#endif
}

// The linear depth a depth map stores at texel.xy of view texel.z (inside the map): every
// filter's texel read, so that a paged map is read through its page table.
float fetchMapDepth(sampler2DArray map, ivec3 texel) {
#ifdef PN_VIRTUAL_PAGES
  return pagedDepth(map, texel.xy, texel.z);
#else
  return texelFetch(map, texel, 0).r;
#endif
}

// The view that covers ws: a point light's face by direction, a cascade by camera depth, a
// virtual map's level by the pixel's size there (of a point light's face by direction).
int shadowViewFor(vec3 ws) {
#ifdef PN_VIRTUAL_PAGES
  return virtualLevelFor(ws, vec3(0.0));
#else
  return isPointLight() ? cubeFace(ws - u_frame.light.position.xyz) : shadowViewAtDepth(cameraViewDepth(ws));
#endif
}

// Set by the visibility pass while it evaluates one side of a cascade blend (-1: by depth).
// Filters need not know: every one of them asks selectShadowView.
int g_forcedShadowView = -1;

// The view (cascade) a filter should use for this point.
int selectShadowView(vec3 ws) {
#if defined(PN_SHADOW_VIEWS) && PN_SHADOW_VIEWS == 1
  return 0;
#else
  return g_forcedShadowView >= 0 ? g_forcedShadowView : shadowViewFor(ws);
#endif
}

// Cascade blend: within the band (extent.z metres of camera depth) before a split, visibility is
// mix(V(first), V(second), weight), the weight rising linearly from 0 to 1 across the band, so
// the resolution step at the split does not show as a seam. The next cascade is fitted to cover
// the band. Outside a band: first == second, weight 0.
struct ShadowViewBlend {
  int first;
  int second;
  float weight;
};

ShadowViewBlend shadowViewBlend(vec3 ws) {
  ShadowViewBlend b;
  b.weight = 0.0;
#if defined(PN_SHADOW_VIEWS) && PN_SHADOW_VIEWS == 1
  b.first = b.second = 0;
#else
  b.first = shadowViewFor(ws);
  b.second = b.first;
#if !defined(PN_CASCADE_BLEND) || PN_CASCADE_BLEND
  float depth = cameraViewDepth(ws);
  float band = u_shadow.views[b.first].extent.z;
  if (!isPointLight() && b.first < shadowViewCount() - 1 && band > 0.0) {
    float start = u_shadow.views[b.first].range.w - band;
    if (depth > start) {
      b.second = b.first + 1;
      b.weight = clamp((depth - start) / band, 0.0, 1.0);
    }
  }
#endif
#endif
  return b;
}


