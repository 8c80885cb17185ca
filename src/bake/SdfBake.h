#pragma once
// The CPU bake of the distance-field shadow technique (docs/sdf.md), cached on disk.
//  - Distance: exact unsigned distance to the nearest caster triangle at every voxel centre,
//    from Embree 3 point queries (rtcPointQuery + a closest-point-on-triangle callback).
//  - Sign: ray-cast winding numbers. One ray per grid line along each axis collects every caster
//    crossing with its facing; each voxel gets six votes (±x, ±y, ±z: the signed crossing count
//    between it and either end of its line) and is inside when at least four votes say so.
//    Closed meshes, overlapping closed meshes and either winding order come out right; an open
//    sheet (a floor plane, a single quad) is never "inside" from more than one direction, so it
//    gets positive distance on both sides: a zero-thickness occluder, which the march still
//    stops at (distance → 0).
//  - Open flat sheets (a caster object whose triangles all lie in one plane: floors, ground
//    quads) are kept out of the grid, up to kMaxSheetTriangles in all: the shader measures the
//    exact distance to their triangles instead. A 24 m floor would otherwise stretch the grid
//    and leave the objects standing on it a voxel or two thick.
//  - Alpha-masked materials are treated as solid (the field has no holes).
#include "frame/CasterSet.h"
#include "techniques/sdf/SdfVolume.h"

#include <penumbra/Bake.h>

#include <filesystem>

namespace penumbra::sdf {

/// Bakes without touching the cache. Throws penumbra::Error on a bad resolution or an Embree failure.
SdfVolume bake(std::span<const CasterGeometry> casters, const BakeOptions& options = {});

/// The cached grid for these casters and resolution when a valid cache file exists; otherwise
/// bakes it and stores it (temporary name, then rename). Unreadable or corrupt files are ignored
/// and replaced. Throws penumbra::Error when the cache directory cannot be created or written.
SdfVolume loadOrBake(std::span<const CasterGeometry> casters, const BakeOptions& options = {});

/// The same for a scene's casting objects.
inline SdfVolume bake(const Scene& scene, const BakeOptions& options = {}) { return bake(casterGeometry(scene), options); }
inline SdfVolume loadOrBake(const Scene& scene, const BakeOptions& options = {}) {
  return loadOrBake(casterGeometry(scene), options);
}

/// "<dir>/sdf-<key>.bin"
std::filesystem::path cacheFilePath(const std::filesystem::path& dir, uint64_t key);

}  // namespace penumbra::sdf
