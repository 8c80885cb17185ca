#pragma once
// Depth comparisons shared by the shadow-map filters: the receiver's bias (its tangent plane
// continued to every tap, plus a slope-scaled margin), the test itself, and percentage-closer
// filtering (Reeves, Salesin & Cook 1987): the RESULTS of many tests around the receiver are
// averaged, never the stored depths (averaging depths and testing once would still give 0 or
// 1). Depths are linear light depths in [0,1]; 1 = lit.
// With PN_HARDWARE_COMPARE defined (prelude), every tap is the hardware's bilinear 2×2
// comparison (sampler2DArrayShadow): the map must then be bound with a comparison sampler.
#include "common/sampling.glsl"
#include "common/visibility.glsl"

#if defined(PN_HARDWARE_COMPARE) && defined(PN_VIRTUAL_PAGES)
#error "a paged map is read texel by texel: the hardware's 2x2 comparison would straddle pages"
#endif
#ifdef PN_HARDWARE_COMPARE
#define PN_COMPARISON_MAP sampler2DArrayShadow
#else
#define PN_COMPARISON_MAP sampler2DArray
#endif

// Linear depth that a plane tilted from the light by an angle of tangent tanTheta spans across
// `texels` map texels at ws: the slope-scaled bias (a texel is a flat step of the map, and the
// receiver's true depth differs from it by up to texel · tan θ).
float slopeDepthOffset(int view, vec3 ws, float tanTheta, float texels) {
  return texels * shadowTexelWorldSize(view, ws) * tanTheta / depthRangeM(view);
}

// The test: lit when the receiver is not farther from the light than the stored surface.
float compareDepth(float receiverDepth, float storedDepth) { return receiverDepth <= storedDepth ? 1.0 : 0.0; }

// The texel of `map` (layer `layer`) under uv, clamped to the edge of the layer's view.
ivec3 mapTexel(sampler2DArray map, vec2 uv, int layer) {
  ivec2 size = mapTexels(map);
  ivec2 last = ivec2(vec2(size) * viewUvExtent(layer)) - 1;
  return ivec3(clamp(ivec2(floor(uv * vec2(size))), ivec2(0), last), layer);
}

// What a filter compares: the receiver in its map, as a plane, and its bias.
struct ComparisonReceiver {
  vec2 uv;          // map coordinates
  int layer;        // map layer = shadow view
  float depth;      // linear light depth in [0,1] at uv
  vec2 depthPerUv;  // the receiver plane's depth gradient in the map at uv (linear depth per uv)
  // The plane's depth at uv + Δ is depth + dot(depthPerUv, Δ) / (1 − dot(projectivePerUv, Δ)): a
  // plane seen through a perspective or warped view is a projective function of the map's
  // coordinates, not a linear one (0 for an orthographic view).
  vec2 projectivePerUv;
  float bias;       // subtracted for every tap (linear depth)
  // Subtracted per texel of the compared texel's distance from the receiver (linear depth): the
  // plane moved back one texel along its normal for every texel it is carried (planeReachDepth).
  float biasPerTexel;
  // Subtracted per texel more by a kernel's taps (pcf's; 0 for pcss): the depth a wall standing
  // square on the receiver rises in front of its plane per texel (creaseDepthPerTexel).
  float creasePerTexel;
};

// Beyond this tangent of the angle to the light (~84 degrees, as slopeTangent clamps) a bias
// would push through casters; steeper receivers keep this much and may show acne.
const float kMaxReceiverTangent = 10.0;

