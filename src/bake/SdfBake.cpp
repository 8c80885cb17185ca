// The SDF bake (see SdfBake.h for the method). Embree answers two kinds of query over the same
// BVH of the casters' world-space triangles: closest-point queries for the unsigned distance
// and all-hits rays along grid lines for the sign. Both loops run in parallel with oneTBB.
#include "bake/SdfBake.h"

#include "base/ProgressBar.h"

#include <penumbra/Error.h>

#include <embree3/rtcore.h>
#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstddef>
#include <limits>
#include <memory>
#include <mutex>
#include <string>

namespace penumbra::sdf {
namespace {

using Clock = std::chrono::steady_clock;
constexpr float kInfinity = std::numeric_limits<float>::infinity();

/// The Lipschitz bound d(p) ≤ d(q) + |p − q| seeds each point query's radius; it is widened by
/// this fraction (plus kSeedSlackVoxels) so float rounding can never shrink it below the answer.
constexpr float kSeedSlackFraction = 1e-4f;
constexpr float kSeedSlackVoxels = 1e-3f;
/// Crossings of one grid line closer than this (voxels) with the same facing are one crossing:
/// a line through a shared edge or vertex reports it once per triangle around it.
constexpr float kCoincidentVoxels = 1e-3f;
/// Each voxel gets six inside/outside votes (±x, ±y, ±z); at least this many make it inside.
/// A closed mesh gets six; one spoiled line (grazing a face) costs at most one.
constexpr int kInsideVotes = 4;
constexpr size_t kMiB = size_t{1} << 20;

// ---------------------------------------------------------------------------------------------
// Embree: device with a memory monitor, one triangle geometry holding every caster.

struct MemoryMonitor {
  std::atomic<int64_t> current{0}, peak{0};
  static bool track(void* user, ssize_t bytes, bool /*post*/) {
    auto* m = static_cast<MemoryMonitor*>(user);
    const int64_t now = m->current.fetch_add(bytes) + bytes;
    int64_t seen = m->peak.load();
    while (now > seen && !m->peak.compare_exchange_weak(seen, now)) {}
    return true;
  }
};

struct ErrorLog {
  std::mutex mutex;
  std::string last;
  static void record(void* user, RTCError code, const char* message) {
    auto* log = static_cast<ErrorLog*>(user);
    const std::lock_guard lock(log->mutex);
    log->last = fmt::format("Embree error {}: {}", static_cast<int>(code), message ? message : "");
  }
};

struct Crossing {
  float t;
  int facing;  // +1: the line enters the surface (against its CCW normal), −1: leaves it
  unsigned prim;
};

/// The intersect context of one grid line. Embree hands `context` back to the filter, which
/// finds the rest of the struct behind it (hence standard layout, context first).
struct LineQuery {
  RTCIntersectContext context;
  const glm::vec3* triangles;
  glm::vec3 direction;
  std::vector<Crossing>* crossings;
};
static_assert(offsetof(LineQuery, context) == 0, "the filter casts the context back to LineQuery");

/// Records every hit and rejects it, so that one rtcIntersect1 visits every crossing of the line.
void collectCrossings(const RTCFilterFunctionNArguments* args) {
  const auto* query = reinterpret_cast<const LineQuery*>(args->context);
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] != -1) continue;
    const unsigned prim = RTCHitN_primID(args->hit, args->N, i);
    const glm::vec3* t = query->triangles + 3 * static_cast<size_t>(prim);
    const glm::vec3 normal = glm::cross(t[1] - t[0], t[2] - t[0]);
    const float facing = glm::dot(normal, query->direction);
    if (facing != 0.0f) query->crossings->push_back({RTCRayN_tfar(args->ray, args->N, i), facing < 0.0f ? 1 : -1, prim});
    args->valid[i] = 0;
  }
}

struct PointQueryState {
  const glm::vec3* triangles;
  float best = kInfinity;
};

bool closestTriangle(RTCPointQueryFunctionArguments* args) {
  auto* state = static_cast<PointQueryState*>(args->userPtr);
  const glm::vec3 p{args->query->x, args->query->y, args->query->z};
  const glm::vec3* t = state->triangles + 3 * static_cast<size_t>(args->primID);
  const float d = glm::length(p - closestPointOnTriangle(p, t[0], t[1], t[2]));
  if (d >= args->query->radius) return false;
  args->query->radius = d;  // shrinks the search: Embree skips nodes farther than the best so far
  state->best = d;
  return true;
}

