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

// The texel of `map` (layer `layer`) under uv, clamped to the map's edge.
ivec3 mapTexel(sampler2DArray map, vec2 uv, int layer) {
  ivec2 size = textureSize(map, 0).xy;
  return ivec3(clamp(ivec2(floor(uv * vec2(size))), ivec2(0), size - 1), layer);
}

// What a filter compares: the receiver in its map, as a plane, and its bias.
struct ComparisonReceiver {
  vec2 uv;          // map coordinates
  int layer;        // map layer = shadow view
  float depth;      // linear light depth in [0,1] at uv
  vec2 depthPerUv;  // the receiver plane's depth gradient in the map (linear depth per uv)
  float bias;       // subtracted for every tap (linear depth)
};

// Beyond this tangent of the angle to the light (~84 degrees, as slopeTangent clamps) a bias
// would push through casters; steeper receivers keep this much and may show acne.
const float kMaxReceiverTangent = 10.0;

// The receiver's tangent plane as depth over map uv (Isidoro 2006, "receiver plane depth bias"):
// the plane is stepped one texel's width along two tangents and both steps projected into the
// map (an orthographic view: the same in closed form). Exact for orthographic, perspective and
// warped views alike. (For a spot light depth is measured along the light's axis, not along the
// ray, so a surface facing the light head-on can still change depth from texel to texel; the
// angle to the ray, slopeTangent, misses that.)
// The gradient's length is bounded by kMaxReceiverTangent texels of slope per texel.
vec2 receiverDepthGradient(int view, SurfacePoint s) {
  vec3 n = s.geoNormal;
  vec2 depthPerUv;
  if (!isPerspectiveView(view) && !isWarpedView(view)) {
    // An orthographic view (the sun's) maps the world to (u, v, depth) linearly, x ↦ (a_u·x,
    // a_v·x, p·x) + const, so the plane's step x for a step (du, dv) in the map solves
    // [a_u; a_v; n] x = (du, dv, 0): Cramer's rule gives the same gradient in closed form, with
    // no differences of nearby projections.
    mat4 m = u_shadow.views[view].clipFromWorld;
    vec3 au = 0.5 * vec3(m[0][0], m[1][0], m[2][0]);
    vec3 av = 0.5 * vec3(m[0][1], m[1][1], m[2][1]);
    vec3 p = u_shadow.views[view].depthPlane.xyz;
    float det = dot(n, cross(au, av));
    if (det == 0.0) return vec2(0.0);  // seen edge-on: no plane to follow
    depthPerUv = vec2(dot(n, cross(p, av)), dot(n, cross(au, p))) / det;
  } else {
    vec3 t1 = normalize(cross(n, abs(n.y) < 0.9 ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 0.0, 0.0)));
    vec3 t2 = cross(n, t1);
    float stepM = shadowTexelWorldSize(view, s.ws);
    vec3 c0 = shadowCoord(view, s.ws);
    vec3 d1 = shadowCoord(view, s.ws + stepM * t1) - c0;
    vec3 d2 = shadowCoord(view, s.ws + stepM * t2) - c0;
    mat2 uvFromPlane = mat2(d1.xy, d2.xy);  // plane coordinates → map uv
    if (determinant(uvFromPlane) == 0.0) return vec2(0.0);  // seen edge-on: no plane to follow
    depthPerUv = vec2(d1.z, d2.z) * inverse(uvFromPlane);
  }
  float maxPerUv = slopeDepthOffset(view, s.ws, kMaxReceiverTangent, 1.0) * shadowMapSize();
  float len = length(depthPerUv);
  return len > maxPerUv ? depthPerUv * (maxPerUv / len) : depthPerUv;
}

// Receiver at shadow coordinate `coord` of `view`. Each tap compares the receiver's own plane
// at the tap (so a wide kernel on a tilted receiver neither shadows the receiver nor, on the
// side away from the light, over-biases past real blockers), lowered by constantBias plus
// slopeTexels texels of the plane's steepest slope: the slope-scaled bias, which covers the
// map's flat texels (a stored depth is exact only at its texel's centre).
ComparisonReceiver comparisonReceiver(int view, SurfacePoint s, vec3 coord, float constantBias, float slopeTexels) {
  ComparisonReceiver r;
  r.uv = coord.xy;
  r.layer = view;
  r.depth = coord.z;
  r.depthPerUv = receiverDepthGradient(view, s);
  r.bias = constantBias + slopeTexels * length(r.depthPerUv) / shadowMapSize();
  return r;
}

