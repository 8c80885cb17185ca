// The bounded cache folder: `penumbra cache` shows, trims and clears it; compare evicts the least
// recently used reference when the folder is over its cap, and a cache hit counts as a use.
#include "CliSupport.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>
#include <vector>

#include <sys/wait.h>
#include <unistd.h>

using namespace penumbra::test;

namespace {

namespace fs = std::filesystem;

constexpr size_t kMiB = size_t{1} << 20;

std::string cacheEnv(const std::string& dir) { return "PENUMBRA_CACHE='" + dir + "'"; }

/// The id of a process that has ended (a child, waited for).
pid_t goneProcess() {
  const pid_t child = fork();
  if (child == 0) _exit(0);
  int status = 0;
  waitpid(child, &status, 0);
  return child;
}

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

// Entries are <kind>-<16 hex>.bin; a temporary being written (its process runs) and a foreign
// file are not entries and survive --clear, while the temporary of a write whose process is gone
// (a kill during the write) is an interrupted entry: listed first, counted and removed first.
// --cache-max-mb trims the oldest first; bad caps are usage errors.
TEST(CacheCli, ListsTrimsAndClearsOnlyItsEntries) {
  const std::string dir = freshDir("cache-cmd");
  const pid_t gone = goneProcess();
  writeFile(dir + "/reference-00000000000000a1.bin", kMiB, std::chrono::seconds(300));
  writeFile(dir + "/sdf-00000000000000b2.bin", kMiB, std::chrono::seconds(200));
  writeFile(dir + "/reference-00000000000000c3.bin", kMiB, std::chrono::seconds(100));
  const std::string writing = "reference-00000000000000d4.bin.tmp." + std::to_string(getpid()) + ".0";
  const std::string interrupted = "reference-00000000000000e5.bin.tmp." + std::to_string(gone) + ".3";
  writeFile(dir + "/" + writing, kMiB, std::chrono::seconds(400));
  writeFile(dir + "/" + interrupted, kMiB / 2, std::chrono::seconds(10));
  writeFile(dir + "/notes.txt", 10, std::chrono::seconds(500));

  nlohmann::json j = cacheJson(dir);
  EXPECT_EQ(j["folder"], dir);
  EXPECT_EQ(listed(j), (std::vector<std::string>{interrupted, "reference-00000000000000a1.bin", "sdf-00000000000000b2.bin",
                                                   "reference-00000000000000c3.bin"}));
  EXPECT_EQ(j["entries"][0]["interrupted"], true);
  EXPECT_EQ(j["entries"][1]["interrupted"], false);
  EXPECT_EQ(j["bytes"], 3 * kMiB + kMiB / 2);
  const RunResult listing = runPenumbra("cache", dir, cacheEnv(dir));
  EXPECT_NE(listing.out.find(interrupted + "   "), std::string::npos) << listing.out;
  EXPECT_NE(listing.out.find("an interrupted write, from"), std::string::npos) << listing.out;
  j = cacheJson(dir, "--cache-max-mb 3");
  EXPECT_EQ(j["removed"], nlohmann::json::array({interrupted})) << "an interrupted write goes first, however recent";
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
  EXPECT_TRUE(fs::exists(dir + "/" + writing)) << "a write under way is left alone";

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
  const std::string compare = "compare --scene boxes --set light.size=0 --size 256x256 --shadow-map 1024 --json --out imgs";
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

// A cache folder that cannot be one is said, not taken for an empty cache: a file in its place,
// a symbolic link to nothing. compare goes on without the cache, with one warning.
TEST(CacheCli, AFileOrADanglingLinkInTheFoldersPlaceIsNamed) {
  const std::string dir = freshDir("cache-not-a-folder");
  std::ofstream(dir + "/file") << "not a folder";
  fs::create_symlink(dir + "/nowhere", dir + "/link");
  for (const auto& [folder, problem] : {std::pair<std::string, std::string>{dir + "/file", "is a file, not a folder"},
                                        {dir + "/link", "is a symbolic link to " + dir + "/nowhere, which does not exist"}}) {
    for (const char* args : {"cache", "cache --clear", "cache --json"}) {
      const RunResult r = runPenumbra(args, dir, cacheEnv(folder));
      EXPECT_EQ(r.exitCode, 1) << args << " with " << folder;
      EXPECT_EQ(r.err, "penumbra: the cache folder " + folder + " " + problem + "\n") << args;
      EXPECT_TRUE(r.out.empty()) << r.out;
    }
    const RunResult c = runPenumbra("compare --size 24x16 --shadow-map 1024 --samples 2 --json --out imgs", dir, cacheEnv(folder));
    ASSERT_EQ(c.exitCode, 0) << c.err;
    EXPECT_NE(c.err.find("penumbra: warning: reference cache: the cache folder " + folder + " " + problem +
                         "; references are traced but not kept"),
              std::string::npos) << c.err;
    EXPECT_EQ(std::count(c.err.begin(), c.err.end(), '\n'), 1) << "one warning: " << c.err;
    EXPECT_TRUE(fs::exists(dir + "/imgs/sheet.png"));
  }
  EXPECT_FALSE(fs::exists(dir + "/nowhere")) << "the link's target is not made";
}

// A cache folder this user cannot write (as root, the runs drop to nobody): compare keeps its
// traced result, writes its images and says once that the reference is not cached; cache
// --clear says what it could not remove and exits 1.
TEST(CacheCli, AReadOnlyFolderCostsTheCacheNotTheResult) {
  const std::string dir = freshDir("cache-read-only");
  const std::string cache = dir + "/c";
  const std::string compare = "compare --size 24x16 --shadow-map 1024 --samples 2 --json --out imgs";
  ASSERT_EQ(runPenumbra(compare + " --camera 4,3,5:0,0.5,0", dir, cacheEnv(cache)).exitCode, 0);  // one entry
  ASSERT_EQ(listed(cacheJson(cache)).size(), 1u);
  // The user the runs are made as: this one, or nobody when this one is root (root writes anywhere).
  std::string as;
  if (geteuid() == 0) {
    if (std::system("command -v setpriv > /dev/null") != 0) GTEST_SKIP() << "root, and no setpriv to run as another user";
    as = "setpriv --reuid=65534 --regid=65534 --clear-groups";
    fs::permissions(dir, fs::perms::all);  // nobody writes the run's output there
    fs::permissions(fs::path(dir) / "imgs", fs::perms::all);
  }
  fs::permissions(cache, fs::perms::owner_read | fs::perms::owner_exec | fs::perms::group_read | fs::perms::group_exec |
                             fs::perms::others_read | fs::perms::others_exec);
  const RunResult r = runPenumbra(compare + " --camera -4,3,5:0,0.5,0", dir, as + " env " + cacheEnv(cache));
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.err.find("penumbra: warning: reference cache: " + cache + "/reference-"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("(Permission denied); references are traced but not kept"), std::string::npos) << r.err;
  EXPECT_FALSE(nlohmann::json::parse(r.out)["reference_cached"].get<bool>());
  EXPECT_TRUE(fs::exists(dir + "/imgs/sheet.png"));
  EXPECT_EQ(listed(cacheJson(cache)).size(), 1u) << "nothing was added";

  const RunResult clear = runPenumbra("cache --clear", dir, as + " env " + cacheEnv(cache));
  EXPECT_EQ(clear.exitCode, 1);
  EXPECT_NE(clear.err.find(cache + ": removed 0 entries, but 1 cannot be removed (the first: reference-"), std::string::npos) << clear.err;
  EXPECT_NE(clear.err.find("Permission denied)"), std::string::npos) << clear.err;
  fs::permissions(cache, fs::perms::owner_all);
  EXPECT_EQ(listed(cacheJson(cache)).size(), 1u) << "the entry is still there, as the message says";
}