class CasterBvh {
public:
  explicit CasterBvh(const std::vector<glm::vec3>& triangles) : mTriangles(triangles) {
    mDevice = rtcNewDevice(nullptr);
    PN_CHECK(mDevice, "sdf bake: cannot create an Embree device");
    rtcSetDeviceErrorFunction(mDevice, ErrorLog::record, &mErrors);
    rtcSetDeviceMemoryMonitorFunction(mDevice, MemoryMonitor::track, &mMemory);
    mScene = rtcNewScene(mDevice);
    // Robust: watertight edges, so no grid line slips between two triangles of a mesh.
    rtcSetSceneFlags(mScene, RTC_SCENE_FLAG_ROBUST);
    rtcSetSceneBuildQuality(mScene, RTC_BUILD_QUALITY_MEDIUM);
    RTCGeometry geometry = rtcNewGeometry(mDevice, RTC_GEOMETRY_TYPE_TRIANGLE);
    const size_t count = triangles.size() / 3;
    auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                                 3 * sizeof(float), triangles.size()));
    auto* indices = static_cast<unsigned*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                                   3 * sizeof(unsigned), count));
    check("allocating the caster geometry");
    for (size_t i = 0; i < triangles.size(); ++i) {
      vertices[3 * i] = triangles[i].x;
      vertices[3 * i + 1] = triangles[i].y;
      vertices[3 * i + 2] = triangles[i].z;
      indices[i] = static_cast<unsigned>(i);
    }
    rtcSetGeometryIntersectFilterFunction(geometry, collectCrossings);
    rtcCommitGeometry(geometry);
    rtcAttachGeometry(mScene, geometry);
    rtcReleaseGeometry(geometry);
    rtcCommitScene(mScene);
    check("building the BVH");
  }
  ~CasterBvh() {
    if (mScene) rtcReleaseScene(mScene);
    if (mDevice) rtcReleaseDevice(mDevice);
  }
  CasterBvh(const CasterBvh&) = delete;
  CasterBvh& operator=(const CasterBvh&) = delete;

  /// Exact distance from p to the nearest triangle; `bound` must be ≥ that distance.
  float distance(const glm::vec3& p, float bound) const {
    PointQueryState state{mTriangles.data()};
    RTCPointQuery query{};
    query.x = p.x; query.y = p.y; query.z = p.z;
    query.radius = bound;
    RTCPointQueryContext context;
    rtcInitPointQueryContext(&context);
    rtcPointQuery(mScene, &query, &context, closestTriangle, &state);
    if (state.best == kInfinity && bound != kInfinity) return distance(p, kInfinity);  // never expected
    return state.best;
  }

  /// Every crossing of the segment origin + t·direction, t in [0, tFar], sorted by t.
  void crossings(const glm::vec3& origin, const glm::vec3& direction, float tFar, std::vector<Crossing>& out) const {
    out.clear();
    LineQuery query;
    rtcInitIntersectContext(&query.context);
    query.triangles = mTriangles.data();
    query.direction = direction;
    query.crossings = &out;
    RTCRayHit rayHit{};
    rayHit.ray.org_x = origin.x; rayHit.ray.org_y = origin.y; rayHit.ray.org_z = origin.z;
    rayHit.ray.dir_x = direction.x; rayHit.ray.dir_y = direction.y; rayHit.ray.dir_z = direction.z;
    rayHit.ray.tnear = 0.0f;
    rayHit.ray.tfar = tFar;
    rayHit.ray.mask = std::numeric_limits<unsigned>::max();
    rayHit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(mScene, &query.context, &rayHit);
    std::sort(out.begin(), out.end(), [](const Crossing& a, const Crossing& b) {
      return a.t < b.t || (a.t == b.t && a.prim < b.prim);
    });
  }

  size_t peakBytes() const { return static_cast<size_t>(std::max<int64_t>(mMemory.peak.load(), 0)); }

private:
  void check(const std::string& what) {
    const RTCError code = rtcGetDeviceError(mDevice);
    const std::lock_guard lock(mErrors.mutex);
    PN_CHECK(code == RTC_ERROR_NONE,
             fmt::format("sdf bake: {} failed ({})", what, mErrors.last.empty() ? "unknown Embree error" : mErrors.last));
  }

  const std::vector<glm::vec3>& mTriangles;
  ErrorLog mErrors;
  MemoryMonitor mMemory;
  RTCDevice mDevice = nullptr;
  RTCScene mScene = nullptr;
};

// ---------------------------------------------------------------------------------------------

