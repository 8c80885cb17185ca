#pragma once
// The CPU bake of the distance-field shadow technique (docs/sdf.md): a grid of signed distance
// (m) to the scene's shadow casters, baked once per scene and cached on disk.
//  - Distance: exact unsigned distance to the nearest caster triangle at every voxel centre,
//    from Embree 3 point queries (rtcPointQuery + a closest-point-on-triangle callback).
//  - Sign: ray-cast winding numbers. One ray per grid line along each axis collects every caster
//    crossing with its facing; each voxel gets six votes (±x, ±y, ±z: the signed crossing count
//    between it and either end of its line) and is inside when at least four votes say so.
//    Closed meshes, overlapping closed meshes and either winding order come out right; an open
//    sheet (a floor plane, a single quad) is never "inside" from more than one direction, so it
//    gets positive distance on both sides: a zero-thickness occluder, which the march still
//    stops at (distance → 0).
//  - Alpha-masked materials are treated as solid (the field has no holes).
#include <penumbra/Math.h>
#include <penumbra/Scene.h>

#include <glm/glm.hpp>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <vector>

namespace penumbra::sdf {

/// Version of the bake's maths; part of every cache key. Bump it whenever a change to the code
/// changes the numbers it produces, so that stale cache files are never read.
inline constexpr uint32_t kSdfCodeVersion = 1;
/// Grid resolution limits: voxels along the grid's longest axis.
inline constexpr int kDefaultResolution = 128;
inline constexpr int kMinResolution = 8;
inline constexpr int kMaxResolution = 512;
/// Empty voxels around the casters' bounds on every side, so that trilinear samples next to the
/// outermost caster still interpolate real distances and the march can enter the grid in free space.
inline constexpr int kPadVoxels = 2;
/// A bake slower than this prints its summary line even when not verbose (s).
inline constexpr double kReportBakeSeconds = 2.0;

struct BakeOptions {
  /// Voxels along the longest axis of the casters' bounds (+ padding), in
  /// [kMinResolution, kMaxResolution]. Voxels are cubes; shorter axes get proportionally fewer.
  int resolution = kDefaultResolution;
  bool progress = true;  ///< progress bar on stderr, drawn only when stderr is a terminal
  /// Print the one-line summary (time, memory) on stderr after every bake; otherwise only
  /// bakes longer than kReportBakeSeconds print it. Cache hits never print.
  bool verbose = false;
  bool useCache = true;  ///< read and write the on-disk cache
  /// Where cache files go; empty = $PENUMBRA_CACHE, else $XDG_CACHE_HOME/penumbra, else
  /// ~/.cache/penumbra (no caching when none of these can be formed).
  std::filesystem::path cacheDir;
};

/// What a bake cost. For a cache hit, seconds is the load time and bakeSeconds the original bake's.
struct BakeStats {
  double seconds = 0.0;
  double bakeSeconds = 0.0;
  size_t triangles = 0;
  size_t gridBytes = 0;     ///< the distances kept (float per voxel)
  size_t scratchBytes = 0;  ///< peak of the transient data: sign votes, triangle soup, Embree's BVH
  bool fromCache = false;
  uint64_t cacheKey = 0;
};

/// Signed distance (m) at voxel centres lo + (ijk + 0.5)·voxelM; < 0 inside a caster.
/// Storage order: x fastest, then y, then z (the order glTexImage3D reads).
struct SdfVolume {
  glm::ivec3 dims{0};
  glm::vec3 lo{0.0f};  ///< the grid's min corner (m)
  float voxelM = 0.0f; ///< edge of one cubic voxel (m)
  std::vector<float> distances;
  BakeStats stats;

  bool empty() const { return distances.empty(); }  ///< the scene has no shadow casters
  glm::vec3 size() const { return glm::vec3(dims) * voxelM; }
  glm::vec3 hi() const { return lo + size(); }
  size_t index(int i, int j, int k) const {
    return static_cast<size_t>(i) + static_cast<size_t>(dims.x) * (static_cast<size_t>(j) + static_cast<size_t>(dims.y) * static_cast<size_t>(k));
  }
  float at(int i, int j, int k) const { return distances[index(i, j, k)]; }
  glm::vec3 voxelCenter(int i, int j, int k) const { return lo + (glm::vec3(i, j, k) + 0.5f) * voxelM; }
  /// Trilinear interpolation with clamp-to-edge, like the GPU's sampler3D: the value the
  /// shader sees at ws. Meaningful inside [lo, hi].
  float sample(const glm::vec3& ws) const;
};

/// The world-space triangles of the scene's shadow casters (objects with castsShadow), three
/// vertices each: what the field measures distance to, and what the reference ray-traces.
std::vector<glm::vec3> casterTriangles(const Scene& scene);

/// The grid a bake of `scene` at `resolution` would use (dims, lo, voxelM; no distances):
/// cubic voxels, kPadVoxels of padding around the casters' world bounds. dims = 0 when the scene
/// has no shadow-casting triangles.
SdfVolume gridFor(const Scene& scene, int resolution);

/// Hash of the casters' world-space triangles, the resolution and kSdfCodeVersion: equal keys
/// bake equal grids. Costs one pass over the casters' vertices (~1 ms per 100k triangles).
uint64_t cacheKey(const Scene& scene, int resolution);

/// Bakes without touching the cache. Throws penumbra::Error on a bad resolution or an Embree failure.
SdfVolume bake(const Scene& scene, const BakeOptions& options = {});

/// The cached grid for this scene and resolution when a valid cache file exists; otherwise bakes
/// it and stores it (temporary name, then rename). Unreadable or corrupt files are ignored and
/// replaced. Throws penumbra::Error when the cache directory cannot be created or written.
SdfVolume loadOrBake(const Scene& scene, const BakeOptions& options = {});

/// Exposed for tests: the point of triangle abc closest to p (degenerate triangles allowed).
glm::vec3 closestPointOnTriangle(const glm::vec3& p, const glm::vec3& a, const glm::vec3& b, const glm::vec3& c);

/// "<dir>/sdf-<key>.bin"
std::filesystem::path cacheFilePath(const std::filesystem::path& dir, uint64_t key);

}  // namespace penumbra::sdf