// A kernel of taps around a receiver, placed in texels of its map: each tap is two multiply-adds
// from its point of a unit pattern, one more pair for the receiver's plane there, and the fetch.
// The whole kernel is kept on the map's outermost texel centres by moving its centre, not each tap:
// within its reach of the edge it is shifted inward (at most its radius, ×√2 for a turned
// pattern), and every tap is compared with the receiver's plane at the tap, so plane and map agree
// there (a tap past the edge would read the edge texel, clamp to edge, against the plane continued
// past it: a false blocker wherever the plane deepens outward, a shadow line along the map's edge
// on a lit floor).
struct TapKernel {
  vec2 centre;         // the kernel's centre, in texels
  mat2 texelsPerUnit;  // a pattern point (unit disk or square) → texel offset: radius and rotation
  float depth;         // the receiver's plane at the centre, minus its bias
  vec2 depthPerUnit;   // the plane's depth change per unit of the pattern
  vec2 uvPerTexel;
  int layer;
};

// The kernel of radius radiusUv (per axis) around r, its pattern turned by `rotation`, in a map of
// mapSize (textureSize) texels.
TapKernel tapKernel(ComparisonReceiver r, vec2 radiusUv, mat2 rotation, ivec2 mapSize) {
  vec2 size = vec2(mapSize);
  vec2 radiusTexels = radiusUv * size;
  TapKernel k;
  k.texelsPerUnit = mat2(rotation[0] * radiusTexels, rotation[1] * radiusTexels);
  // The farthest tap per axis. The filters keep a kernel inside the map (their radii at most
  // maxKernelRadiusTexels, PcfFilter.h): narrowing it here, per pixel, cost pcf's pass 5 %.
  vec2 reach = abs(k.texelsPerUnit[0]) + abs(k.texelsPerUnit[1]);
  vec2 receiver = r.uv * size;
  k.centre = clamp(receiver, 0.5 + reach, size - 0.5 - reach);
  vec2 depthPerTexel = r.depthPerUv / size;
  k.depth = r.depth - r.bias + dot(depthPerTexel, k.centre - receiver);
  k.depthPerUnit = depthPerTexel * k.texelsPerUnit;
  k.uvPerTexel = 1.0 / size;
  k.layer = r.layer;
  return k;
}

// Where the tap at pattern point `unit` falls (texels) and the receiver's biased depth there.
vec2 tapTexel(TapKernel k, vec2 unit) { return k.centre + k.texelsPerUnit * unit; }
float tapDepth(TapKernel k, vec2 unit) { return k.depth + dot(k.depthPerUnit, unit); }

// The depth stored at a tap's texel (inside the map: truncation is the floor).
float storedDepth(sampler2DArray map, TapKernel k, vec2 texel) { return texelFetch(map, ivec3(ivec2(texel), k.layer), 0).r; }

// One comparison at pattern point `unit`: the nearest texel's stored depth …
float comparisonTap(sampler2DArray map, TapKernel k, vec2 unit) {
  return compareDepth(tapDepth(k, unit), storedDepth(map, k, tapTexel(k, unit)));
}
// … or the hardware's bilinear blend of the four surrounding comparisons. The maps have one
// level and filter linearly both ways: zero gradients (magnification) are what any level of
// detail would read, and give no stage a derivative to take (the pass runs as a fragment shader).
float comparisonTap(sampler2DArrayShadow map, TapKernel k, vec2 unit) {
  return textureGrad(map, vec4(tapTexel(k, unit) * k.uvPerTexel, float(k.layer), tapDepth(k, unit)), vec2(0.0), vec2(0.0));
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

// Percentage-closer filtering over a (2·halfSide + 1)² grid spanning ±radiusUv on each axis.
float percentageCloserBox(PN_COMPARISON_MAP map, ComparisonReceiver r, vec2 radiusUv, int halfSide) {
  int taps = boxTapCount(halfSide);
  TapKernel k = tapKernel(r, radiusUv, mat2(1.0), textureSize(map, 0).xy);
  float lit = 0.0;
  for (int i = 0; i < taps; ++i) lit += comparisonTap(map, k, boxTap(i, halfSide));
  return lit / float(taps);
}

// Percentage-closer filtering over the first `taps` points of the Poisson disk of radius radiusUv
// (per axis), turned by `rotation`.
float percentageCloserPoisson(PN_COMPARISON_MAP map, ComparisonReceiver r, vec2 radiusUv, int taps, mat2 rotation) {
  int n = clamp(taps, 1, kPoissonDiskSize);
  TapKernel k = tapKernel(r, radiusUv, rotation, textureSize(map, 0).xy);
  float lit = 0.0;
  for (int i = 0; i < n; ++i) lit += comparisonTap(map, k, kPoissonDisk[i]);
  return lit / float(n);
}