// The receiver's tangent plane over the map (Isidoro 2006, "receiver plane depth bias"), exact
// for orthographic, perspective and warped views alike. Two tangents t1, t2 of the plane and the
// view's clip coordinates c = clipFromWorld·(p, 1) give, for a map offset Δ from the receiver,
// the plane point's tangent coordinates (a, b) = w·A·Δ with w = w0 / (1 − dot(Aᵀ(w1, w2), Δ)),
// A the inverse of w0 × the map's Jacobian along the tangents (its columns
// 0.5·(x_i·w0 − w_i·x0, y_i·w0 − w_i·y0) / w0²); the depth is affine in (a, b) (depthPlane), so
// depth(Δ) = depth + dot(g, Δ) / (1 − dot(q, Δ)), g = w0·Aᵀ(dot(p, t1), dot(p, t2)), q = Aᵀ(w1, w2).
// No differences of nearby projections: every term is a derivative taken in closed form. (For a
// spot light depth is measured along the light's axis, not along the ray, so a surface facing
// the light head-on can still change depth from texel to texel; the angle to the ray misses that.)
// The gradient's length is bounded by kMaxReceiverTangent texels of slope per texel.
void receiverPlane(int view, SurfacePoint s, out vec2 depthPerUv, out vec2 projectivePerUv) {
  vec3 n = s.geoNormal;
  vec3 t1 = normalize(cross(n, abs(n.y) < 0.9 ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 0.0, 0.0)));
  vec3 t2 = cross(n, t1);
  mat4 m = u_shadow.views[view].clipFromWorld;
  vec4 c0 = m * vec4(s.ws, 1.0);
  vec4 c1 = m * vec4(t1, 0.0);
  vec4 c2 = m * vec4(t2, 0.0);
  // w0 × ∂uv/∂(a, b): column i is the derivative along t_i.
  mat2 jacobianW0 = (0.5 / c0.w) * mat2(c1.x * c0.w - c1.w * c0.x, c1.y * c0.w - c1.w * c0.y,
                                        c2.x * c0.w - c2.w * c0.x, c2.y * c0.w - c2.w * c0.y);
  depthPerUv = vec2(0.0);
  projectivePerUv = vec2(0.0);
  if (determinant(jacobianW0) == 0.0) return;  // seen edge-on: no plane to follow
  mat2 toTangent = inverse(jacobianW0);
  vec3 p = u_shadow.views[view].depthPlane.xyz;
  depthPerUv = c0.w * (vec2(dot(p, t1), dot(p, t2)) * toTangent);
  projectivePerUv = vec2(c1.w, c2.w) * toTangent;
  float maxPerUv = slopeDepthOffset(view, s.ws, kMaxReceiverTangent, 1.0) * shadowMapSize();
  float len = length(depthPerUv);
  if (len > maxPerUv) depthPerUv *= maxPerUv / len;
}

// The plane's gradient alone (the biases' slope and the lookups that average boxes of the map).
vec2 receiverDepthGradient(int view, SurfacePoint s) {
  vec2 g, q;
  receiverPlane(view, s, g, q);
  return g;
}

// The denominator 1 − dot(q, Δ) is w / w0 > 0 wherever the plane is in front of the light; it is
// kept above this near the plane's horizon in the map, where the depth runs off to infinity.
const float kMinPlaneW = 1e-3;

// The receiver plane's linear depth at map coordinate uv (before the bias).
float receiverDepthAt(ComparisonReceiver r, vec2 uv) {
  vec2 d = uv - r.uv;
  return r.depth + dot(r.depthPerUv, d) / max(1.0 - dot(r.projectivePerUv, d), kMinPlaneW);
}

// The depth (linear units) that moving the receiver's plane `texels` texels of world size along
// its normal puts between it and the light: a texel's world size t across the rays, and the
// plane's depth change s·t over one texel, in quadrature (t·√(1 + s²) = t / cos θ for a plane at
// θ to the light). A margin the receiver's plane does not cover — facets and curvature, a
// concave crease whose other face a texel's centre lands on, the normal's and the positions'
// rounding — is a distance off the plane, which a light at θ sees as that distance / cos θ.
float planeNormalOffsetDepth(int view, vec3 ws, vec2 depthPerUv, float texels) {
  float texelDepth = shadowTexelWorldSize(view, ws) / depthRangeM(view);
  float slopeDepth = length(depthPerUv) / shadowMapSize();
  return texels * sqrt(texelDepth * texelDepth + slopeDepth * slopeDepth);
}

// A wall standing square on the receiver (a concave crease: a lit wall on a lit floor) rises in
// front of the receiver's plane carried d texels toward it by d·t / (cos θ · sin θ) of depth, θ
// the receiver's angle to the light: its texels are seen at height d·t / sin θ. The plane margin
// (1 + d)·t / cos θ covers that only where sin θ ≥ d / (1 + d) (θ ≥ 42° for a 2-texel tap), so
// under a high sun or a lamp overhead a filter's kernel straddling the foot of a lit wall reads
// the wall as a blocker and darkens a strip of floor as wide as the kernel. This is the depth per
// texel of tap distance to add to planeNormalOffsetDepth's one texel (t / cos θ) so that the two
// together are t / (cos θ · sin θ): (1/sin θ − 1)·t / cos θ, with 1/sin θ capped at
// kMaxCreaseFactor. It hides, d texels from the receiver, anything lower than d·t / sin θ above
// its plane (at most kMaxCreaseFactor·d texels), so only a kernel of a few texels may take it:
// pcf's (its radius, 2 texels by default, bounds d). pcss sets it to 0 (pcss.glsl).
const float kMaxCreaseFactor = 10.0;
float creaseDepthPerTexel(vec2 depthPerUv, float biasPerTexel) {
  float slopeDepth = length(depthPerUv) / shadowMapSize();
  float invSin = biasPerTexel / max(slopeDepth, biasPerTexel / kMaxCreaseFactor);  // 1 / sin θ, capped
  return (invSin - 1.0) * biasPerTexel;
}

