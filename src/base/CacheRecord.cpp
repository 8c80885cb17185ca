#include "base/CacheRecord.h"

#include "base/Hash.h"

#include <penumbra/Error.h>
#include <penumbra/Files.h>

#include <algorithm>

namespace penumbra {
namespace {

constexpr char kMagic[8] = {'P', 'N', 'C', 'A', 'C', 'H', 'E', '1'};
// More blocks than any kind has: a header that claims more is damaged.
constexpr uint32_t kMaxBlocks = 64;

struct Header {
  char magic[8];
  char kind[kCacheKindChars];  ///< zero-padded
  uint32_t codeVersion;
  uint32_t blockCount;
  uint64_t key;
  uint64_t hash;  ///< of the header (this field 0), the block sizes and the blocks
};
static_assert(sizeof(Header) == 48, "the header has no padding: every byte is written");

Header makeHeader(std::string_view kind, uint32_t codeVersion, uint64_t key, size_t blocks) {
  PN_ASSERT(!kind.empty() && kind.size() <= kCacheKindChars && blocks <= kMaxBlocks);
  Header h{};
  std::memcpy(h.magic, kMagic, sizeof(kMagic));
  std::memcpy(h.kind, kind.data(), kind.size());
  h.codeVersion = codeVersion;
  h.blockCount = static_cast<uint32_t>(blocks);
  h.key = key;
  return h;
}

uint64_t recordHash(Header header, std::span<const uint64_t> sizes, std::span<const std::span<const char>> blocks) {
  header.hash = 0;
  Hasher hash;
  hash.value(header);
  hash.bytes(sizes.data(), sizes.size_bytes());
  for (const std::span<const char> b : blocks) hash.bytes(b.data(), b.size());
  return hash.digest();
}

}  // namespace

void writeCacheRecord(const std::filesystem::path& entry, std::string_view kind, uint32_t codeVersion, uint64_t key,
                      std::span<const std::span<const char>> blocks) {
  Header header = makeHeader(kind, codeVersion, key, blocks.size());
  std::vector<uint64_t> sizes;
  for (const std::span<const char> b : blocks) sizes.push_back(b.size());
  header.hash = recordHash(header, sizes, blocks);
  std::vector<std::span<const char>> file{cacheBlock(header), cacheBlock(std::span<const uint64_t>(sizes))};
  file.insert(file.end(), blocks.begin(), blocks.end());
  writeBinaryFile(entry, std::span<const std::span<const char>>(file));
}

std::optional<CacheRecord> readCacheRecord(const std::filesystem::path& entry, std::string_view kind, uint32_t codeVersion,
                                           uint64_t key) {
  std::optional<std::vector<char>> bytes = readCacheEntry(entry);
  if (!bytes || bytes->size() < sizeof(Header)) return std::nullopt;
  Header header;
  std::memcpy(&header, bytes->data(), sizeof(Header));
  const Header expected = makeHeader(kind, codeVersion, key, std::min(header.blockCount, kMaxBlocks));
  if (std::memcmp(header.magic, expected.magic, sizeof(kMagic)) != 0 ||
      std::memcmp(header.kind, expected.kind, kCacheKindChars) != 0 || header.codeVersion != codeVersion ||
      header.key != key || header.blockCount > kMaxBlocks)
    return std::nullopt;
  const size_t sizesAt = sizeof(Header), blocksAt = sizesAt + header.blockCount * sizeof(uint64_t);
  if (bytes->size() < blocksAt) return std::nullopt;
  std::vector<uint64_t> sizes(header.blockCount);
  std::memcpy(sizes.data(), bytes->data() + sizesAt, sizes.size() * sizeof(uint64_t));
  CacheRecord record;
  std::vector<std::span<const char>> blocks;
  size_t at = blocksAt;
  for (const uint64_t size : sizes) {
    if (size > bytes->size() - at) return std::nullopt;
    record.mRanges.emplace_back(at, static_cast<size_t>(size));
    blocks.emplace_back(bytes->data() + at, static_cast<size_t>(size));
    at += static_cast<size_t>(size);
  }
  if (at != bytes->size() || recordHash(header, sizes, blocks) != header.hash) return std::nullopt;
  record.mBytes = std::move(*bytes);  // a moved vector keeps its buffer: the ranges stay valid
  return record;
}

}  // namespace penumbra
