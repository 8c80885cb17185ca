// penumbra tune as a user runs it: at a tiny size, the recommended configuration is no worse than
// the default within the budget, and `compare` with its printed command reproduces its error;
// an interrupted (or repeated) run resumes from evaluations.jsonl; bad input fails clearly.
#include "CliSupport.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <sstream>

using namespace penumbra::test;
namespace fs = std::filesystem;

namespace {

// Tiny: seconds per configuration on llvmpipe. The reference at 16 samples is cached after the
// first run.
const std::string kTinyTune =
    "tune --scene pen --filters pcf --size 96x54 --shadow-map 256 --samples 16 --candidates 6 --max-minutes 1 --out out";

// compare's error agrees with the tuned row's within this fraction (the 2 %).
constexpr double kReproduceFraction = 0.02;

nlohmann::json readJson(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream ss;
  ss << in.rdbuf();
  return nlohmann::json::parse(ss.str());
}

}  // namespace

TEST(TuneCli, RecommendsNoWorseThanTheDefaultWithinBudgetAndCompareReproducesIt) {
  const std::string dir = freshDir("tune-pen");
  const RunResult r = runPenumbra(kTinyTune + " --json", dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.err.find("about"), std::string::npos) << "progress with the time left on stderr: " << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j, readJson(fs::path(dir) / "out" / "tune.json"));
  EXPECT_TRUE(fs::exists(fs::path(dir) / "out" / "tune.html"));
  for (const char* key : {"recommended", "default", "front", "gl_renderer", "cpu"}) EXPECT_TRUE(j.contains(key)) << key;
  const nlohmann::json& rec = j["recommended"];
  const nlohmann::json& def = j["default"];
  for (const nlohmann::json* row : {&rec, &def})
    for (const char* key : {"filter", "projection", "params", "rmse", "shadow_cost_ms", "shadow_memory_mb", "command"})
      EXPECT_TRUE(row->contains(key)) << key;
  EXPECT_EQ(rec["filter"], "pcf");
  EXPECT_LE(rec["rmse"].get<double>(), def["rmse"].get<double>());
  EXPECT_LE(rec["shadow_cost_ms"].get<double>(), j["budget_ms"].get<double>());
  EXPECT_GE(j["front"].size(), 1u);
  for (const auto& [key, value] : rec["params"].items()) {
    // --set keys of the technique tuned: the filter's and the projection's (the scene's own: uniform)
    EXPECT_TRUE(key.starts_with("pcf.") || key.starts_with("uniform.")) << key;
    EXPECT_NE(rec["command"].get<std::string>().find("--set " + key + "="), std::string::npos) << key;
  }

  // The printed compare line, run as is, gives the same error.
  std::string command = rec["command"].get<std::string>();
  ASSERT_EQ(command.rfind("penumbra compare ", 0), 0u) << command;
  command = command.substr(std::string("penumbra ").size()) + " --json --out cmp";
  const RunResult c = runPenumbra(command, dir);
  ASSERT_EQ(c.exitCode, 0) << c.err;
  const double rmse = nlohmann::json::parse(c.out)["rmse"].get<double>();
  EXPECT_NEAR(rmse, rec["rmse"].get<double>(), kReproduceFraction * rec["rmse"].get<double>()) << command;

  // The same run again reads every configuration back instead of measuring it.
  const RunResult again = runPenumbra(kTinyTune + " --json", dir);
  ASSERT_EQ(again.exitCode, 0) << again.err;
  const nlohmann::json j2 = nlohmann::json::parse(again.out);
  EXPECT_EQ(j2["evaluations"], 0) << again.err;
  EXPECT_GT(j2["resumed"].get<int>(), 0);
  EXPECT_EQ(j2["recommended"]["params"], rec["params"]);
}

TEST(TuneCli, BadInputFailsWithOneClearLine) {
  const std::string dir = freshDir("tune-bad");
  struct Case {
    std::string args, message;
  };
  for (const Case& k : std::vector<Case>{
           {"tune --scene pen --objective speed", "--objective speed"},
           {"tune --scene pen --filters nosuch", "nosuch"},
           {"tune --scene nosuch", "nosuch"},
           {"tune --scene pen --budget-ms 1 --max-error 0.1", "not both"},
           {"tune --scene pen --budget-ms -1", "--budget-ms"},
           {"tune --filters pcf", "--scene"},
           {"tune --scene pen --shard 1/2 --merge a", "not both"},
       }) {
    const RunResult r = runPenumbra(k.args, dir);
    EXPECT_NE(r.exitCode, 0) << k.args;
    EXPECT_NE(r.err.find(k.message), std::string::npos) << k.args << ": " << r.err;
  }
}

