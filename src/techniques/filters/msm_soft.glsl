// msm-soft: moment soft shadows (after Peters et al. 2016, "Moment Soft Shadow Mapping"). VSSM's
// O(1) structure with four moments: box means of (z, z², z³, z⁴) from a summed-area table, exact
// in 64-bit fixed point (common/sat.glsl). (1) Blocker search: over the PCSS search region
// (common/penumbra.glsl), the three-point distribution with these moments that has a point at the
// receiver depth t; its points in front of t are the blockers and their weighted mean depth is
// z_occ (our simplification of the paper's estimate: no z_unocc = t assumption is needed);
// (2) penumbra width from z_occ by similar triangles; (3) visibility = 1 − the Hamburger 4MSM
// bound over the penumbra-sized box. Linear light depth per view. Artifacts: far less bleeding
// than vssm; the bound's slack still lightens the inside of overlapping penumbrae.
#include "common/moments.glsl"
#include "common/sat.glsl"
#include "common/soft_receiver.glsl"
#include "techniques/filters/msm_soft.shared.h"

layout(std140, binding = PN_UBO_FILTER) uniform MsmSoftBlock { MsmSoftUniforms u_msmSoft; };
// The SAT is common/sat.glsl's storage buffer: two pair layers per view.

// Box means of (z, z², z³, z⁴) over half-size radiusUv around uv in `view`, biased by alpha. `exact`: a
// box with fractional edges (the filter); otherwise edges snap to whole texels (the blocker
// search: 8 texel fetches instead of 32).
vec4 regionMoments(int view, vec2 uv, vec2 radiusUv, float alpha, bool exact) {
  ivec2 size = ivec2(shadowMapSize());
  vec4 b = vec4(vec2(satRegionMean(size, uv, radiusUv, 2 * view, exact)),
                vec2(satRegionMean(size, uv, radiusUv, 2 * view + 1, exact)));
  return biasMoments(b, alpha);
}

float shadowVisibility(SurfacePoint s) {
  SoftReceiver r;
  if (!softReceiverNoRecord(s, u_msmSoft.params.z, u_msmSoft.params.w, r)) return 1.0;
  float t = r.coord.z - u_msmSoft.params.y;
  float alpha = floorMomentBias(texelDepthVariance(r.view, s.ws, u_msmSoft.params.x), false);  // solved in float32

  // (1) Moment-based blocker search.
  vec2 blocker = momentBlockerDepth(regionMoments(r.view, r.coord.xy, softSearchRegionUv(s, r), alpha, false), t);
  if (blocker.y < kMinBlockerFraction) return 1.0;

  // (2) Penumbra; (3) filtering over it.
  return 1.0 - hamburgerShadowIntensity(regionMoments(r.view, r.coord.xy, softFilterRadiusUv(s, r, blocker.x), alpha, true), t);
}
