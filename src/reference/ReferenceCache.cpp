#include "reference/ReferenceCache.h"

#include "base/Hash.h"

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

constexpr char kMagic[8] = {'P', 'N', 'R', 'E', 'F', 'B', 'I', 'N'};

// Fixed-size header; the payload follows: litMask (n bytes), visibility, visibilityCosWeighted
// (n floats each), shadingExact, shadingSplit (3n floats each) and, for a scene with translucent
// casters only, visibilityRgb and visibilityCosWeightedRgb (3n floats each; the payload's size
// says which). Native (little-endian) order: the cache is local to one machine.
struct Header {
  char magic[8];
  uint32_t codeVersion;
  int32_t samplesPerPixel;
  uint64_t key;
  int32_t width, height;
  double traceSeconds;
  uint64_t hash;  ///< of the header (this field 0) and the payload: no byte of the file goes unchecked
};

static_assert(sizeof(Header) == 48, "the header has no padding: every byte is written");

size_t payloadBytes(size_t pixels, bool colour) {
  return pixels * (sizeof(uint8_t) + 2 * sizeof(float) + (colour ? 4 : 2) * sizeof(glm::vec3));
}

template <class T>
void append(std::vector<char>& out, std::span<const T> values) {
  const auto* bytes = reinterpret_cast<const char*>(values.data());
  out.insert(out.end(), bytes, bytes + values.size_bytes());
}

template <class T>
const char* take(const char* in, std::vector<T>& values, size_t count) {
  values.resize(count);
  std::memcpy(values.data(), in, count * sizeof(T));
  return in + count * sizeof(T);
}

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
  const std::optional<std::vector<char>> read = readCacheEntry(cacheFilePath(dir, key));
  if (!read) return std::nullopt;
  const std::vector<char>& file = *read;
  Header header;
  if (file.size() < sizeof(Header)) return std::nullopt;
  std::memcpy(&header, file.data(), sizeof(Header));
  if (std::memcmp(header.magic, kMagic, sizeof(kMagic)) != 0 || header.codeVersion != kReferenceCodeVersion ||
      header.key != key || header.width <= 0 || header.height <= 0)
    return std::nullopt;
  const size_t pixels = static_cast<size_t>(header.width) * static_cast<size_t>(header.height);
  const bool colour = file.size() == sizeof(Header) + payloadBytes(pixels, true);
  if (file.size() != sizeof(Header) + payloadBytes(pixels, colour)) return std::nullopt;
  if (cacheEntryHash(header, &Header::hash, file.data() + sizeof(Header), payloadBytes(pixels, colour)) != header.hash)
    return std::nullopt;

  ReferenceResult r;
  r.width = header.width;
  r.height = header.height;
  r.samplesPerPixel = header.samplesPerPixel;
  r.traceSeconds = header.traceSeconds;
  r.cacheKey = key;
  r.fromCache = true;
  const char* p = file.data() + sizeof(Header);
  p = take(p, r.litMask, pixels);
  p = take(p, r.visibility, pixels);
  p = take(p, r.visibilityCosWeighted, pixels);
  p = take(p, r.shadingExact, pixels);
  p = take(p, r.shadingSplit, pixels);
  if (colour) {
    p = take(p, r.visibilityRgb, pixels);
    take(p, r.visibilityCosWeightedRgb, pixels);
  }
  // Derived, not stored: recomputing it is exact and keeps the file a fifth smaller.
  r.approximationError.resize(pixels);
  for (size_t i = 0; i < pixels; ++i) r.approximationError[i] = r.shadingSplit[i] - r.shadingExact[i];
  r.horizonPixels = countHorizonPixels(r);
  touchCacheEntry(cacheFilePath(dir, key));  // used: the last to be evicted
  return r;
}

void storeCachedResult(const fs::path& dir, const ReferenceResult& result) {
  const size_t pixels = static_cast<size_t>(result.width) * static_cast<size_t>(result.height);
  const bool colour = !result.visibilityRgb.empty();
  std::vector<char> payload;
  payload.reserve(payloadBytes(pixels, colour));
  append(payload, std::span<const uint8_t>(result.litMask));
  append(payload, std::span<const float>(result.visibility));
  append(payload, std::span<const float>(result.visibilityCosWeighted));
  append(payload, std::span<const glm::vec3>(result.shadingExact));
  append(payload, std::span<const glm::vec3>(result.shadingSplit));
  if (colour) {
    append(payload, std::span<const glm::vec3>(result.visibilityRgb));
    append(payload, std::span<const glm::vec3>(result.visibilityCosWeightedRgb));
  }
  PN_ASSERT(payload.size() == payloadBytes(pixels, colour));

  Header header{};
  std::memcpy(header.magic, kMagic, sizeof(kMagic));
  header.codeVersion = kReferenceCodeVersion;
  header.samplesPerPixel = result.samplesPerPixel;
  header.key = result.cacheKey;
  header.width = result.width;
  header.height = result.height;
  header.traceSeconds = result.traceSeconds;
  header.hash = cacheEntryHash(header, &Header::hash, payload.data(), payload.size());

  const fs::path path = cacheFilePath(dir, result.cacheKey);
  writeBinaryFile(path, {std::span<const char>(reinterpret_cast<const char*>(&header), sizeof(header)),
                         std::span<const char>(payload.data(), payload.size())});
}

}  // namespace penumbra::reference