/// Six inside votes per voxel from the grid lines along each axis (see SdfBake.h).
void voteSigns(const CasterBvh& bvh, const SdfVolume& grid, std::vector<uint8_t>& votes) {
  const float h = grid.voxelM;
  const float tolerance = kCoincidentVoxels * h;
  for (int axis = 0; axis < 3; ++axis) {
    const int b = (axis + 1) % 3, c = (axis + 2) % 3;
    const int length = grid.dims[axis];
    const int lines = grid.dims[b] * grid.dims[c];
    glm::vec3 direction(0.0f);
    direction[axis] = 1.0f;
    tbb::parallel_for(tbb::blocked_range<int>(0, lines), [&](const tbb::blocked_range<int>& range) {
      std::vector<Crossing> all, kept;
      for (int line = range.begin(); line != range.end(); ++line) {
        glm::ivec3 cell(0);
        cell[b] = line % grid.dims[b];
        cell[c] = line / grid.dims[b];
        cell[axis] = -1;  // the line starts one voxel before the grid: no caster lies there
        const glm::vec3 origin = grid.voxelCenter(cell.x, cell.y, cell.z);
        bvh.crossings(origin, direction, static_cast<float>(length + 1) * h, all);
        kept.clear();
        float lastT[2] = {-kInfinity, -kInfinity};  // per facing
        int total = 0;
        for (const Crossing& x : all) {
          float& last = lastT[x.facing > 0 ? 1 : 0];
          if (x.t - last <= tolerance) continue;
          last = x.t;
          kept.push_back(x);
          total += x.facing;
        }
        int before = 0;  // signed crossings between the line's start and the voxel
        size_t next = 0;
        for (int i = 0; i < length; ++i) {
          const float t = static_cast<float>(i + 1) * h;
          while (next < kept.size() && kept[next].t < t) before += kept[next++].facing;
          const int after = total - before;  // seen from the far end, with the facings reversed
          cell[axis] = i;
          votes[grid.index(cell.x, cell.y, cell.z)] += static_cast<uint8_t>((before != 0) + (after != 0));
        }
      }
    });
  }
}

/// Exact unsigned distances, one slice (z) per task; within a slice the previous voxel's
/// distance + one voxel bounds the next query (Lipschitz), which keeps each query local.
void computeDistances(const CasterBvh& bvh, SdfVolume& grid, ProgressBar& progress) {
  const float h = grid.voxelM;
  auto seed = [h](float neighbour) { return neighbour == kInfinity ? kInfinity : (neighbour + h) * (1.0f + kSeedSlackFraction) + kSeedSlackVoxels * h; };
  tbb::parallel_for(tbb::blocked_range<int>(0, grid.dims.z, 1), [&](const tbb::blocked_range<int>& range) {
    for (int k = range.begin(); k != range.end(); ++k) {
      float rowStart = kInfinity;
      for (int j = 0; j < grid.dims.y; ++j) {
        float previous = kInfinity;
        for (int i = 0; i < grid.dims.x; ++i) {
          const float bound = seed(i == 0 ? rowStart : previous);
          previous = bvh.distance(grid.voxelCenter(i, j, k), bound);
          if (i == 0) rowStart = previous;
          grid.distances[grid.index(i, j, k)] = previous;
        }
      }
      progress.advance(1);
    }
  });
}

}  // namespace

SdfVolume bake(std::span<const CasterGeometry> geometry, const BakeOptions& options) {
  const Clock::time_point start = Clock::now();
  const CasterTriangles casters = casterTriangles(geometry);
  SdfVolume grid = gridForTriangles(casters, options.resolution);
  grid.stats.triangles = (casters.volume.size() + casters.sheets.size()) / 3;
  if (!grid.hasGrid()) return grid;
  const std::vector<glm::vec3>& triangles = casters.volume;
  const size_t voxels = static_cast<size_t>(grid.dims.x) * static_cast<size_t>(grid.dims.y) * static_cast<size_t>(grid.dims.z);
  grid.distances.assign(voxels, 0.0f);

  const CasterBvh bvh(triangles);
  std::vector<uint8_t> votes(voxels, 0);
  voteSigns(bvh, grid, votes);
  const Clock::time_point signed_ = Clock::now();
  {
    ProgressBar progress("sdf bake", static_cast<size_t>(grid.dims.z), options.progress);
    computeDistances(bvh, grid, progress);
  }
  for (size_t i = 0; i < voxels; ++i)
    if (votes[i] >= kInsideVotes) grid.distances[i] = -grid.distances[i];

  const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
  const double signSeconds = std::chrono::duration<double>(signed_ - start).count();
  grid.stats.seconds = grid.stats.bakeSeconds = seconds;
  grid.stats.gridBytes = voxels * sizeof(float);
  grid.stats.scratchBytes = votes.size() + triangles.size() * sizeof(glm::vec3) + bvh.peakBytes();
  if (options.verbose || seconds > kReportBakeSeconds)
    std::fputs(fmt::format("sdf: baked {}x{}x{} voxels ({:.2f} mm) over {} triangles (+ {} in sheets) in {:.2f} s (signs {:.2f} s); "
                           "grid {:.1f} MiB, transient {:.1f} MiB (Embree BVH {:.1f} MiB)\n",
                           grid.dims.x, grid.dims.y, grid.dims.z, grid.voxelM * 1000.0f, triangles.size() / 3, casters.sheets.size() / 3, seconds,
                           signSeconds, static_cast<double>(grid.stats.gridBytes) / kMiB,
                           static_cast<double>(grid.stats.scratchBytes) / kMiB,
                           static_cast<double>(bvh.peakBytes()) / kMiB)
                   .c_str(),
               stderr);
  return grid;
}

// Makes loadOrBake the sdf filter's baker (setBaker).
void installEmbreeBaker() {
  setBaker([](std::span<const CasterGeometry> casters, const BakeOptions& options) { return loadOrBake(casters, options); });
}

}  // namespace penumbra::sdf
