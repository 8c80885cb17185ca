// msm-soft: moment soft shadows (after Peters et al. 2016, "Moment Soft Shadow Mapping"). VSSM's
// O(1) structure with four moments: box means of (z, z², z³, z⁴) from a summed-area table, exact
// in 64-bit fixed point (common/sat.glsl). (1) Blocker search: over the PCSS search region
// (common/penumbra.glsl), the three-point distribution with these moments that has a point at the
// receiver depth t; its points in front of t are the blockers and their weighted mean depth is
// z_occ (our simplification of the paper's estimate: no z_unocc = t assumption is needed);
// (2) penumbra width from z_occ by similar triangles; (3) visibility = 1 − the Hamburger 4MSM
// bound over the penumbra-sized box. Linear light depth per view. Artifacts: far less bleeding
// than vssm; the bound's slack still lightens the inside of overlapping penumbrae.
#include "common/depth_compare.glsl"
#include "common/moments.glsl"
#include "common/penumbra.glsl"
#include "common/sat.glsl"
#include "common/visibility.glsl"
#include "techniques/filters/msm_soft.shared.h"

layout(std140, binding = PN_UBO_FILTER) uniform MsmSoftBlock { MsmSoftUniforms u_msmSoft; };
// The SAT is common/sat.glsl's storage buffer: two pair layers per view.

// Box means of (z, z², z³, z⁴) over half-size radiusUv around uv in `view`, biased by alpha. `exact`: a
// box with fractional edges (the filter); otherwise edges snap to whole texels (the blocker
// search: 8 texel fetches instead of 32).
vec4 regionMoments(int view, vec2 uv, vec2 radiusUv, float alpha, bool exact) {
  ivec2 size = ivec2(shadowMapSize());
  vec2 lo, hi;
  satCentredBox(size, uv * vec2(size), radiusUv * vec2(size), lo, hi);
  vec4 b = exact ? vec4(vec2(satBoxMean(size, lo, hi, 2 * view)), vec2(satBoxMean(size, lo, hi, 2 * view + 1)))
                 : vec4(vec2(satBoxMeanSnapped(size, lo, hi, 2 * view)), vec2(satBoxMeanSnapped(size, lo, hi, 2 * view + 1)));
  return biasMoments(b, alpha);
}

float shadowVisibility(SurfacePoint s) {
  int view = selectShadowView(s.ws);
  vec3 coord = shadowCoord(view, s.ws);
  if (!insideMap(coord)) return 1.0;
  coord = coordInsideMap(view, s, coord, ivec2(shadowMapSize()));
  float lightSize = u_frame.light.radiance.w;
  float t = coord.z - u_msmSoft.params.y;
  float texelUv = 1.0 / shadowMapSize();
  vec2 minRadiusUv = vec2(u_msmSoft.params.z * texelUv), maxRadiusUv = vec2(u_msmSoft.params.w * texelUv);
  float alpha = floorMomentBias(texelDepthVariance(view, s.ws, u_msmSoft.params.x), false);  // solved in float32

  // (1) Moment-based blocker search.
  vec2 searchUv = blockerSearchRegionUv(view, s.ws, coord.xy, lightSize, minRadiusUv, maxRadiusUv);
  vec2 blocker = momentBlockerDepth(regionMoments(view, coord.xy, searchUv, alpha, false), t);
  if (blocker.y < kMinBlockerFraction) return 1.0;

  // (2) Penumbra; (3) filtering over it.
  vec2 radiusUv = clamp(0.5 * penumbraWidthUv(view, s.ws, blocker.x, lightSize), minRadiusUv, maxRadiusUv);
  return 1.0 - hamburgerShadowIntensity(regionMoments(view, coord.xy, radiusUv, alpha, true), t);
}
