#pragma once
// One format for every cache entry (the reference's results, the distance-field bakes): a header
// (magic, the entry's kind, the kind's code version, the key, the number of blocks, a hash of every
// other byte of the file), each block's size, then the blocks. Block 0 is the kind's own fixed
// record (image size, times); the others are its arrays. Native (little-endian) order: a cache is
// local to one machine.
//
// Blocks are read straight into the caller's arrays (no copy of the file in between: a 540 KB
// reference came back 1.6x slower through a whole-file buffer, which the allocator maps and
// unmaps each time), so a reader trusts what it read only once `verified()` says every byte
// checked.
#include "base/Hash.h"

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <span>
#include <string_view>
#include <type_traits>
#include <vector>

namespace penumbra {

/// The bytes of a value or an array, as a block to write.
template <class T>
std::span<const char> cacheBlock(const T& value) {
  static_assert(std::is_trivially_copyable_v<T>);
  return {reinterpret_cast<const char*>(&value), sizeof(T)};
}
template <class T>
std::span<const char> cacheBlock(std::span<const T> values) {
  static_assert(std::is_trivially_copyable_v<T>);
  return {reinterpret_cast<const char*>(values.data()), values.size_bytes()};
}

/// The longest kind name (they are short words: "reference", "sdf").
inline constexpr size_t kCacheKindChars = 16;

/// Writes an entry of `kind` atomically (writeBinaryFile). Throws penumbra::Error naming the file
/// on I/O failure.
void writeCacheRecord(const std::filesystem::path& entry, std::string_view kind, uint32_t codeVersion, uint64_t key,
                      std::span<const std::span<const char>> blocks);

/// An entry being read, block after block, in the order they were written. Never throws: a cache
/// that cannot be read is a miss (a read returns false, `verified()` is false).
class CacheReader {
public:
  /// The entry, its header checked (magic, kind, version, key, block count, sizes that fit the
  /// file), or nothing when it is missing or unreadable or any of those does not match.
  static std::optional<CacheReader> open(const std::filesystem::path& entry, std::string_view kind,
                                         uint32_t codeVersion, uint64_t key);

  size_t blockCount() const { return mSizes.size(); }

  /// The next block as a T (the kind's fixed record): false when its size is not sizeof(T).
  template <class T>
  bool next(T& out) {
    static_assert(std::is_trivially_copyable_v<T>);
    return nextBytes(&out, sizeof(T));
  }
  /// The next block as `count` values of T: false when its size is not count · sizeof(T).
  template <class T>
  bool next(std::vector<T>& out, size_t count) {
    static_assert(std::is_trivially_copyable_v<T>);
    if (!expect(count, sizeof(T))) return false;
    out.resize(count);
    return nextBytes(out.data(), count * sizeof(T));
  }

  /// True once every block has been read and the hash of the whole entry checks: only then is
  /// what was read the entry's.
  bool verified() const;

private:
  struct FileCloser {
    void operator()(std::FILE* f) const { std::fclose(f); }
  };
  CacheReader() = default;
  /// Whether the next block holds `count` values of `valueBytes`; a no marks the entry failed.
  bool expect(size_t count, size_t valueBytes);
  bool nextBytes(void* out, size_t bytes);

  std::unique_ptr<std::FILE, FileCloser> mFile;
  std::vector<uint64_t> mSizes;
  size_t mNext = 0;
  uint64_t mExpectedHash = 0;
  Hasher mHash;
  bool mFailed = false;
};

}  // namespace penumbra
