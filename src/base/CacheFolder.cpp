// The bounded cache folder (penumbra/Files.h): entries by name, least recently used first, and
// the trim that keeps the folder under its cap. It serves every cache that writes the folder
// (the reference's results, the sdf bakes): the cap is the folder's, not one cache's.
#include <penumbra/Error.h>
#include <penumbra/Files.h>

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cstdlib>
#include <string_view>
#include <system_error>

namespace penumbra {
namespace {

namespace fs = std::filesystem;

constexpr std::uintmax_t kBytesPerMiB = std::uintmax_t{1} << 20;
constexpr size_t kKeyDigits = 16;  // a 64-bit key in hex

/// <kind>-<16 hex digits>.bin, kind in lower-case letters: what Penumbra's caches name their
/// files. Temporaries (".tmp.<pid>.<n>" appended) and foreign files do not match.
bool isEntryName(std::string_view name) {
  constexpr std::string_view kSuffix = ".bin";
  if (name.size() < kKeyDigits + kSuffix.size() + 2 || !name.ends_with(kSuffix)) return false;
  const std::string_view stem = name.substr(0, name.size() - kSuffix.size());
  const size_t dash = stem.size() - kKeyDigits - 1;
  if (stem[dash] != '-' || dash == 0) return false;
  const auto lower = [](char c) { return c >= 'a' && c <= 'z'; };
  const auto hex = [](char c) { return (c >= '0' && c <= '9') || (c >= 'a' && c <= 'f'); };
  return std::all_of(stem.begin(), stem.begin() + static_cast<std::ptrdiff_t>(dash), lower) &&
         std::all_of(stem.begin() + static_cast<std::ptrdiff_t>(dash) + 1, stem.end(), hex);
}

}  // namespace

std::uintmax_t defaultCacheMaxBytes() {
  const char* text = std::getenv(kCacheMaxEnv);
  if (!text || !*text) return kDefaultCacheMaxMiB * kBytesPerMiB;
  const std::string_view s(text);
  std::uintmax_t mib = 0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), mib);
  if (ec != std::errc() || end != s.data() + s.size() || mib > UINTMAX_MAX / kBytesPerMiB)
    throw usageError(fmt::format("{}={}: expected the cache's cap as a whole number of MiB, e.g. 4096", kCacheMaxEnv, s));
  return mib * kBytesPerMiB;
}

std::vector<CacheEntry> listCacheEntries(const fs::path& dir) {
  std::vector<CacheEntry> entries;
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const fs::directory_entry& e = *it;
    std::error_code fileError;
    if (!e.is_regular_file(fileError) || !isEntryName(e.path().filename().string())) continue;
    CacheEntry entry{e.path(), e.file_size(fileError), e.last_write_time(fileError)};
    if (!fileError) entries.push_back(std::move(entry));  // gone meanwhile: another process trimmed it
  }
  std::sort(entries.begin(), entries.end(), [](const CacheEntry& a, const CacheEntry& b) {
    return a.lastUse != b.lastUse ? a.lastUse < b.lastUse : a.path < b.path;
  });
  return entries;
}

void touchCacheEntry(const fs::path& entry) {
  std::error_code ignored;
  fs::last_write_time(entry, fs::file_time_type::clock::now(), ignored);
}

std::vector<CacheEntry> trimCache(const fs::path& dir, std::uintmax_t maxBytes) {
  std::vector<CacheEntry> entries = listCacheEntries(dir), removed;
  std::uintmax_t total = 0;
  for (const CacheEntry& e : entries) total += e.bytes;
  for (const CacheEntry& e : entries) {
    if (total <= maxBytes) break;
    std::error_code ec;
    if (fs::remove(e.path, ec)) removed.push_back(e);
    total -= e.bytes;  // removed now, or by someone else before us: either way no longer here
  }
  return removed;
}

}  // namespace penumbra
