#include "reference/ReferenceCache.h"

#include "base/CacheRecord.h"

#include <penumbra/Error.h>
#include <penumbra/Files.h>

#include <fmt/format.h>

#include <cstdlib>
#include <cstring>
#include <span>
#include <system_error>
#include <vector>

namespace penumbra::reference {
namespace {

namespace fs = std::filesystem;

constexpr std::string_view kKind = "reference";

// Block 0 of an entry (base/CacheRecord.h); the blocks after it: litMask (n bytes), visibility,
// visibilityCosWeighted (n floats each), shadingExact, shadingSplit (n vec3 each) and, for a scene
// with translucent casters only, visibilityRgb and visibilityCosWeightedRgb (n vec3 each).
struct Record {
  int32_t samplesPerPixel;
  int32_t width, height;
  int32_t reserved;  // 0: no padding, every byte written
  double traceSeconds;
};
static_assert(sizeof(Record) == 24, "the record has no padding: every byte is written");

}  // namespace

size_t countHorizonPixels(const ReferenceResult& result) {
  size_t count = 0;
  for (size_t i = 0; i < result.litMask.size(); ++i)
    count += result.litMask[i] == 0 && result.shadingExact[i] != glm::vec3(0.0f) ? 1 : 0;
  return count;
}

fs::path cacheFilePath(const fs::path& dir, uint64_t key) {
  return dir / fmt::format("reference-{:016x}.bin", key);
}

void prepareCacheDir(const fs::path& dir) {
  try {
    checkCacheFolder(dir);
  } catch (const Error& e) {
    throw Error(fmt::format("reference cache: {}", e.what()));
  }
  std::error_code error;
  fs::create_directories(dir, error);
  if (error || !fs::is_directory(dir))
    throw Error(fmt::format("reference cache: cannot create the folder {} ({})", dir.string(),
                            error ? error.message() : "a file is in its place"));
}

std::optional<ReferenceResult> loadCachedResult(const fs::path& dir, uint64_t key) {
  std::optional<CacheReader> entry = CacheReader::open(cacheFilePath(dir, key), kKind, kReferenceCodeVersion, key);
  Record record;
  if (!entry || !entry->next(record) || record.width <= 0 || record.height <= 0) return std::nullopt;
  const size_t pixels = static_cast<size_t>(record.width) * static_cast<size_t>(record.height);
  const bool colour = entry->blockCount() == 8;
  ReferenceResult r;
  if ((entry->blockCount() != 6 && !colour) || !entry->next(r.litMask, pixels) || !entry->next(r.visibility, pixels) ||
      !entry->next(r.visibilityCosWeighted, pixels) || !entry->next(r.shadingExact, pixels) ||
      !entry->next(r.shadingSplit, pixels) ||
      (colour && (!entry->next(r.visibilityRgb, pixels) || !entry->next(r.visibilityCosWeightedRgb, pixels))) ||
      !entry->verified())
    return std::nullopt;
  r.width = record.width;
  r.height = record.height;
  r.samplesPerPixel = record.samplesPerPixel;
  r.traceSeconds = record.traceSeconds;
  r.cacheKey = key;
  r.fromCache = true;
  // Derived, not stored: recomputing it is exact and keeps the file a fifth smaller.
  r.approximationError.resize(pixels);
  for (size_t i = 0; i < pixels; ++i) r.approximationError[i] = r.shadingSplit[i] - r.shadingExact[i];
  r.horizonPixels = countHorizonPixels(r);
  touchCacheEntry(cacheFilePath(dir, key));  // used: the last to be evicted
  return r;
}

void storeCachedResult(const fs::path& dir, const ReferenceResult& result) {
  const Record record{result.samplesPerPixel, result.width, result.height, 0, result.traceSeconds};
  std::vector<std::span<const char>> blocks{
      cacheBlock(record),
      cacheBlock(std::span<const uint8_t>(result.litMask)),
      cacheBlock(std::span<const float>(result.visibility)),
      cacheBlock(std::span<const float>(result.visibilityCosWeighted)),
      cacheBlock(std::span<const glm::vec3>(result.shadingExact)),
      cacheBlock(std::span<const glm::vec3>(result.shadingSplit))};
  if (!result.visibilityRgb.empty()) {
    blocks.push_back(cacheBlock(std::span<const glm::vec3>(result.visibilityRgb)));
    blocks.push_back(cacheBlock(std::span<const glm::vec3>(result.visibilityCosWeightedRgb)));
  }
  writeCacheRecord(cacheFilePath(dir, result.cacheKey), kKind, kReferenceCodeVersion, result.cacheKey, blocks);
}

}  // namespace penumbra::reference
