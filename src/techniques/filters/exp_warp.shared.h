#pragma once
// Exponential depth warps (esm, evsm, evsm-soft), written once for C++ and GLSL: the warps, the
// exponents each storage format can hold, and the warp shadow pass's uniform block.
// Linear light depth z in [0, 1] is rescaled to z' = 2z − 1 in [−1, 1] (so a warp spans e^-c …
// e^c, symmetric about 1, and the exponents read as Lauritzen's, MJP's and Filament's) and warped:
//   positive  p(z) = exp(c+ · z')      esm stores p; evsm stores p and p²
//   negative  n(z) = −exp(−c− · z')    evsm with 4 components also stores n and n²
// Both increase with z, so "z >= t" is "p >= p(t)" and "n >= n(t)".
#include "shared/Cpp.h"

#ifdef __cplusplus
#include <glm/exponential.hpp>
#endif

// The largest |log| of a stored value, per storage format. A filter stores powers 1 (esm) or 1
// and 2 (evsm) of a warp, so its exponent is at most this / the highest power.
//  float32: e^86 = 2.2e37 and e^-86 = 4.5e-38 are normal floats (FLT_MIN 1.2e-38), and the
//    visibility's arithmetic stays finite: σ² + (t − μ)² <= e^86 + (2·e^43)² = 1.1e38 < FLT_MAX
//    3.4e38. So esm's c <= 86, evsm's c+, c− <= 43.
//  float16: e^11 = 59874 < 65504, the largest half, and rounds to a finite half (>= 65520 rounds
//    to infinity); e^-11 = 1.7e-5 is subnormal (spacing 6e-8: 0.4 % relative), the price of the
//    range. evsm's c+, c− <= 5.5 (Filament and MJP clamp to 5.54, whose e^11.08 = 64,950 leaves
//    no room for the slope term below).
#define PN_EXP_WARP_MAX_LOG_FLOAT32 86.0f
#define PN_EXP_WARP_MAX_LOG_FLOAT16 11.0f

// The smallest variance a warp's Chebyshev bound uses, relative to the receiver's warp squared,
// from the storage's rounding: E[w²] − E[w]² cancels, and each stored moment is off by half an
// ulp (float32 2^-24, float16 2^-11 relative), so a flat region's variance reads ± 2 ulp of w².
#define PN_EXP_WARP_MIN_RELATIVE_VARIANCE_FLOAT32 1e-6f
#define PN_EXP_WARP_MIN_RELATIVE_VARIANCE_FLOAT16 1e-3f

PN_GPU_BEGIN

#ifdef __cplusplus
using glm::exp;
#endif

// The warp shadow pass's block (passes/exp_warp.frag.glsl), bound at PN_UBO_FILTER while it draws.
struct ExpWarpUniforms {
  vec4 warp;  // x: c+ (positive exponent), y: c− (negative exponent), z: the largest value stored
              // (e^max log: a second moment with its slope term is clamped to it), w: unused
};

PN_SHARED_FN float warpDepth(float z) { return 2.0f * z - 1.0f; }
PN_SHARED_FN float positiveWarp(float z, float c) { return exp(c * warpDepth(z)); }
PN_SHARED_FN float negativeWarp(float z, float c) { return -exp(-c * warpDepth(z)); }

// (p, p², n, n²) of depth z: the moments of one texel, before the slope term.
PN_SHARED_FN vec4 expWarpMoments(float z, float cPositive, float cNegative) {
  float p = positiveWarp(z, cPositive);
  float n = negativeWarp(z, cNegative);
  return vec4(p, p * p, n, n * n);
}

PN_GPU_END

#ifdef __cplusplus
static_assert(sizeof(penumbra::gpu::ExpWarpUniforms) == 16, "std140 size of ExpWarpUniforms");
#endif
