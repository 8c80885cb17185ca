// sdf: distance-field soft shadows. No shadow map: a ray leaves the receiver toward the light
// and sphere-traces (Hart 1996) a signed distance field of the casters baked once per scene
// (SdfBake.h). At ray length t the free distance d keeps every caster at least the angle ≈ d/t
// off the ray, so the smallest k·d/t along the ray ("safe angle", Quilez 2010) estimates how much
// of the light is visible; Aaltonen (2018) places the closest approach between two samples.
// k ≈ 1/tan(angular radius of the light) ties the estimate to the light's physical size.
// Assumptions: world-space field in metres, cubic voxels, nothing casts outside the grid.
// Artifacts: shapes thinner than a voxel thin out or vanish; banding with few steps; in outer
// mode the whole penumbra lies outside the hard shadow (umbra too large); alpha masks are solid.
#include "common/visibility.glsl"
#include "shadows/sdf/sdf.shared.h"

layout(std140, binding = PN_UBO_FILTER) uniform SdfBlock { SdfUniforms u_sdf; };
layout(binding = PN_TEX_FILTER0) uniform sampler3D s_sdf;

// A ray direction component below this is treated as parallel to the grid's slab (avoids 1/0).
const float kParallelDir = 1e-12;
// Lengths (m) and tangents are divided by at least this: keeps t = 0 and point lights finite.
const float kTinyM = 1e-9;

// Signed distance (m) to the nearest caster; ws inside the grid (clamp-to-edge beyond).
float sdfDistance(vec3 ws) { return texture(s_sdf, (ws - u_sdf.gridLo.xyz) / u_sdf.gridSize.xyz).r; }

// [enter, exit] ray lengths of origin + t·dir inside the grid; enter > exit when it misses.
vec2 gridInterval(vec3 origin, vec3 dir) {
  vec3 safeDir = mix(dir, vec3(kParallelDir), lessThan(abs(dir), vec3(kParallelDir)));
  vec3 t0 = (u_sdf.gridLo.xyz - origin) / safeDir;
  vec3 t1 = (u_sdf.gridLo.xyz + u_sdf.gridSize.xyz - origin) / safeDir;
  vec3 near = min(t0, t1), far = max(t0, t1);
  return vec2(max(max(near.x, near.y), near.z), min(min(far.x, far.y), far.z));
}

// Penumbra hardness at a receiver. Light mode: the light's angular radius α seen from ws
// (sun: its angular radius; sphere of radius R at distance D: sin α = R / D), k = 1 / tan α,
// so that k·d/t = 1 exactly where the ray clears every caster by the light's own angle.
float penumbraK(vec3 ws) {
  if (u_sdf.mode.y == PN_SDF_K_MANUAL) return u_sdf.march.x;
  float size = u_frame.lightRadiance.w;
  float tanAlpha;
  if (isSpotLight()) {
    float sinAlpha = min(size / max(distance(u_frame.lightPosition.xyz, ws), kTinyM), 1.0);
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
  if (u_sdf.gridSize.w < 0.5) return 1.0;  // no casters
  float voxelM = u_sdf.gridLo.w;
  vec3 origin = s.ws + s.geoNormal * (u_sdf.march.z * voxelM);
  vec3 dir;
  float tLight;
  if (isSpotLight()) {
    vec3 toCentre = u_frame.lightPosition.xyz - origin;
    float distanceM = length(toCentre);
    dir = toCentre / max(distanceM, kTinyM);
    tLight = distanceM - u_frame.lightRadiance.w;  // the light's sphere is not an occluder
  } else {
    dir = -u_frame.lightDirection.xyz;
    tLight = 3.0e38;
  }
  // Outside the grid there is no caster within the padding, so the march is confined to it.
  vec2 span = gridInterval(origin, dir);
  float tEnd = min(span.y, tLight);
  float t = max(span.x, 0.0);
  if (t >= tEnd) return 1.0;

  float k = penumbraK(s.ws);
  float epsilonM = u_sdf.march.y * voxelM;
  bool centered = u_sdf.mode.w == PN_SDF_PENUMBRA_CENTERED;
  bool improved = u_sdf.mode.z == PN_SDF_ESTIMATOR_IMPROVED;
  float lowest = 1.0;      // min over the samples of k·d/t
  float previousM = 3.0e38;  // the previous sample's distance
  for (int i = 0; i < u_sdf.mode.x; ++i) {
    float d = sdfDistance(origin + t * dir);
    if (!centered && d < epsilonM) return 0.0;  // reached a caster: umbra
    float estimate;
    if (improved && d > 0.0 && previousM > 0.0) {
      // The spheres of radius previousM (at t − step) and d (at t) overlap; the closest
      // approach of a caster lies on their intersection circle: y back along the ray at
      // distance dd from it.
      float y = d * d / (2.0 * previousM);
      float dd = sqrt(max(d * d - y * y, 0.0));
      estimate = k * dd / max(t - y, kTinyM);
    } else {
      estimate = k * d / max(t, kTinyM);
    }
    lowest = min(lowest, estimate);
    if (centered && lowest <= -1.0) return 0.0;  // the whole light is behind the caster
    previousM = d;
    // Inside a caster (centered mode) a step of |d| cannot leave it (1-Lipschitz field).
    t += max(abs(d), epsilonM);
    if (t >= tEnd) break;
  }
  return centered ? discVisibleFraction(lowest) : clamp(lowest, 0.0, 1.0);
}