TEST(TuneCli, HelpNamesTheOptionsAndOutputs) {
  const RunResult r = runPenumbra("tune --help");
  ASSERT_EQ(r.exitCode, 0);
  for (const char* word : {"--budget-ms", "--budget-mb", "--objective", "--max-minutes", "--filters", "--projections",
                           "tune.json", "tune.html", "evaluations.jsonl", "--json"})
    EXPECT_NE(r.out.find(word), std::string::npos) << word;
}

TEST(TuneCli, AcneSearchesTheBiasOnlyAndReturnsOneWithoutAcne) {
  const std::string dir = freshDir("tune-acne");
  const RunResult r = runPenumbra(
      "tune --scene grazing --filters hard --objective acne --size 96x54 --samples 1 --candidates 6 --max-minutes 1 "
      "--out out --json",
      dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  const nlohmann::json& rec = j["recommended"];
  EXPECT_EQ(j["objective"], "acne");
  EXPECT_LE(rec["acne_pct"].get<double>(), 0.1);
  EXPECT_TRUE(rec.contains("umbra_leak_pct"));
  EXPECT_EQ(rec["shadow_map"], j["default"]["shadow_map"]);  // the map size is not searched
  for (const auto& [key, value] : rec["params"].items())
    EXPECT_TRUE(key == "hard.bias" || key == "hard.constantBias" || key == "hard.slopeBias" || key == "hard.normalOffsetTexels")
        << key;
}

TEST(TuneCli, ShardsMergeIntoTheRunThatMeasuresTheirScreenOnce) {
  const std::string dir = freshDir("tune-shards");
  const std::string base = "tune --scene pen --filters pcf --size 96x54 --shadow-map 256 --samples 16 --candidates 6 --max-minutes 1";
  const std::vector<std::pair<std::string, std::string>> shards = {{"1/2", "s1"}, {"2/2", "s2"}};
  for (const auto& [shard, out] : shards) {
    const RunResult r = runPenumbra(base + " --shard " + shard + " --out " + out, dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.out.find("configurations measured"), std::string::npos) << r.out;
    EXPECT_FALSE(fs::exists(fs::path(dir) / out / "tune.json"));
  }
  const RunResult merged = runPenumbra(base + " --merge s1 s2 --out m --json", dir);
  ASSERT_EQ(merged.exitCode, 0) << merged.err;
  const RunResult single = runPenumbra(base + " --out one --json", dir);
  ASSERT_EQ(single.exitCode, 0) << single.err;
  const nlohmann::json m = nlohmann::json::parse(merged.out), one = nlohmann::json::parse(single.out);
  // The default and the 6 candidates of the screen came from the shards: the merge measured none
  // of them. (The rest of the search may take another path than a single run's: the screen's
  // costs are measured, and noisy, so the halving may keep other candidates.)
  EXPECT_EQ(m["resumed"], 7) << merged.err;
  EXPECT_NE(merged.err.find("1/4 screen: 7 configurations at 57x32 (0 to measure"), std::string::npos) << merged.err;
  EXPECT_EQ(m["default"]["rmse"], one["default"]["rmse"]);
  EXPECT_FALSE(m["front"].empty());

  const RunResult bad = runPenumbra(base + " --shard 3/2 --out x", dir);
  EXPECT_NE(bad.exitCode, 0);
  EXPECT_NE(bad.err.find("--shard 3/2"), std::string::npos) << bad.err;
  const RunResult missing = runPenumbra(base + " --merge nowhere --out y", dir);
  EXPECT_NE(missing.exitCode, 0);
  EXPECT_NE(missing.err.find("nowhere"), std::string::npos) << missing.err;
}

TEST(TuneCli, AnInterruptedRunResumesFromTheRowsItFinished) {
  const std::string dir = freshDir("tune-resume");
  ASSERT_EQ(runPenumbra(kTinyTune + " --json", dir).exitCode, 0);
  // Interrupted after the screen: its 7 rows kept, and the next row cut off in the middle.
  const fs::path log = fs::path(dir) / "out" / "evaluations.jsonl";
  std::vector<std::string> lines;
  {
    std::ifstream in(log);
    for (std::string line; std::getline(in, line);) lines.push_back(line);
  }
  ASSERT_GT(lines.size(), 8u);
  {
    std::ofstream out(log, std::ios::trunc);
    for (size_t i = 0; i < 7; ++i) out << lines[i] << '\n';
    out << lines[7].substr(0, lines[7].size() / 2);
  }
  fs::remove(fs::path(dir) / "out" / "tune.json");
  const RunResult r = runPenumbra(kTinyTune + " --json", dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["resumed"], 7) << r.err;
  EXPECT_GT(j["evaluations"].get<int>(), 0);
  EXPECT_NE(r.err.find("(0 to measure"), std::string::npos) << r.err;  // the screen
  EXPECT_TRUE(fs::exists(fs::path(dir) / "out" / "tune.json"));
}