// Receiver at shadow coordinate `coord` of `view`. Each tap compares a texel with the receiver's
// own plane at that texel's centre — where the stored depth was rasterised — so a planar
// receiver meets its own map exactly at every tap and a wide kernel on a tilted receiver neither
// shadows the receiver nor, on the side away from the light, over-biases past real blockers. The
// plane is lowered by constantBias (linear depth), slopeTexels texels of its steepest slope, and
// planeTexels + d texels of world size along its normal (planeNormalOffsetDepth), d the compared
// texel's distance from the receiver in texels: the margin for what a plane does not model. It
// grows with d because what it covers does: a curved or faceted receiver departs from the plane
// by more the farther it is carried, and a concave crease's other face (a lit wall on the floor)
// rises in front of it (a filter's taps add creasePerTexel for that); at the receiver itself only
// planeTexels remain, so contact shadows keep their root.
ComparisonReceiver comparisonReceiver(int view, SurfacePoint s, vec3 coord, float constantBias, float slopeTexels,
                                      float planeTexels) {
  ComparisonReceiver r;
  r.uv = coord.xy;
  r.layer = view;
  r.depth = coord.z;
  receiverPlane(view, s, r.depthPerUv, r.projectivePerUv);
  r.biasPerTexel = planeNormalOffsetDepth(view, s.ws, r.depthPerUv, 1.0);
  r.creasePerTexel = creaseDepthPerTexel(r.depthPerUv, r.biasPerTexel);
  r.bias = constantBias + slopeTexels * length(r.depthPerUv) / shadowMapSize() + planeTexels * r.biasPerTexel;
  return r;
}

// The receiver's biased depth to compare with the texel whose centre is at map coordinate uv.
float biasedDepthAt(ComparisonReceiver r, vec2 uv) {
  return receiverDepthAt(r, uv) - r.bias - r.biasPerTexel * length((uv - r.uv) * shadowMapSize());
}

// A kernel of taps around a receiver, placed in texels of its map: each tap is two multiply-adds
// from its point of a unit pattern, the receiver's plane at the tap's texel centre (a dot product
// and a division more for a warped or perspective view), and the fetch.
// The whole kernel is kept on the map's outermost texel centres by moving its centre, not each tap:
// within its reach of the edge it is shifted inward (at most its radius, ×√2 for a turned
// pattern), and every tap is compared with the receiver's plane at the tap, so plane and map agree
// there (a tap past the edge would read the edge texel, clamp to edge, against the plane continued
// past it: a false blocker wherever the plane deepens outward, a shadow line along the map's edge
// on a lit floor).
struct TapKernel {
  vec2 centre;         // the kernel's centre, in texels
  mat2 texelsPerUnit;  // a pattern point (unit disk or square) → texel offset: radius and rotation
  vec2 receiver;       // the receiver, in texels
  float depth;         // the receiver's plane there, minus its bias
  vec2 depthPerTexel;  // the plane's gradient and projective term per texel (ComparisonReceiver)
  vec2 projectivePerTexel;
  float biasPerTexel;  // ComparisonReceiver::biasPerTexel + creasePerTexel
  // The hardware's 2×2 comparison takes one reference depth for four texels: the plane at the tap
  // point differs from the plane at their centres by up to half a texel of slope on each axis.
  float bilinearMargin;
  vec2 uvPerTexel;
  int layer;
};

// The kernel of radius radiusUv (per axis) around r, its pattern turned by `rotation`, in a map of
// mapSize (textureSize) texels (of which r's view may cover a corner: viewUvExtent).
TapKernel tapKernel(ComparisonReceiver r, vec2 radiusUv, mat2 rotation, ivec2 mapSize) {
  vec2 size = vec2(mapSize);
  vec2 radiusTexels = radiusUv * size;
  TapKernel k;
  k.texelsPerUnit = mat2(rotation[0] * radiusTexels, rotation[1] * radiusTexels);
  // The farthest tap per axis. The filters keep a kernel inside the map (their radii at most
  // maxKernelRadiusTexels, PcfFilter.h): narrowing it here, per pixel, cost pcf's pass 5 %.
  vec2 reach = abs(k.texelsPerUnit[0]) + abs(k.texelsPerUnit[1]);
  k.receiver = r.uv * size;
  k.centre = clamp(k.receiver, 0.5 + reach, size * viewUvExtent(r.layer) - 0.5 - reach);
  k.depthPerTexel = r.depthPerUv / size;
  k.projectivePerTexel = r.projectivePerUv / size;
  k.depth = r.depth - r.bias;
  k.biasPerTexel = r.biasPerTexel + r.creasePerTexel;
  k.bilinearMargin = 0.5 * (abs(k.depthPerTexel.x) + abs(k.depthPerTexel.y));
  k.uvPerTexel = 1.0 / size;
  k.layer = r.layer;
  return k;
}

