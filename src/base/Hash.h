#pragma once
// A streaming 64-bit hash for cache keys: not cryptographic, but every input bit reaches every
// output bit (splitmix64 finaliser), and it reads 8 bytes at a time so that hashing a G-buffer
// or a few million triangles costs milliseconds next to the seconds a trace takes.
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>
#include <string_view>
#include <type_traits>

namespace penumbra {

class Hasher {
public:
  void bytes(const void* data, size_t size) {
    const auto* p = static_cast<const unsigned char*>(data);
    size_t i = 0;
    for (; i + 8 <= size; i += 8) {
      uint64_t word;
      std::memcpy(&word, p + i, 8);
      mix(word);
    }
    uint64_t tail = 0;
    if (size > i) std::memcpy(&tail, p + i, size - i);
    mix(tail ^ (static_cast<uint64_t>(size - i) << 56));
    mLength += size;
  }
  template <class T>
  void value(const T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    bytes(&v, sizeof(T));
  }
  template <class T>
  void array(std::span<const T> values) {
    static_assert(std::is_trivially_copyable_v<T>);
    value(values.size());
    bytes(values.data(), values.size_bytes());
  }
  void text(std::string_view s) { value(s.size()); bytes(s.data(), s.size()); }
  uint64_t digest() const { return finalise(mState ^ mLength); }

  static uint64_t finalise(uint64_t x) {  // splitmix64's finaliser
    x ^= x >> 30; x *= 0xbf58476d1ce4e5b9ull;
    x ^= x >> 27; x *= 0x94d049bb133111ebull;
    return x ^ (x >> 31);
  }

private:
  void mix(uint64_t word) {
    mState = (mState ^ finalise(word + kGolden)) * kMultiplier;
    mState = (mState << 27) | (mState >> 37);
  }
  static constexpr uint64_t kGolden = 0x9e3779b97f4a7c15ull;
  static constexpr uint64_t kMultiplier = 0xff51afd7ed558ccdull;
  uint64_t mState = 0x243f6a8885a308d3ull;  // π's fraction: an arbitrary non-zero start
  uint64_t mLength = 0;
};

/// The hash that checks a cache file, every byte of it: its fixed-size header with its own hash
/// field (`hashField`) zeroed, then the payload.
template <class Header>
uint64_t cacheEntryHash(Header header, uint64_t Header::*hashField, const void* payload, size_t bytes) {
  header.*hashField = 0;
  Hasher hash;
  hash.value(header);
  hash.bytes(payload, bytes);
  return hash.digest();
}

}  // namespace penumbra
