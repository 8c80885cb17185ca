// The one format of every cache entry (base/CacheRecord.h): what is written is read back block for
// block, and an entry of another kind, version or key, or with any byte changed, is a miss.
#include "base/CacheRecord.h"

#include <gtest/gtest.h>

#include <unistd.h>

#include <array>
#include <filesystem>
#include <fstream>
#include <string>

namespace penumbra {
namespace {

namespace fs = std::filesystem;

struct Fields {
  int32_t width = 7, height = 3;
  double seconds = 1.25;
};

TEST(CacheRecord, ReadsBackWhatItWroteAndRefusesEveryOtherEntry) {
  const fs::path dir = fs::temp_directory_path() / ("penumbra-cache-record-" + std::to_string(getpid()));
  fs::create_directories(dir);
  const fs::path entry = dir / "test-00000000000000aa.bin";
  const std::vector<float> values{1.0f, 2.5f, -3.0f};
  const std::vector<uint8_t> mask{0, 1};
  const Fields fields;
  const std::array<std::span<const char>, 4> blocks{cacheBlock(fields), cacheBlock(std::span<const float>(values)),
                                                    cacheBlock(std::span<const uint8_t>()),
                                                    cacheBlock(std::span<const uint8_t>(mask))};
  writeCacheRecord(entry, "test", 3, 0xaa, blocks);

  // Reads every block of the entry as the test wrote it; false on the first that does not read.
  const auto readAll = [](const fs::path& file) {
    std::optional<CacheReader> in = CacheReader::open(file, "test", 3, 0xaa);
    Fields f{0, 0, 0.0};
    std::vector<float> v;
    std::vector<uint8_t> empty, m;
    return in && in->next(f) && in->next(v, 3) && in->next(empty, 0) && in->next(m, 2) && in->verified();
  };

  std::optional<CacheReader> back = CacheReader::open(entry, "test", 3, 0xaa);
  ASSERT_TRUE(back);
  ASSERT_EQ(back->blockCount(), 4u);
  Fields f{0, 0, 0.0};
  std::vector<float> v;
  std::vector<uint8_t> empty{9}, m;
  EXPECT_TRUE(back->next(f));
  EXPECT_EQ(f.width, 7);
  EXPECT_EQ(f.seconds, 1.25);
  EXPECT_FALSE(back->verified()) << "verified before every block was read";
  EXPECT_TRUE(back->next(v, 3));
  EXPECT_EQ(v, values);
  EXPECT_TRUE(back->next(empty, 0));
  EXPECT_TRUE(empty.empty());
  EXPECT_TRUE(back->next(m, 2));
  EXPECT_EQ(m, mask);
  EXPECT_TRUE(back->verified());
  EXPECT_FALSE(back->next(m, 0)) << "a block past the last";
  EXPECT_FALSE(back->verified()) << "a failed read spoils the entry";
  {
    std::optional<CacheReader> in = CacheReader::open(entry, "test", 3, 0xaa);
    ASSERT_TRUE(in && in->next(f));
    EXPECT_FALSE(in->next(v, 4)) << "a block read as more values than it holds";
    EXPECT_FALSE(in->next(v, 3)) << "reads after a failed one";
    EXPECT_FALSE(in->verified());
  }
  {
    std::optional<CacheReader> in = CacheReader::open(entry, "test", 3, 0xaa);
    ASSERT_TRUE(in);
    EXPECT_FALSE(in->next(m, 2)) << "a record read as an array of another size";
  }
  EXPECT_TRUE(readAll(entry));

  EXPECT_FALSE(CacheReader::open(entry, "tes", 3, 0xaa)) << "another kind";
  EXPECT_FALSE(CacheReader::open(entry, "test", 4, 0xaa)) << "another code version";
  EXPECT_FALSE(CacheReader::open(entry, "test", 3, 0xab)) << "another key";
  EXPECT_FALSE(CacheReader::open(dir / "missing.bin", "test", 3, 0xaa));
  EXPECT_FALSE(CacheReader::open(dir, "test", 3, 0xaa)) << "a folder";

  // Every byte counts: each one flipped in turn makes the entry a miss.
  const size_t bytes = fs::file_size(entry);
  EXPECT_EQ(bytes, 48 + 4 * 8 + sizeof(Fields) + sizeof(float) * 3 + 2);
  size_t accepted = 0;
  for (size_t at = 0; at < bytes; ++at) {
    const fs::path copy = dir / "flipped.bin";
    fs::copy_file(entry, copy, fs::copy_options::overwrite_existing);
    {
      std::fstream file(copy, std::ios::in | std::ios::out | std::ios::binary);
      file.seekg(static_cast<std::streamoff>(at));
      const char c = static_cast<char>(file.get());
      file.seekp(static_cast<std::streamoff>(at));
      file.put(static_cast<char>(c ^ 0x10));
    }
    accepted += readAll(copy) ? 1 : 0;
  }
  EXPECT_EQ(accepted, 0u) << "entries read back with a byte changed";
  fs::resize_file(entry, bytes - 1);
  EXPECT_FALSE(CacheReader::open(entry, "test", 3, 0xaa)) << "a truncated entry";
  {
    std::ofstream grow(entry, std::ios::binary | std::ios::app);
    grow.write("xy", 2);
  }
  EXPECT_FALSE(CacheReader::open(entry, "test", 3, 0xaa)) << "an entry longer than its blocks";
  fs::remove_all(dir);
}

}  // namespace
}  // namespace penumbra
