// msm: moment shadow maps (Peters & Klein 2015). The map stores four moments (z, z^2, z^3, z^4)
// of linear light depth — as 32-bit floats, or as 16-bit UNORM in the paper's optimised basis —
// filtered like vsm's two (mip chain, trilinear taps over the pixel footprint widened to
// msm.filterTexels). Visibility is 1 − the Hamburger 4MSM bound: the smallest fraction of depth in
// front of the receiver that any distribution with these moments can have (common/moments.glsl).
// Four moments describe two overlapping occluders at different depths, so far less light bleeds
// than with vsm; what remains is the bound's slack, and the moment bias α lightens shadows a
// little. Costs: twice vsm's storage at 32 bits, and a 3x3 solve and a quadratic per lookup.
// With PN_MSM_TRANSLUCENT (msm.translucent, and some caster translucent) the moments hold the opaque
// casters alone and V is RGB: the opaque casters' V times the translucent casters' transmittance
// exp(−A·F), A the filtered per-channel absorbance over the texel and F the share of the absorbance
// weight in front of the receiver, the Hamburger bound of the weighted moments normalised by their
// zeroth moment (shadows/filters/msm_translucent.frag.glsl writes both maps). One depth
// distribution serves the three channels: exact where the receiver is behind every translucent
// layer or in front of all; between layers of different colours the share is the mean absorbance's.
#ifdef PN_MSM_TRANSLUCENT
#define PN_SHADOW_VALUE vec3
#endif
#include "common/footprint.glsl"
#include "common/moments.glsl"
#include "techniques/filters/msm.shared.h"

layout(std140, binding = PN_UBO_FILTER) uniform MsmBlock { MsmUniforms u_msm; };
layout(binding = PN_TEX_FILTER0) uniform sampler2DArray s_moments;

float opaqueVisibility(SurfacePoint s, int view, vec3 coord) {
  vec4 b = momentsOverFootprint(s_moments, view, s, coord.xy, u_msm.params.z, u_msm.mode.x, PN_FOOTPRINT_PIXEL != 0);
  if (PN_MSM_QUANTIZED != 0) b = dequantizeMoments16(b);
  float alpha = floorMomentBias(texelDepthVariance(view, s.ws, u_msm.params.x), PN_MSM_QUANTIZED != 0);
  return 1.0 - hamburgerShadowIntensity(biasMoments(b, alpha), coord.z - u_msm.params.y);
}

#ifdef PN_MSM_TRANSLUCENT

layout(binding = PN_TEX_FILTER1) uniform sampler2DArray s_translucentMoments;  // Σ w·(z, z², z³, z⁴)
layout(binding = PN_TEX_FILTER2) uniform sampler2DArray s_absorbance;          // (Σ A_r, Σ A_g, Σ A_b, Σ w)

// Below this total weight over the footprint no translucent caster is there: T = 1.
const float kMinAbsorbanceWeight = 1.0e-4;

vec3 translucentTransmittance(SurfacePoint s, int view, vec3 coord) {
  vec4 a = momentsOverFootprint(s_absorbance, view, s, coord.xy, u_msm.params.z, u_msm.mode.x, PN_FOOTPRINT_PIXEL != 0);
  if (a.w < kMinAbsorbanceWeight) return vec3(1.0);
  vec4 b = momentsOverFootprint(s_translucentMoments, view, s, coord.xy, u_msm.params.z, u_msm.mode.x, PN_FOOTPRINT_PIXEL != 0) / a.w;
  float alpha = floorMomentBias(texelDepthVariance(view, s.ws, u_msm.params.x * u_msm.params.w), false);
  float inFront = hamburgerShadowIntensity(biasMoments(b, alpha), coord.z - u_msm.params.y);
  return exp(-a.rgb * inFront);
}

vec3 shadowVisibility(SurfacePoint s) {
  int view = selectShadowView(s.ws);
  vec3 coord = shadowCoord(view, s.ws);
  if (!insideMap(coord)) return vec3(1.0);
  float v = opaqueVisibility(s, view, coord);
  return v > 0.0 ? v * translucentTransmittance(s, view, coord) : vec3(0.0);
}

#else

float shadowVisibility(SurfacePoint s) {
  int view = selectShadowView(s.ws);
  vec3 coord = shadowCoord(view, s.ws);
  if (!insideMap(coord)) return 1.0;
  return opaqueVisibility(s, view, coord);
}

#endif
