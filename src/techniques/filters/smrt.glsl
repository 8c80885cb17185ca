// smrt: shadow-map ray tracing (as Unreal Engine 5 and Blender's EEVEE trace soft shadows
// through their shadow maps). From each receiver, rays toward points spread over the light's
// disk (a spot or point light's sphere as the receiver sees it, the sun's cone of directions),
// each marched through the map in PN_SMRT_STEPS steps; V is the share of the rays above the
// receiver's horizon that reach the light. The map holds one surface per texel, the one nearest
// the light's centre, and what lies behind it is unknown: a step is blocked where a caster lies
// in front of the ray by less than smrt.thicknessM, or where the ray has crossed a caster's
// surface since the previous step. The march runs from the receiver to the nearest surface in
// the light's footprint (a min-depth pyramid); none in front of the receiver: V = 1 without a
// ray. A probe of PN_SMRT_PROBE_RAYS rays decides lit and umbra pixels; the others trace
// PN_SMRT_RAYS. Linear light depth per view; a step that leaves the receiver's map reads a
// coarser cascade or a point light's neighbouring face.
// Artifacts: a ray behind a caster by less than the thickness is blocked even where it passes
// under a thinner caster, and a ray that leaves a caster through a side the light's centre does
// not see passes between two steps; noise of a few rays (stratified, turned per pixel and per
// frame: temporal.* averages it); cost grows with rays × steps, on penumbra pixels only.
#include "common/depth_compare.glsl"
#include "common/penumbra.glsl"
#include "techniques/filters/smrt.shared.h"

layout(std140, binding = PN_UBO_FILTER) uniform SmrtBlock { SmrtUniforms u_smrt; };
layout(binding = PN_TEX_FILTER0) uniform sampler2DArray s_depthMap;

// Rounds of the nearest-surface search (each at most four pyramid reads); the third shrank the
// region little on the built-in scenes.
const int kNearestRounds = 3;

// The probe's ring, in radii of the light's disk: a straight shadow edge that crosses the disk
// leaves points of this circle on both of its sides when they are at most 2·acos(1/1.25) = 74
// degrees apart.
const float kProbeRadius = 1.25;

// The golden ratio's fraction: successive rays' step offsets spread evenly over [0, 1).
const float kGoldenFraction = 0.61803398875;

// The view whose map holds the march's point p, and p's shadow coordinate there: the receiver's
// view while p stays in its map; past its edge, a point light's face in p's direction or the
// first coarser cascade that holds p. -1: no map holds p, and the step reads nothing.
int marchView(int view, vec3 p, out vec3 coord) {
  coord = shadowCoord(view, p);
  if (insideViewMap(view, coord)) return view;
#if !defined(PN_SHADOW_VIEWS) || PN_SHADOW_VIEWS > 1
  if (isPointLight()) {
    int face = cubeFaceView(p, view);
    coord = shadowCoord(face, p);
    return insideViewMap(face, coord) ? face : -1;
  }
  for (int v = view + 1; v < shadowViewCount(); ++v) {
    coord = shadowCoord(v, p);
    if (insideMap(coord)) return v;
  }
#endif
  return -1;
}

// The linear depth the map of `view` stores at uv.
float marchStoredDepth(int view, vec2 uv) { return fetchMapDepth(s_depthMap, mapTexel(s_depthMap, uv, view)); }

// Whether the surface the map of `view` stores at coord.xy (linear depth `stored`) can cast on the
// receiver r: it lies in front of the receiver's tangent plane there by more than r's bias (pcf's
// receiver-plane test: the receiver's own surface, at any distance along the ray, is never a
// caster). In another view than the receiver's the plane is not followed.
bool isCaster(ComparisonReceiver r, int view, vec3 coord, float stored) {
  return view != r.layer || stored < r.depth + dot(r.depthPerUv, coord.xy - r.uv) - r.bias;
}

