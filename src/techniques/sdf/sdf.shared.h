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

// Flat caster sheets (floors) measured exactly in the shader, in triangles (src/bake/SdfBake.h)
#define PN_SDF_MAX_SHEET_TRIANGLES 16

PN_GPU_BEGIN

struct SdfUniforms {
  vec4 gridLo;        // xyz: world min corner of the grid (m); w: voxel edge (m)
  vec4 gridSize;      // xyz: world extent of the grid (m); w: 1 when there is a grid, 0 = only sheets or nothing
  vec4 gridCasterLo;  // xyz: the grid's casters' bounds (the grid less its padding): outside the grid,
  vec4 gridCasterHi;  //      the distance to this box bounds the distance to them from below
  vec4 castersLo;     // xyz: bounds of every caster (grid and sheets): the march never leaves them
  vec4 castersHi;
  vec4 march;         // x: k (manual); y: epsilon (voxels); z: start offset (voxels); w: largest k (light mode)
  ivec4 mode;         // x: max steps; y: PN_SDF_K_*; z: PN_SDF_ESTIMATOR_*; w: PN_SDF_PENUMBRA_*
  ivec4 sheetInfo;    // x: sheet triangles in use (0 = no casters at all when gridSize.w = 0); yzw: unused
  vec4 sheetVertices[3 * PN_SDF_MAX_SHEET_TRIANGLES];  // xyz: world-space vertices (m), three per triangle
};

PN_GPU_END

#ifdef __cplusplus
static_assert(sizeof(penumbra::gpu::SdfUniforms) == (9 + 3 * PN_SDF_MAX_SHEET_TRIANGLES) * 16, "std140 size of SdfUniforms");
static_assert(offsetof(penumbra::gpu::SdfUniforms, sheetVertices) == 9 * 16, "std140 offset of sheetVertices");
#endif
