// sdf: distance-field soft shadows. No shadow map: a ray leaves the receiver toward the light
// and sphere-traces (Hart 1996) a signed distance field of the casters baked once per scene
// (src/bake/SdfBake.h). At ray length t the free distance d keeps every caster at least the angle ≈ d/t
// off the ray, so the smallest k·d/t along the ray ("safe angle", Quilez 2010) estimates how much
// of the light is visible; Aaltonen (2018) places the closest approach between two samples.
// k ≈ 1/tan(angular radius of the light) ties the estimate to the light's physical size.
// Assumptions: world-space field in metres, cubic voxels; flat sheets (floors) are exact
// triangles beside the grid; nothing casts outside the casters' bounds.
// Artifacts: shapes thinner than a voxel thin out or vanish; banding with few steps; in outer
// mode the whole penumbra lies outside the hard shadow (umbra too large); a sheet has no inner
// half-penumbra (a ray through it is blocked); alpha masks are solid.
#include "common/visibility.glsl"
#include "techniques/sdf/sdf.shared.h"

layout(std140, binding = PN_UBO_FILTER) uniform SdfBlock { SdfUniforms u_sdf; };
layout(binding = PN_TEX_FILTER0) uniform sampler3D s_sdf;

// A ray direction component below this is treated as parallel to the grid's slab (avoids 1/0).
const float kParallelDir = 1e-12;
// Lengths (m) and tangents are divided by at least this: keeps t = 0 and point lights finite.
const float kTinyM = 1e-9;

// Unsigned distance (m) from p to triangle abc.
float triangleDistance(vec3 p, vec3 a, vec3 b, vec3 c) {
  vec3 ab = b - a, bc = c - b, ca = a - c;
  vec3 n = cross(ab, -ca);
  // Inside the prism over the triangle (left of every edge seen along n): the distance to its plane.
  if (dot(cross(n, ab), p - a) >= 0.0 && dot(cross(n, bc), p - b) >= 0.0 && dot(cross(n, ca), p - c) >= 0.0)
    return abs(dot(n, p - a)) / max(length(n), kTinyM * kTinyM);
  // Outside it: the nearest of the three edges.
  vec3 pa = p - a, pb = p - b, pc = p - c;
  vec3 ea = pa - ab * clamp(dot(pa, ab) / max(dot(ab, ab), kTinyM * kTinyM), 0.0, 1.0);
  vec3 eb = pb - bc * clamp(dot(pb, bc) / max(dot(bc, bc), kTinyM * kTinyM), 0.0, 1.0);
  vec3 ec = pc - ca * clamp(dot(pc, ca) / max(dot(ca, ca), kTinyM * kTinyM), 0.0, 1.0);
  return sqrt(min(min(dot(ea, ea), dot(eb, eb)), dot(ec, ec)));
}

// Distance (m) from p to an axis-aligned box (0 inside).
float boxDistance(vec3 p, vec3 lo, vec3 hi) { return length(max(max(lo - p, p - hi), 0.0)); }

// The distance the march steps by: the grid's trilinear sample inside the grid (signed, m), a
// lower bound outside it, and the exact distance to every sheet triangle; the smallest.
// SdfVolume::distance is the CPU twin.
float sdfDistance(vec3 ws) {
  float d = 3.0e38;
  if (u_sdf.gridSize.w > 0.5) {
    // Outside the grid, two lower bounds: the distance to the grid's nearest point less the
    // way there (1-Lipschitz), tight near the grid, and the distance to the casters' box.
    vec3 lo = u_sdf.gridLo.xyz, hi = lo + u_sdf.gridSize.xyz;
    vec3 q = clamp(ws, lo, hi);
    d = textureLod(s_sdf, (q - lo) / u_sdf.gridSize.xyz, 0.0).r;  // one level
    if (q != ws) d = max(d - distance(q, ws), boxDistance(ws, u_sdf.gridCasterLo.xyz, u_sdf.gridCasterHi.xyz));
  }
  for (int i = 0; i < u_sdf.sheetInfo.x; ++i)
    d = min(d, triangleDistance(ws, u_sdf.sheetVertices[3 * i].xyz, u_sdf.sheetVertices[3 * i + 1].xyz,
                                u_sdf.sheetVertices[3 * i + 2].xyz));
  return d;
}

// True when the segment origin + t·dir, t in (0, tEnd), passes through a sheet triangle
// (Möller–Trumbore). A sheet has no inside for the march to find, so it is tested once.
bool crossesSheet(vec3 origin, vec3 dir, float tEnd) {
  for (int i = 0; i < u_sdf.sheetInfo.x; ++i) {
    vec3 a = u_sdf.sheetVertices[3 * i].xyz;
    vec3 e1 = u_sdf.sheetVertices[3 * i + 1].xyz - a, e2 = u_sdf.sheetVertices[3 * i + 2].xyz - a;
    vec3 pv = cross(dir, e2);
    float det = dot(e1, pv);
    if (abs(det) < kTinyM * kTinyM) continue;  // parallel to the sheet
    vec3 tv = origin - a;
    float u = dot(tv, pv) / det;
    vec3 qv = cross(tv, e1);
    float v = dot(dir, qv) / det;
    float t = dot(e2, qv) / det;
    if (u >= 0.0 && v >= 0.0 && u + v <= 1.0 && t > 0.0 && t < tEnd) return true;
  }
  return false;
}