// The ray origin + t·dir, t in [0, tEnd], marched in PN_SMRT_STEPS steps, jittered and spaced by a
// smoothstep: dense near the receiver, where contact shadows are decided, and near the march's
// end, the nearest caster; the last step is at tEnd. True at the first step where the ray meets a
// caster: one lies in front of the ray by less than smrt.thicknessM (along the light's axis), or
// the ray has crossed one since the previous step (it was behind a caster then, and the caster at
// this step lies in front of where the ray was: not a deeper surface past an outline).
// receiverBehind: the receiver itself lies behind a caster (t = 0).
bool rayBlocked(ComparisonReceiver r, vec3 origin, vec3 dir, float tEnd, float jitter, bool receiverBehind) {
  float steps = float(PN_SMRT_STEPS);
  int previousView = r.layer;
  float previousDepth = r.depth;
  bool behind = receiverBehind;
  for (int i = 1; i <= PN_SMRT_STEPS; ++i) {
    float s = min((float(i) + jitter) / steps, 1.0);
    vec3 coord;
    int v = marchView(r.layer, origin + dir * (smoothstep(0.0, 1.0, s) * tEnd), coord);
    if (v < 0) {
      behind = false;
      continue;
    }
    float stored = marchStoredDepth(v, coord.xy);
    bool caster = isCaster(r, v, coord, stored);
    if (caster && stored < coord.z) {
      if ((coord.z - stored) * depthRangeM(v) < u_smrt.params.z) return true;
    } else if (caster && behind && v == previousView && stored < previousDepth) {
      return true;
    }
    behind = caster && stored < coord.z;
    previousView = v;
    previousDepth = coord.z;
  }
  return false;
}

// The ray from ws toward the light's sample at `unit` (a point of the unit disk), as a direction
// whose t = 1 is the sample itself for a spot or point light (a point of the disk that the
// sphere of radius lightSize shows from ws: the cone of directions it subtends, cut at its
// centre) and one metre for the sun (the cone of half angle lightSize, cut at one metre).
vec3 lightSampleRay(vec3 ws, vec3 axis, vec3 t1, vec3 t2, vec2 unit, float lightSize) {
  if (isPositionalLight()) {
    vec3 centre = u_frame.light.position.xyz;
    float d = distance(centre, ws);
    float discRadiusM = lightSize * d / sqrt(max(d * d - lightSize * lightSize, kMinLightDistanceM));
    return centre + discRadiusM * (unit.x * t1 + unit.y * t2) - ws;
  }
  return axis + tan(lightSize) * (unit.x * t1 + unit.y * t2);
}

// The rays of one pass: `count` points of a sunflower over the light's disk, or (ring) count − 1
// points evenly around a circle of kProbeRadius disks and the disk's centre, turned by
// `rotation`; adds to the rays above the receiver's horizon and to those of them that reach the
// light. `first` numbers the pass's rays after the earlier passes' (their step offsets differ).
void traceRays(SurfacePoint s, ComparisonReceiver r, float endDepth, bool receiverBehind, int count, int first,
               bool ring, mat2 rotation, float jitter, inout int above, inout int open) {
  float lightSize = u_frame.light.radiance.w;
  vec3 axis = s.toLight;
  vec3 t1 = normalize(cross(axis, abs(axis.y) < 0.9 ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 0.0, 0.0)));
  vec3 t2 = cross(axis, t1);
  vec3 depthPerM = u_shadow.views[r.layer].depthPlane.xyz;
  for (int i = 0; i < count; ++i) {
    float angle = 6.28318530718 * float(i) / float(max(count - 1, 1));
    vec2 unit = ring ? (i == count - 1 ? vec2(0.0) : kProbeRadius * vec2(cos(angle), sin(angle))) : sunflowerDiskTap(i, count);
    vec3 dir = lightSampleRay(s.ws, axis, t1, t2, rotation * unit, lightSize);
    if (dot(dir, s.geoNormal) <= 0.0) continue;  // below the receiver's horizon: no light from there
    ++above;
    float depthPerT = dot(depthPerM, dir);
    // t where the ray reaches the march's end (depthPerT < 0: the ray rises toward the light).
    float tEnd = depthPerT < 0.0 ? (endDepth - r.depth) / depthPerT : 0.0;
    if (isPositionalLight()) tEnd = min(tEnd, 1.0);
    if (tEnd <= 0.0 || !rayBlocked(r, s.ws, dir, tEnd, fract(jitter + float(first + i) * kGoldenFraction), receiverBehind))
      ++open;
  }
}

