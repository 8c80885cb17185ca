// The bounded cache folder: `penumbra cache` shows, trims and clears it; compare evicts the least
// recently used reference when the folder is over its cap, and a cache hit counts as a use.
#include "CliSupport.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>
#include <vector>

using namespace penumbra::test;

namespace {

namespace fs = std::filesystem;

constexpr size_t kMiB = size_t{1} << 20;

std::string cacheEnv(const std::string& dir) { return "PENUMBRA_CACHE='" + dir + "'"; }

void writeFile(const fs::path& path, size_t bytes, std::chrono::seconds age) {
  std::ofstream(path, std::ios::binary) << std::string(bytes, 'x');
  fs::last_write_time(path, fs::file_time_type::clock::now() - age);
}

/// The entries `penumbra cache --json` lists, in its order (least recently used first).
std::vector<std::string> listed(const nlohmann::json& j) {
  std::vector<std::string> names;
  for (const auto& e : j["entries"]) names.push_back(e["name"]);
  return names;
}

nlohmann::json cacheJson(const std::string& dir, const std::string& args = "") {
  const RunResult r = runPenumbra("cache --json " + args, dir, cacheEnv(dir));
  EXPECT_EQ(r.exitCode, 0) << r.err;
  return nlohmann::json::parse(r.out);
}

}  // namespace

// Entries are <kind>-<16 hex>.bin; a temporary being written and a foreign file are not entries
// and survive --clear. --cache-max-mb trims the oldest first; bad caps are usage errors.
TEST(CacheCli, ListsTrimsAndClearsOnlyItsEntries) {
  const std::string dir = freshDir("cache-cmd");
  writeFile(dir + "/reference-00000000000000a1.bin", kMiB, std::chrono::seconds(300));
  writeFile(dir + "/sdf-00000000000000b2.bin", kMiB, std::chrono::seconds(200));
  writeFile(dir + "/reference-00000000000000c3.bin", kMiB, std::chrono::seconds(100));
  writeFile(dir + "/reference-00000000000000d4.bin.tmp.123.0", kMiB, std::chrono::seconds(400));
  writeFile(dir + "/notes.txt", 10, std::chrono::seconds(500));

  nlohmann::json j = cacheJson(dir);
  EXPECT_EQ(j["folder"], dir);
  EXPECT_EQ(listed(j), (std::vector<std::string>{"reference-00000000000000a1.bin", "sdf-00000000000000b2.bin",
                                                   "reference-00000000000000c3.bin"}));
  EXPECT_EQ(j["bytes"], 3 * kMiB);
  EXPECT_EQ(j["max_bytes"], size_t{4096} * kMiB) << "the default cap";

  const RunResult text = runPenumbra("cache", dir, cacheEnv(dir));
  ASSERT_EQ(text.exitCode, 0) << text.err;
  EXPECT_NE(text.out.find(dir), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("3 entries"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("reference-00000000000000a1.bin"), std::string::npos) << text.out;

  j = cacheJson(dir, "--cache-max-mb 2");
  EXPECT_EQ(j["removed"], nlohmann::json::array({"reference-00000000000000a1.bin"})) << "the least recently used goes";
  EXPECT_EQ(listed(j), (std::vector<std::string>{"sdf-00000000000000b2.bin", "reference-00000000000000c3.bin"}));

  j = cacheJson(dir, "--clear");
  EXPECT_EQ(j["removed"].size(), 2u);
  EXPECT_TRUE(listed(j).empty());
  EXPECT_TRUE(fs::exists(dir + "/notes.txt"));
  EXPECT_TRUE(fs::exists(dir + "/reference-00000000000000d4.bin.tmp.123.0"));

  EXPECT_EQ(runPenumbra("cache --clear --cache-max-mb 1", dir, cacheEnv(dir)).exitCode, 2);
  const RunResult badEnv = runPenumbra("cache", dir, cacheEnv(dir) + " PENUMBRA_CACHE_MAX_MB=lots");
  EXPECT_EQ(badEnv.exitCode, 2);
  EXPECT_NE(badEnv.err.find("PENUMBRA_CACHE_MAX_MB"), std::string::npos) << badEnv.err;
  EXPECT_EQ(badEnv.err.find('\n'), badEnv.err.size() - 1) << "one line: " << badEnv.err;
}

// Three views of boxes at 256x256 make three 2.1 MiB references. With a 5 MiB cap two fit. A is
// written, then B, then A is read again (a hit: now B is the least recently used); C's write
// evicts B, not A. PENUMBRA_CACHE_MAX_MB=0 keeps nothing at all, the sdf bake's entry too.
TEST(CacheCli, CompareEvictsTheLeastRecentlyUsedReference) {
  const std::string dir = freshDir("cache-lru");
  const std::string compare = "compare --scene boxes --set light.size=0 --size 256x256 --shadow-map 256 --json --out imgs";
  const auto run = [&](const std::string& camera, const std::string& extra = "", const std::string& env = "") {
    const RunResult r = runPenumbra(compare + " --camera " + camera + " " + extra, dir, cacheEnv(dir + "/c") + env);
    EXPECT_EQ(r.exitCode, 0) << r.err;
    return nlohmann::json::parse(r.out)["reference_cached"].get<bool>();
  };
  const std::string a = "4,3,5:0,0.5,0", b = "-4,3,5:0,0.5,0", c = "0,6,1:0,0,0";
  EXPECT_FALSE(run(a));
  const std::string entryA = listed(cacheJson(dir + "/c")).at(0);
  EXPECT_FALSE(run(b));
  const std::vector<std::string> two = listed(cacheJson(dir + "/c"));
  ASSERT_EQ(two.size(), 2u);
  EXPECT_EQ(two[0], entryA);
  const std::string entryB = two[1];
  EXPECT_TRUE(run(a)) << "the same view reads its reference from the cache";
  EXPECT_EQ(listed(cacheJson(dir + "/c")), (std::vector<std::string>{entryB, entryA})) << "a hit is a use";
  EXPECT_FALSE(run(c, "--cache-max-mb 5"));
  const std::vector<std::string> after = listed(cacheJson(dir + "/c"));
  ASSERT_EQ(after.size(), 2u);
  EXPECT_EQ(after[0], entryA);
  EXPECT_NE(after[1], entryB);
  EXPECT_TRUE(run(a)) << "A survived the eviction";

  EXPECT_FALSE(run(b, "", " PENUMBRA_CACHE_MAX_MB=0"));
  EXPECT_TRUE(listed(cacheJson(dir + "/c")).empty());
  const RunResult sdf = runPenumbra("render --scene pen --filter sdf --size 64x48 --out s.png", dir,
                                    cacheEnv(dir + "/c") + " PENUMBRA_CACHE_MAX_MB=0");
  ASSERT_EQ(sdf.exitCode, 0) << sdf.err;
  EXPECT_NE(sdf.err.find("sdf: baked"), std::string::npos) << "the bake ran and was stored: " << sdf.err;
  EXPECT_TRUE(listed(cacheJson(dir + "/c")).empty()) << "the sdf bake's write trims the folder too";
}
