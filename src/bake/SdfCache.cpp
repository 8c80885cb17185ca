// The on-disk cache of baked SDFs: one file per key, "<dir>/sdf-<key>.bin", written to a unique
// temporary name and renamed, so a reader never sees half a file. A file that fails any check
// (size, magic, version, key, dimensions, the hash of every other byte) is ignored and baked over.
#include "bake/SdfBake.h"

#include "base/Hash.h"

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

constexpr char kMagic[8] = {'P', 'N', 'S', 'D', 'F', 'B', 'I', 'N'};

// Fixed-size header; the payload follows: dims.x·dims.y·dims.z floats (x fastest), then the
// sheets' vertices (3 floats each, three vertices per triangle). Native
// (little-endian) order: the cache is local to one machine.
struct Header {
  char magic[8];
  uint32_t codeVersion;
  int32_t dims[3];
  uint64_t key;
  float lo[3];
  float voxelM;
  uint64_t triangles;
  double bakeSeconds;
  uint64_t hash;  ///< of the header (this field 0) and the payload: no byte of the file goes unchecked
  uint32_t sheetTriangles;
  uint32_t reserved;  // 0; keeps the size a multiple of 8 without compiler padding
};
static_assert(sizeof(Header) == 80, "the header has no padding: every byte is written");

size_t voxelCount(const int32_t dims[3]) {
  return static_cast<size_t>(dims[0]) * static_cast<size_t>(dims[1]) * static_cast<size_t>(dims[2]);
}

std::optional<SdfVolume> load(const fs::path& path, uint64_t key) {
  const std::optional<std::vector<char>> read = readCacheEntry(path);
  if (!read) return std::nullopt;
  const std::vector<char>& file = *read;
  if (file.size() < sizeof(Header)) return std::nullopt;
  Header header;
  std::memcpy(&header, file.data(), sizeof(Header));
  if (std::memcmp(header.magic, kMagic, sizeof(kMagic)) != 0 || header.codeVersion != kSdfCodeVersion || header.key != key)
    return std::nullopt;
  const bool noGrid = header.dims[0] == 0 && header.dims[1] == 0 && header.dims[2] == 0;
  for (int32_t d : header.dims)
    if (!noGrid && (d < 1 || d > 4 * kMaxResolution)) return std::nullopt;
  if (header.sheetTriangles > static_cast<uint32_t>(kMaxSheetTriangles)) return std::nullopt;
  const size_t voxels = voxelCount(header.dims);
  const size_t sheetVertices = 3 * static_cast<size_t>(header.sheetTriangles);
  const size_t payload = voxels * sizeof(float) + sheetVertices * sizeof(glm::vec3);
  if (file.size() != sizeof(Header) + payload) return std::nullopt;
  if (cacheEntryHash(header, &Header::hash, file.data() + sizeof(Header), payload) != header.hash || !(header.voxelM > 0.0f))
    return std::nullopt;

  SdfVolume v;
  v.dims = {header.dims[0], header.dims[1], header.dims[2]};
  v.lo = {header.lo[0], header.lo[1], header.lo[2]};
  v.voxelM = header.voxelM;
  v.distances.resize(voxels);
  std::memcpy(v.distances.data(), file.data() + sizeof(Header), voxels * sizeof(float));
  v.sheets.resize(sheetVertices);
  std::memcpy(v.sheets.data(), file.data() + sizeof(Header) + voxels * sizeof(float), sheetVertices * sizeof(glm::vec3));
  v.stats.bakeSeconds = header.bakeSeconds;
  v.stats.triangles = header.triangles;
  v.stats.gridBytes = voxels * sizeof(float);
  v.stats.fromCache = true;
  v.stats.cacheKey = key;
  return v;
}

void store(const fs::path& path, const SdfVolume& v) {
  Header header{};
  std::memcpy(header.magic, kMagic, sizeof(kMagic));
  header.codeVersion = kSdfCodeVersion;
  for (int a = 0; a < 3; ++a) {
    header.dims[a] = v.dims[a];
    header.lo[a] = v.lo[a];
  }
  header.key = v.stats.cacheKey;
  header.voxelM = v.voxelM;
  header.triangles = v.stats.triangles;
  header.bakeSeconds = v.stats.bakeSeconds;
  header.sheetTriangles = static_cast<uint32_t>(v.sheets.size() / 3);
  std::vector<char> payload(v.distances.size() * sizeof(float) + v.sheets.size() * sizeof(glm::vec3));
  std::memcpy(payload.data(), v.distances.data(), v.distances.size() * sizeof(float));
  std::memcpy(payload.data() + v.distances.size() * sizeof(float), v.sheets.data(), v.sheets.size() * sizeof(glm::vec3));
  header.hash = cacheEntryHash(header, &Header::hash, payload.data(), payload.size());

  writeBinaryFile(path, {std::span<const char>(reinterpret_cast<const char*>(&header), sizeof(header)),
                         std::span<const char>(payload.data(), payload.size())});
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
