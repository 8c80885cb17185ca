#pragma once
// The sdf filter's uniform block and enum values, declared once for C++ and GLSL.
#include "shared/Cpp.h"

// sdf.kMode: where the penumbra hardness k comes from
#define PN_SDF_K_MANUAL 0  // sdf.k as set
#define PN_SDF_K_LIGHT 1   // 1 / tan(angular radius of the light seen from the receiver)

// sdf.estimator: how each march step bounds the visible angle
#define PN_SDF_ESTIMATOR_CLASSIC 0   // k · d / t at the sample (Quilez)
#define PN_SDF_ESTIMATOR_IMPROVED 1  // k · d' / t' at the estimated closest point between two samples (Aaltonen)

// sdf.penumbra: which side of the shadow edge the penumbra lies on
#define PN_SDF_PENUMBRA_OUTER 0     // V = min(k d / t, 1): the penumbra lies outside the hard shadow
#define PN_SDF_PENUMBRA_CENTERED 1  // the march goes on inside casters (d < 0); V = smoothstep(-1, 1, min k d / t)

PN_GPU_BEGIN

struct SdfUniforms {
  vec4 gridLo;    // xyz: world min corner of the grid (m); w: voxel edge (m)
  vec4 gridSize;  // xyz: world extent of the grid (m); w: 1 when there is a field, 0 = no casters (V = 1)
  vec4 march;     // x: k (manual); y: epsilon (voxels); z: start offset (voxels); w: largest k (light mode)
  ivec4 mode;     // x: max steps; y: PN_SDF_K_*; z: PN_SDF_ESTIMATOR_*; w: PN_SDF_PENUMBRA_*
};

PN_GPU_END

#ifdef __cplusplus
static_assert(sizeof(penumbra::gpu::SdfUniforms) == 4 * 16, "std140 size of SdfUniforms");
#endif
