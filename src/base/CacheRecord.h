#pragma once
// One format for every cache entry (the reference's results, the distance-field bakes): a header
// (magic, the entry's kind, the kind's code version, the key, the number of blocks, a hash of every
// other byte of the file), each block's size, then the blocks. Block 0 is the kind's own fixed
// record (image size, times); the others are its arrays. A reader gets the blocks only when every
// check passes, so a kind's own code checks only that each block's size fits its record. Native
// (little-endian) order: a cache is local to one machine.
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <optional>
#include <span>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

namespace penumbra {

/// The blocks of one entry as read: views into the file's bytes, which it owns.
class CacheRecord {
public:
  size_t blockCount() const { return mRanges.size(); }
  std::span<const char> block(size_t i) const { return {mBytes.data() + mRanges[i].first, mRanges[i].second}; }

  /// Block `i` as a T (the kind's fixed record): false when its size is not sizeof(T).
  template <class T>
  bool read(size_t i, T& out) const {
    static_assert(std::is_trivially_copyable_v<T>);
    if (i >= blockCount() || block(i).size() != sizeof(T)) return false;
    std::memcpy(&out, block(i).data(), sizeof(T));
    return true;
  }
  /// Block `i` as `count` values of T: false when its size is not count · sizeof(T).
  template <class T>
  bool read(size_t i, std::vector<T>& out, size_t count) const {
    static_assert(std::is_trivially_copyable_v<T>);
    if (i >= blockCount() || block(i).size() != count * sizeof(T)) return false;
    out.resize(count);
    if (count > 0) std::memcpy(out.data(), block(i).data(), count * sizeof(T));
    return true;
  }

private:
  friend std::optional<CacheRecord> readCacheRecord(const std::filesystem::path&, std::string_view, uint32_t, uint64_t);
  std::vector<char> mBytes;
  std::vector<std::pair<size_t, size_t>> mRanges;  // offset, size
};

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
/// The entry's blocks, or nothing when it is missing or unreadable, of another kind, version or
/// key, or its sizes or hash do not check. Never throws: a cache that cannot be read is a miss.
std::optional<CacheRecord> readCacheRecord(const std::filesystem::path& entry, std::string_view kind, uint32_t codeVersion,
                                           uint64_t key);

}  // namespace penumbra
