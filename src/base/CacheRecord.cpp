#include "base/CacheRecord.h"

#include <penumbra/Error.h>
#include <penumbra/Files.h>

#include <algorithm>
#include <cstring>
#include <limits>
#include <system_error>

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

// The hash starts with the header (its hash field 0) and the sizes; each block follows as one
// Hasher::bytes call, in the writer and the reader alike.
Hasher startHash(Header header, std::span<const uint64_t> sizes) {
  header.hash = 0;
  Hasher hash;
  hash.value(header);
  hash.bytes(sizes.data(), sizes.size_bytes());
  return hash;
}

}  // namespace

void writeCacheRecord(const std::filesystem::path& entry, std::string_view kind, uint32_t codeVersion, uint64_t key,
                      std::span<const std::span<const char>> blocks) {
  Header header = makeHeader(kind, codeVersion, key, blocks.size());
  std::vector<uint64_t> sizes;
  for (const std::span<const char> b : blocks) sizes.push_back(b.size());
  Hasher hash = startHash(header, sizes);
  for (const std::span<const char> b : blocks) hash.bytes(b.data(), b.size());
  header.hash = hash.digest();
  std::vector<std::span<const char>> file{cacheBlock(header), cacheBlock(std::span<const uint64_t>(sizes))};
  file.insert(file.end(), blocks.begin(), blocks.end());
  writeBinaryFile(entry, std::span<const std::span<const char>>(file));
}

std::optional<CacheReader> CacheReader::open(const std::filesystem::path& entry, std::string_view kind,
                                             uint32_t codeVersion, uint64_t key) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(entry, ec)) return std::nullopt;
  const uintmax_t fileBytes = std::filesystem::file_size(entry, ec);
  if (ec || fileBytes < sizeof(Header)) return std::nullopt;
  CacheReader reader;
  reader.mFile.reset(std::fopen(entry.c_str(), "rb"));
  if (!reader.mFile) return std::nullopt;
  Header header;
  if (std::fread(&header, sizeof(Header), 1, reader.mFile.get()) != 1) return std::nullopt;
  const Header expected = makeHeader(kind, codeVersion, key, std::min(header.blockCount, kMaxBlocks));
  if (std::memcmp(header.magic, expected.magic, sizeof(kMagic)) != 0 ||
      std::memcmp(header.kind, expected.kind, kCacheKindChars) != 0 || header.codeVersion != codeVersion ||
      header.key != key || header.blockCount > kMaxBlocks)
    return std::nullopt;
  reader.mSizes.resize(header.blockCount);
  if (!reader.mSizes.empty() &&
      std::fread(reader.mSizes.data(), sizeof(uint64_t), reader.mSizes.size(), reader.mFile.get()) != reader.mSizes.size())
    return std::nullopt;
  // The sizes must add up to the file exactly (and no sum may wrap): nothing is allocated for a
  // block the file does not hold.
  uintmax_t total = sizeof(Header) + reader.mSizes.size() * sizeof(uint64_t);
  for (const uint64_t size : reader.mSizes) {
    if (size > fileBytes - std::min(total, fileBytes)) return std::nullopt;
    total += size;
  }
  if (total != fileBytes) return std::nullopt;
  reader.mExpectedHash = header.hash;
  reader.mHash = startHash(header, reader.mSizes);
  return reader;
}

bool CacheReader::expect(size_t count, size_t valueBytes) {
  mFailed = mFailed || mNext >= mSizes.size() || count > std::numeric_limits<size_t>::max() / valueBytes ||
            mSizes[mNext] != count * valueBytes;
  return !mFailed;
}

bool CacheReader::nextBytes(void* out, size_t bytes) {
  if (!expect(bytes, 1) || (bytes > 0 && std::fread(out, 1, bytes, mFile.get()) != bytes)) {
    mFailed = true;
    return false;
  }
  mHash.bytes(out, bytes);
  ++mNext;
  return true;
}

bool CacheReader::verified() const {
  return !mFailed && mNext == mSizes.size() && mHash.digest() == mExpectedHash;
}

}  // namespace penumbra
