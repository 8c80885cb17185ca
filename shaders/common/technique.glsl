#pragma once
// What a technique folder's GLSL includes first (docs/own-technique.md, "The visibility
// contract"). It brings everything a visibility function may read, and nothing else:
//  - the surface: SurfacePoint (position, geometric normal, direction to the light, N·L, pixel),
//    common/visibility.glsl;
//  - the light's views: selectShadowView, shadowCoord, insideMap (insideViewMap: the view's part of its map), lightDepth, shadowMapSize,
//    shadowTexelWorldSize, texelDepthVariance, … (common/shadow.glsl);
//  - the frame: lightKind(), isPointLight(), samplingFrame(), the camera (common/frame.glsl);
//  - noise: interleavedGradientNoise, pixelRotation, the Poisson disk (common/sampling.glsl);
//  - its parameters: PARAM_<name>, a float (an int for integers and choices; choice k is also
//    PARAM_<name>_<choice> = k), read from the technique's uniform block or, for "constant"
//    parameters, a compile-time constant;
//  - the maps its description lists: pn_depthMap (always: linear light depth of the nearest
//    caster, a sampler2DArray, one layer per view), pn_depthCompareMap (the same texture through
//    a hardware comparison sampler), pn_moments ("moments" / "moments4": (z, z²[, z³, z⁴]),
//    with a mip chain under "mips"), pn_minDepth ("min-depth": common/penumbra.glsl's
//    pyramid, which its blockerSearchRegionUv then uses) and the summed-area table ("sat": common/sat.glsl's satCorner…).
// It must define   float shadowVisibility(SurfacePoint s);   // 0 = shadowed … 1 = lit
#include "common/sampling.glsl"
#include "common/visibility.glsl"

layout(std140, binding = PN_UBO_FILTER) uniform TechniqueBlock { vec4 pn_techniqueParams[PN_TECHNIQUE_PARAM_VEC4S]; };

layout(binding = PN_TEX_FILTER0) uniform sampler2DArray pn_depthMap;
layout(binding = PN_TEX_FILTER1) uniform sampler2DArrayShadow pn_depthCompareMap;
#ifdef PN_TECHNIQUE_MOMENTS
layout(binding = PN_TEX_FILTER3) uniform sampler2DArray pn_moments;
#endif
#ifdef PN_TECHNIQUE_MIN_DEPTH
// The pyramid as the built-in soft filters read it: blockerSearchRegionUv tightens its search.
#define PN_TIGHT_SEARCH
#include "common/penumbra.glsl"
#define pn_minDepth s_minDepth
#endif
#ifdef PN_TECHNIQUE_SAT
#include "common/sat.glsl"
#endif