float shadowVisibility(SurfacePoint s) {
  int view = selectShadowView(s.ws);
  vec3 coord = shadowCoord(view, s.ws);
  if (!insideViewMap(view, coord)) return 1.0;
  float lightSize = u_frame.light.radiance.w;
  if (isPositionalLight() && distance(u_frame.light.position.xyz, s.ws) <= lightSize) return 1.0;  // inside the light
  ComparisonReceiver r = comparisonReceiver(view, s, coord, u_smrt.params.x, u_smrt.params.y, 0.0);

  // Where the march ends: at the nearest surface in the light's footprint. The footprint on the
  // near plane holds every caster a ray can meet; the pyramid's minimum over it is the nearest
  // surface there, and as no caster is nearer, the footprint at that depth holds them all:
  // kNearestRounds such rounds shrink the region to the casters around the receiver.
#ifdef PN_TIGHT_SEARCH
  const vec2 kWholeMapUv = vec2(1.0);  // a region this wide reads the pyramid's top level
  vec2 regionUv = min(blockerSearchRadiusUv(view, s.ws, lightSize), kWholeMapUv);
  float endDepth = minDepthOverBox(s_minDepth, view, coord.xy, regionUv, shadowMapSize());
  for (int k = 1; k < kNearestRounds && endDepth < coord.z; ++k) {
    regionUv = min(lightFootprintRadiusUv(view, s.ws, viewDistanceM(view, endDepth), lightSize), regionUv);
    endDepth = max(endDepth, minDepthOverBox(s_minDepth, view, coord.xy, regionUv, shadowMapSize()));
  }
#else
  // No pyramid: the march runs to the near plane, every caster in front of the receiver within its
  // reach.
  float endDepth = 0.0;
#endif
  if (endDepth >= coord.z - r.bias) return 1.0;  // nothing in front of the receiver that a ray can meet

  mat2 rotation = pixelRotation(s.pixel, samplingFrame());
  float jitter = pixelNoise(s.pixel.yx, samplingFrame());
  float atReceiver = marchStoredDepth(view, coord.xy);
  bool receiverBehind = isCaster(r, view, coord, atReceiver) && atReceiver < coord.z;
  int above = 0, open = 0;
  if (lightSize > 0.0) {
    // A probe first: rays toward the disk's centre and a ring around it. Where they all agree the
    // light's disk lies wholly on one side of any straight shadow edge: V = 0 or 1. Otherwise
    // (a penumbra) the sunflower's rays alone give V.
    if (PN_SMRT_PROBE_RAYS > 0) {
      traceRays(s, r, endDepth, receiverBehind, PN_SMRT_PROBE_RAYS, 0, true, rotation, jitter, above, open);
      if (above > 0 && (open == 0 || open == above)) return open == 0 ? 0.0 : 1.0;
      above = open = 0;
    }
    traceRays(s, r, endDepth, receiverBehind, PN_SMRT_RAYS, PN_SMRT_PROBE_RAYS, false, rotation, jitter, above, open);
  }
  // A hard light, or every sample below the horizon (a grazing receiver): the ray toward the
  // light's centre decides (a ring of one ray is its centre).
  if (above == 0) traceRays(s, r, endDepth, receiverBehind, 1, 0, true, rotation, jitter, above, open);
  return float(open) / float(above);
}
