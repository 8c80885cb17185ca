// The on-disk cache of baked SDFs: one file per key, "<dir>/sdf-<key>.bin", in the format every
// cache entry has (base/CacheRecord.h), written to a unique temporary name and renamed, so a reader
// never sees half a file. A file that fails any check (size, magic, kind, version, key, dimensions,
// the hash of every other byte) is ignored and baked over.
#include "bake/SdfBake.h"

#include "base/CacheRecord.h"

#include <penumbra/Error.h>
#include <penumbra/Files.h>

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <optional>
#include <span>
#include <system_error>

namespace penumbra::sdf {
namespace {

namespace fs = std::filesystem;

constexpr std::string_view kKind = "sdf";

// Block 0 of an entry (base/CacheRecord.h); then the distances (dims.x·dims.y·dims.z floats, x
// fastest) and the sheets' vertices (three a triangle).
struct Record {
  int32_t dims[3];
  float lo[3];
  float voxelM;
  uint32_t sheetTriangles;
  uint64_t triangles;
  double bakeSeconds;
};
static_assert(sizeof(Record) == 48, "the record has no padding: every byte is written");

std::optional<SdfVolume> load(const fs::path& path, uint64_t key) {
  std::optional<CacheReader> entry = CacheReader::open(path, kKind, kSdfCodeVersion, key);
  Record record;
  if (!entry || entry->blockCount() != 3 || !entry->next(record) || !(record.voxelM > 0.0f)) return std::nullopt;
  const bool noGrid = record.dims[0] == 0 && record.dims[1] == 0 && record.dims[2] == 0;
  for (int32_t d : record.dims)
    if (!noGrid && (d < 1 || d > 4 * kMaxResolution)) return std::nullopt;
  if (record.sheetTriangles > static_cast<uint32_t>(kMaxSheetTriangles)) return std::nullopt;
  SdfVolume v;
  const size_t voxels = static_cast<size_t>(record.dims[0]) * static_cast<size_t>(record.dims[1]) *
                        static_cast<size_t>(record.dims[2]);
  if (!entry->next(v.distances, voxels) || !entry->next(v.sheets, 3 * static_cast<size_t>(record.sheetTriangles)) ||
      !entry->verified())
    return std::nullopt;
  v.dims = {record.dims[0], record.dims[1], record.dims[2]};
  v.lo = {record.lo[0], record.lo[1], record.lo[2]};
  v.voxelM = record.voxelM;
  v.stats.bakeSeconds = record.bakeSeconds;
  v.stats.triangles = record.triangles;
  v.stats.gridBytes = voxels * sizeof(float);
  v.stats.fromCache = true;
  v.stats.cacheKey = key;
  return v;
}

void store(const fs::path& path, const SdfVolume& v) {
  Record record{};
  for (int a = 0; a < 3; ++a) {
    record.dims[a] = v.dims[a];
    record.lo[a] = v.lo[a];
  }
  record.voxelM = v.voxelM;
  record.sheetTriangles = static_cast<uint32_t>(v.sheets.size() / 3);
  record.triangles = v.stats.triangles;
  record.bakeSeconds = v.stats.bakeSeconds;
  const std::span<const char> blocks[] = {cacheBlock(record), cacheBlock(std::span<const float>(v.distances)),
                                          cacheBlock(std::span<const glm::vec3>(v.sheets))};
  writeCacheRecord(path, kKind, kSdfCodeVersion, v.stats.cacheKey, blocks);
}

}  // namespace

fs::path cacheFilePath(const fs::path& dir, uint64_t key) { return dir / fmt::format("sdf-{:016x}.bin", key); }

SdfVolume loadOrBake(std::span<const CasterGeometry> casters, const BakeOptions& options) {
  const fs::path dir = options.useCache ? (options.cacheDir.empty() ? defaultCacheDir() : options.cacheDir) : fs::path();
  if (dir.empty()) return bake(casters, options);
  const auto start = std::chrono::steady_clock::now();
  const uint64_t key = cacheKey(casters, options.resolution);
  const fs::path path = cacheFilePath(dir, key);
  if (std::optional<SdfVolume> cached = load(path, key)) {
    touchCacheEntry(path);  // used: the last to be evicted
    cached->stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return std::move(*cached);
  }
  const std::uintmax_t maxBytes = defaultCacheMaxBytes();  // a bad variable stops us before the bake
  SdfVolume v = bake(casters, options);
  v.stats.cacheKey = key;
  if (v.empty()) return v;  // a scene without casters costs nothing to "bake"
  // A folder that cannot hold the field costs the cache, not the field: said, and the bake used.
  try {
    checkCacheFolder(dir);
    std::error_code error;
    fs::create_directories(dir, error);
    if (error || !fs::is_directory(dir))
      throw Error(fmt::format("cannot create the folder {} ({})", dir.string(), error ? error.message() : "a file is in its place"));
    store(path, v);
    trimCache(dir, maxBytes);
  } catch (const Error& e) {
    std::fprintf(stderr, "penumbra: warning: sdf cache: %s; the field is baked but not kept (set PENUMBRA_CACHE to a writable "
                         "folder)\n", e.what());
  }
  return v;
}

}  // namespace penumbra::sdf
