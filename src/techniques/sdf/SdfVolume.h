#pragma once
// The distance field of the sdf technique (docs/sdf.md): a grid of signed distance (m) to the
// scene's shadow casters plus the flat sheets measured exactly, and the geometry every baker
// shares. The bake itself (Embree, oneTBB) is not on this floor: src/bake/ provides one, installed
// with installEmbreeBaker(); an engine may install its own (setBaker) or none (sdf is then refused).
#include "techniques/sdf/sdf.shared.h"

#include <penumbra/Casters.h>
#include <penumbra/Math.h>
#include <penumbra/Scene.h>

#include <glm/glm.hpp>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <span>
#include <vector>

namespace penumbra::sdf {

/// Version of the bake's maths; part of every cache key. Bump it whenever a change to the code
/// changes the numbers it produces, so that stale cache files are never read.
inline constexpr uint32_t kSdfCodeVersion = 2;
/// Grid resolution limits: voxels along the grid's longest axis.
inline constexpr int kDefaultResolution = 128;
inline constexpr int kMinResolution = 8;
inline constexpr int kMaxResolution = 512;
/// Empty voxels around the casters' bounds on every side, so that trilinear samples next to the
/// outermost caster still interpolate real distances and the march can enter the grid in free space.
inline constexpr int kPadVoxels = 2;
/// Flat sheets measured analytically, in triangles over all sheets (the uniform block's room).
inline constexpr int kMaxSheetTriangles = PN_SDF_MAX_SHEET_TRIANGLES;
/// A caster is flat when every vertex lies within this fraction of its size from its plane.
inline constexpr float kSheetFlatness = 1e-5f;
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

/// The baked field: signed distance (m) at voxel centres lo + (ijk + 0.5)·voxelM, < 0 inside a
/// caster, plus the flat sheets that the shader measures exactly. Grid storage order: x fastest,
/// then y, then z (the order glTexImage3D reads). Either part may be empty.
struct SdfVolume {
  glm::ivec3 dims{0};  ///< 0 when every caster is a sheet
  glm::vec3 lo{0.0f};  ///< the grid's min corner (m)
  float voxelM = 0.0f; ///< edge of one cubic voxel (m)
  std::vector<float> distances;
  std::vector<glm::vec3> sheets;  ///< world-space triangles of the flat sheets, three vertices each
  BakeStats stats;

  bool hasGrid() const { return dims.x > 0; }
  bool empty() const { return !hasGrid() && sheets.empty(); }  ///< the scene has no shadow casters
  glm::vec3 size() const { return glm::vec3(dims) * voxelM; }
  glm::vec3 hi() const { return lo + size(); }
  /// The box the grid's casters lie in: the grid without its padding.
  Aabb gridCasterBounds() const;
  /// Every caster (grid and sheets): nothing occludes outside it.
  Aabb casterBounds() const;
  size_t index(int i, int j, int k) const {
    return static_cast<size_t>(i) + static_cast<size_t>(dims.x) * (static_cast<size_t>(j) + static_cast<size_t>(dims.y) * static_cast<size_t>(k));
  }
  float at(int i, int j, int k) const { return distances[index(i, j, k)]; }
  glm::vec3 voxelCenter(int i, int j, int k) const { return lo + (glm::vec3(i, j, k) + 0.5f) * voxelM; }
  /// Trilinear interpolation with clamp-to-edge, like the GPU's sampler3D: the grid's value at
  /// ws. Meaningful inside [lo, hi].
  float sample(const glm::vec3& ws) const;
  /// What the shader marches: the grid's sample inside the grid; outside it the larger of two
  /// lower bounds, sample(nearest grid point q) − |ws − q| and the distance to
  /// gridCasterBounds(); and the exact distance to the sheets. The smallest of these.
  float distance(const glm::vec3& ws) const;
};

/// Unsigned distance from p to triangle abc (m).
float triangleDistance(const glm::vec3& p, const glm::vec3& a, const glm::vec3& b, const glm::vec3& c);

/// The world-space triangles of the casters, three vertices each, split into those baked into the
/// grid and the flat sheets (see above): each caster (a CasterGeometry) is flat or not as a whole.
struct CasterTriangles {
  std::vector<glm::vec3> volume, sheets;
};
CasterTriangles casterTriangles(std::span<const CasterGeometry> casters);

/// The grid a bake of the casters at `resolution` would use (dims, lo, voxelM, sheets; no
/// distances): cubic voxels, kPadVoxels of padding around the bounds of the grid's casters.
SdfVolume gridFor(std::span<const CasterGeometry> casters, int resolution);

/// Hash of the casters' world-space triangles, the resolution and kSdfCodeVersion: equal keys
/// bake equal grids. Costs one pass over the casters' vertices (~1 ms per 100k triangles).
uint64_t cacheKey(std::span<const CasterGeometry> casters, int resolution);

/// The same for a scene's casting objects (Object::castsShadow, in order).
CasterTriangles casterTriangles(const Scene& scene);
SdfVolume gridFor(const Scene& scene, int resolution);
uint64_t cacheKey(const Scene& scene, int resolution);

/// Exposed for tests: the point of triangle abc closest to p (degenerate triangles allowed).
glm::vec3 closestPointOnTriangle(const glm::vec3& p, const glm::vec3& a, const glm::vec3& b, const glm::vec3& c);

/// The grid for these triangles at `resolution` (dims 0 when `casters.volume` is empty; voxelM is
/// then set from the sheets' bounds, so that epsilons and offsets in voxels keep a scale).
SdfVolume gridForTriangles(const CasterTriangles& casters, int resolution);

/// What makes the casters' field: bakes it, or loads it from a cache. Throws penumbra::Error.
using Baker = std::function<SdfVolume(std::span<const CasterGeometry> casters, const BakeOptions& options)>;
/// Installs the baker the sdf filter uses (an empty one uninstalls). Not thread-safe: install it
/// once at start-up.
void setBaker(Baker baker);
/// The installed baker; empty when none is (the sdf filter then refuses to run).
const Baker& baker();

}  // namespace penumbra::sdf