// Where the tap at pattern point `unit` falls (texels).
vec2 tapTexel(TapKernel k, vec2 unit) { return k.centre + k.texelsPerUnit * unit; }
// The receiver's biased plane at a point of the map (texels), lowered by one texel along its
// normal per texel from the receiver (ComparisonReceiver).
float kernelPlaneDepth(TapKernel k, vec2 texel) {
  vec2 d = texel - k.receiver;
  return k.depth + dot(k.depthPerTexel, d) / max(1.0 - dot(k.projectivePerTexel, d), kMinPlaneW) - k.biasPerTexel * length(d);
}
// The receiver's biased depth to compare with the texel that the tap at pattern point `unit`
// reads: the plane at that texel's centre, where its depth was rasterised.
float tapDepth(TapKernel k, vec2 unit) { return kernelPlaneDepth(k, floor(tapTexel(k, unit)) + 0.5); }

// The depth stored at a tap's texel (inside the map: truncation is the floor).
float storedDepth(sampler2DArray map, TapKernel k, vec2 texel) { return fetchMapDepth(map, ivec3(ivec2(texel), k.layer)); }

// One comparison at pattern point `unit`: the nearest texel's stored depth …
float comparisonTap(sampler2DArray map, TapKernel k, vec2 unit) {
  return compareDepth(tapDepth(k, unit), storedDepth(map, k, tapTexel(k, unit)));
}
// … or the hardware's bilinear blend of the four surrounding comparisons. The maps have one
// level and filter linearly both ways: zero gradients (magnification) are what any level of
// detail would read, and give no stage a derivative to take (the pass runs as a fragment shader).
float comparisonTap(sampler2DArrayShadow map, TapKernel k, vec2 unit) {
  vec2 texel = tapTexel(k, unit);
  float depth = kernelPlaneDepth(k, texel) - k.bilinearMargin;
  return textureGrad(map, vec4(texel * k.uvPerTexel, float(k.layer), depth), vec2(0.0), vec2(0.0));
}

// The receiver's map coordinate moved onto the outermost texel centres, its depth carried along
// its own plane: for lookups that average boxes of the map around the receiver (vssm, msm-soft),
// which within half a texel of the edge would otherwise centre on a texel that is not there.
vec3 coordInsideMap(int view, SurfacePoint s, vec3 coord, ivec2 mapSize) {
  vec2 halfTexelUv = 0.5 / vec2(mapSize);
  vec2 inside = clamp(coord.xy, halfTexelUv, 1.0 - halfTexelUv);
  if (inside == coord.xy) return coord;
  return vec3(inside, coord.z + dot(receiverDepthGradient(view, s), inside - coord.xy));
}

// The hardware-comparison map's size (never paged).
ivec2 mapTexels(sampler2DArrayShadow map) { return textureSize(map, 0).xy; }

// Percentage-closer filtering over a (2·halfSide + 1)² grid spanning ±radiusUv on each axis.
float percentageCloserBox(PN_COMPARISON_MAP map, ComparisonReceiver r, vec2 radiusUv, int halfSide) {
  int taps = boxTapCount(halfSide);
  TapKernel k = tapKernel(r, radiusUv, mat2(1.0), mapTexels(map));
  float lit = 0.0;
  for (int i = 0; i < taps; ++i) lit += comparisonTap(map, k, boxTap(i, halfSide));
  return lit / float(taps);
}

// Percentage-closer filtering over the first `taps` points of the Poisson disk of radius radiusUv
// (per axis), turned by `rotation`.
float percentageCloserPoisson(PN_COMPARISON_MAP map, ComparisonReceiver r, vec2 radiusUv, int taps, mat2 rotation) {
  int n = clamp(taps, 1, kPoissonDiskSize);
  TapKernel k = tapKernel(r, radiusUv, rotation, mapTexels(map));
  float lit = 0.0;
  for (int i = 0; i < n; ++i) lit += comparisonTap(map, k, kPoissonDisk[i]);
  return lit / float(n);
}