// [enter, exit] ray lengths of origin + t·dir inside the box [lo, hi]; enter > exit when it misses.
vec2 boxInterval(vec3 origin, vec3 dir, vec3 lo, vec3 hi) {
  vec3 safeDir = mix(dir, vec3(kParallelDir), lessThan(abs(dir), vec3(kParallelDir)));
  vec3 t0 = (lo - origin) / safeDir;
  vec3 t1 = (hi - origin) / safeDir;
  vec3 near = min(t0, t1), far = max(t0, t1);
  return vec2(max(max(near.x, near.y), near.z), min(min(far.x, far.y), far.z));
}

// Penumbra hardness at a receiver. Light mode: the light's angular radius α seen from ws
// (sun: its angular radius; sphere of radius R at distance D: sin α = R / D), k = 1 / tan α,
// so that k·d/t = 1 exactly where the ray clears every caster by the light's own angle.
float penumbraK(vec3 ws) {
  if (u_sdf.mode.y == PN_SDF_K_MANUAL) return u_sdf.march.x;
  float size = u_frame.light.radiance.w;
  float tanAlpha;
  if (isPositionalLight()) {
    float sinAlpha = min(size / max(distance(u_frame.light.position.xyz, ws), kTinyM), 1.0);
    tanAlpha = sinAlpha / sqrt(max(1.0 - sinAlpha * sinAlpha, kTinyM));
  } else {
    tanAlpha = tan(size);
  }
  return min(1.0 / max(tanAlpha, kTinyM), u_sdf.march.w);
}

// Visible fraction of a uniform disc whose centre lies x radii (x in [-1, 1]) beyond a straight
// edge: 1/2 + (x·sqrt(1 − x²) + asin x) / π. The centered penumbra's profile.
float discVisibleFraction(float x) {
  x = clamp(x, -1.0, 1.0);
  return 0.5 + (x * sqrt(1.0 - x * x) + asin(x)) / kPi;
}

float shadowVisibility(SurfacePoint s) {
  if (u_sdf.gridSize.w < 0.5 && u_sdf.sheetInfo.x == 0) return 1.0;  // no casters
  float voxelM = u_sdf.gridLo.w;
  vec3 origin = s.ws + s.geoNormal * (u_sdf.march.z * voxelM);
  vec3 dir;
  float tLight;
  if (isPositionalLight()) {
    vec3 toCentre = u_frame.light.position.xyz - origin;
    float distanceM = length(toCentre);
    dir = toCentre / max(distanceM, kTinyM);
    tLight = distanceM - u_frame.light.radiance.w;  // the light's sphere is not an occluder
  } else {
    dir = -u_frame.light.direction.xyz;
    tLight = 3.0e38;
  }
  // Nothing occludes outside the casters' bounds: the march is confined to them.
  vec2 span = boxInterval(origin, dir, u_sdf.castersLo.xyz, u_sdf.castersHi.xyz);
  float tEnd = min(span.y, tLight);
  float t = max(span.x, 0.0);
  if (t >= tEnd) return 1.0;
  if (crossesSheet(origin, dir, tEnd)) return 0.0;

  float k = penumbraK(s.ws);
  float epsilonM = u_sdf.march.y * voxelM;
  bool centered = u_sdf.mode.w == PN_SDF_PENUMBRA_CENTERED;
  bool improved = u_sdf.mode.z == PN_SDF_ESTIMATOR_IMPROVED;
  float lowest = 1.0;         // min over the samples of k·d/t
  float previousM = -1.0;     // the previous sample's distance (< 0: none usable)
  float stepM = 0.0;          // the distance from the previous sample
  for (int i = 0; i < u_sdf.mode.x; ++i) {
    float d = sdfDistance(origin + t * dir);
    if (!centered && d < epsilonM) return 0.0;  // reached a caster: umbra
    float estimate = k * d / max(t, kTinyM);
    if (improved && d > 0.0 && previousM > 0.0) {
      // Both samples' spheres are free of casters; the closest a caster can come to the ray
      // between them is on the circle where the spheres meet: y back from this sample along
      // the ray, at distance sqrt(d² − y²) from it. Only when that circle lies between them.
      float y = (stepM * stepM + d * d - previousM * previousM) / (2.0 * stepM);
      if (y > 0.0 && y < min(d, stepM)) estimate = k * sqrt(d * d - y * y) / max(t - y, kTinyM);
    }
    lowest = min(lowest, estimate);
    if (centered && lowest <= -1.0) return 0.0;  // the whole light is behind the caster
    previousM = d;
    // Inside a caster (centered mode) a step of |d| cannot leave it (1-Lipschitz field).
    stepM = max(abs(d), epsilonM);
    t += stepM;
    if (t >= tEnd) break;
  }
  return centered ? discVisibleFraction(lowest) : clamp(lowest, 0.0, 1.0);
}
