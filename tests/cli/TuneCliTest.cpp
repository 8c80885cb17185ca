// penumbra tune as a user runs it: at a tiny size, the recommended configuration is no worse than
// the default within the budget, and `compare` with its printed command reproduces its error;
// tuned cascades beat the default ones on city at equal memory; several views are each measured
// and aggregated; shards merged give one run's front (--cost model); an interrupted (or
// repeated) run resumes from evaluations.jsonl; bad input fails clearly.
#include "CliSupport.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

using namespace penumbra::test;
namespace fs = std::filesystem;

namespace {

// Tiny: seconds per configuration on llvmpipe. The reference at 16 samples is cached after the
// first run.
const std::string kTinyTune =
    "tune --scene pen --filters pcf --size 96x54 --shadow-map 1024 --samples 16 --candidates 6 --max-minutes 1 --out out";

// compare's error agrees with the tuned row's within this fraction (the 2 %).
constexpr double kReproduceFraction = 0.02;

nlohmann::json readJson(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream ss;
  ss << in.rdbuf();
  return nlohmann::json::parse(ss.str());
}

// The --json output of a run that must succeed; null (after a failure naming the run) otherwise.
nlohmann::json jsonOf(const std::string& args, const std::string& dir) {
  const RunResult r = runPenumbra(args, dir);
  EXPECT_EQ(r.exitCode, 0) << args << ": " << r.err;
  return r.exitCode == 0 ? nlohmann::json::parse(r.out) : nlohmann::json();
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
  // Confirmed in interleaved rounds with the default: never over the budget within the noise.
  EXPECT_GT(rec["cost_rounds"].get<int>(), 1);
  EXPECT_LE(rec["budget_cost_ms"].get<double>(), j["budget_ms"].get<double>() * (1.0 + 1e-9));
  EXPECT_LE(rec["cost_ratio"]["p90"].get<double>(), 1.0 + 1e-9);
  // The acne objective's bars hold: acne at most 0.1 %, umbra leak at most the default's + 0.01.
  EXPECT_TRUE(rec["within_bars"].get<bool>());
  EXPECT_LE(rec["acne_pct"].get<double>(), std::max(0.1, def["acne_pct"].get<double>()));
  EXPECT_LE(rec["umbra_leak_pct"].get<double>(), def["umbra_leak_pct"].get<double>() + 0.01);
  EXPECT_GE(j["front"].size(), 1u);
  // pen is lit by a spot: the point lights' cube guard band cannot change its frame, so it is
  // neither searched nor printed.
  for (const nlohmann::json& row : j["explored"]) EXPECT_FALSE(row["params"].contains("uniform.cubeGuardTexels")) << row["params"];
  EXPECT_EQ(r.out.find("cubeGuardTexels"), std::string::npos);
  for (const auto& [key, value] : rec["params"].items()) {
    // --set keys of the technique tuned: the filter's and the projection's (the scene's own: uniform)
    EXPECT_TRUE(key.starts_with("pcf.") || key.starts_with("uniform.")) << key;
    EXPECT_NE(rec["command"].get<std::string>().find("--set " + key + "="), std::string::npos) << key;
  }

  // The printed compare line, run as is, gives the same error.
  std::string command = rec["command"].get<std::string>();
  ASSERT_EQ(command.rfind("penumbra compare ", 0), 0u) << command;
  command = command.substr(std::string("penumbra ").size()) + " --json --out cmp";
  const nlohmann::json c = jsonOf(command, dir);
  ASSERT_FALSE(c.is_null());
  const double rmse = c["rmse"].get<double>();
  EXPECT_NEAR(rmse, rec["rmse"].get<double>(), kReproduceFraction * rec["rmse"].get<double>()) << command;

  // The same run again reads every configuration back instead of measuring it; only the
  // finalists' costs are timed again, so its pick is one of the same finalists.
  const RunResult again = runPenumbra(kTinyTune + " --json", dir);
  ASSERT_EQ(again.exitCode, 0) << again.err;
  const nlohmann::json j2 = nlohmann::json::parse(again.out);
  EXPECT_EQ(j2["evaluations"], 0) << again.err;
  EXPECT_GT(j2["resumed"].get<int>(), 0);
  bool measured = false;
  for (const nlohmann::json& row : j["explored"]) measured = measured || row["params"] == j2["recommended"]["params"];
  EXPECT_TRUE(measured) << j2["recommended"]["params"];
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
           {"tune --scene pen --aggregate median", "--aggregate median"},
           {"tune --scene pen --cost guessed", "--cost guessed"},
           {"tune --scene pen --cost model --budget-ms 5", "--cost model"},
           {"tune --scene pen,nosuch", "nosuch"},
           // --params: every key is a parameter of a technique tuned, or the maps' keys.
           {"tune --scene pen --filters pcf --params pcf.radiusTexels,nosuch.key",
            "--params nosuch.key: not a parameter of --filters pcf or --projections uniform"},
           {"tune --scene pen --filters pcf --params nosuch.key", "--params nosuch.key: not a parameter"},
           {"tune --scene pen --filters pcf --params hard.bias", "--params hard.bias: not a parameter of --filters pcf"},
           {"tune --scene pen --filters hard,pcf --params pcf.radiusTexels",
            "hard · uniform has no parameter to search among --params pcf.radiusTexels"},
       }) {
    const RunResult r = runPenumbra(k.args, dir);
    EXPECT_EQ(r.exitCode, 2) << k.args;
    EXPECT_NE(r.err.find(k.message), std::string::npos) << k.args << ": " << r.err;
    EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << "one line: " << r.err;
    EXPECT_FALSE(fs::exists(fs::path(dir) / "tune")) << k.args << " wrote its output folder";
  }
}

TEST(TuneCli, HelpNamesTheOptionsAndOutputs) {
  const RunResult r = runPenumbra("tune --help");
  ASSERT_EQ(r.exitCode, 0);
  for (const char* word : {"--budget-ms", "--budget-mb", "--objective", "--max-minutes", "--filters", "--projections",
                           "--aggregate", "--cost", "--params", "--camera", "tune.json", "tune.html", "evaluations.jsonl", "--json"})
    EXPECT_NE(r.out.find(word), std::string::npos) << word;
}

TEST(TuneCli, AcneSearchesTheBiasOnlyAndReturnsOneWithoutAcne) {
  const std::string dir = freshDir("tune-acne");
  const nlohmann::json j = jsonOf(
      "tune --scene grazing --filters hard --objective acne --size 96x54 --samples 1 --candidates 6 --max-minutes 1 "
      "--out out --json",
      dir);
  ASSERT_FALSE(j.is_null());
  const nlohmann::json& rec = j["recommended"];
  EXPECT_EQ(j["objective"], "acne");
  EXPECT_LE(rec["acne_pct"].get<double>(), 0.1);
  EXPECT_TRUE(rec.contains("umbra_leak_pct"));
  EXPECT_EQ(rec["shadow_map"], j["default"]["shadow_map"]);  // the map size is not searched
  for (const auto& [key, value] : rec["params"].items())
    EXPECT_TRUE(key == "hard.bias" || key == "hard.constantBias" || key == "hard.slopeBias" || key == "hard.normalOffsetTexels" ||
                key == "hard.planeBiasTexels")
        << key;
}

TEST(TuneCli, ShardsMergedGiveTheSameFrontAsOneRunWithTheModelledCost) {
  const std::string dir = freshDir("tune-shards");
  const std::string base = "tune --scene pen --filters pcf --size 96x54 --shadow-map 1024 --samples 16 --candidates 6 "
                           "--max-minutes 1 --cost model";
  const std::vector<std::pair<std::string, std::string>> shards = {{"1/2", "s1"}, {"2/2", "s2"}};
  for (const auto& [shard, out] : shards) {
    const RunResult r = runPenumbra(base + " --shard " + shard + " --out " + out, dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.out.find("configurations measured"), std::string::npos) << r.out;
    EXPECT_FALSE(fs::exists(fs::path(dir) / out / "tune.json"));
  }
  const nlohmann::json m = jsonOf(base + " --merge s1 s2 --out m --json", dir), one = jsonOf(base + " --out one --json", dir);
  ASSERT_FALSE(m.is_null() || one.is_null());
  // The default and the 6 candidates of the screen came from the shards: the merge measured none of them.
  EXPECT_EQ(m["resumed"], 7);
  EXPECT_EQ(m["cost"], "model");
  // The same front: the same configurations with the same errors and work, in the same order;
  // the same recommendation. (Their milliseconds, measured by different processes, differ.)
  ASSERT_FALSE(one["front"].empty());
  ASSERT_EQ(m["front"].size(), one["front"].size());
  for (size_t i = 0; i < one["front"].size(); ++i)
    for (const char* key : {"params", "shadow_map", "shadow_budget", "rmse", "error", "work_mops", "shadow_memory_mb"})
      EXPECT_EQ(m["front"][i][key], one["front"][i][key]) << key << " of front row " << i;
  EXPECT_EQ(m["recommended"]["params"], one["recommended"]["params"]);
  EXPECT_EQ(m["budget_mops"], one["budget_mops"]);

  const RunResult bad = runPenumbra(base + " --shard 3/2 --out x", dir);
  EXPECT_NE(bad.exitCode, 0);
  EXPECT_NE(bad.err.find("--shard 3/2"), std::string::npos) << bad.err;
  const RunResult missing = runPenumbra(base + " --merge nowhere --out y", dir);
  EXPECT_NE(missing.exitCode, 0);
  EXPECT_NE(missing.err.find("nowhere"), std::string::npos) << missing.err;
}

TEST(TuneCli, SeveralViewsAreEachMeasuredAndTheWorstDecides) {
  const std::string dir = freshDir("tune-views");
  // Two cameras on the pen, from the right and from above the left of the scene's own.
  const std::string views = "tune --scene pen --camera 1.5,1.8,2:-0.5,0.1,-0.3 --camera 0.6,2.4,2.2:-0.8,0.1,-0.2 "
                            "--filters pcf --size 96x54 --shadow-map 1024 --samples 16 --candidates 4 --max-minutes 1 --out out --json";
  const nlohmann::json j = jsonOf(views + " --aggregate worst", dir);
  ASSERT_FALSE(j.is_null());
  ASSERT_EQ(j["views"].size(), 2u);
  EXPECT_EQ(j["aggregate"], "worst");
  for (const char* which : {"recommended", "default"}) {
    const nlohmann::json& row = j[which];
    ASSERT_EQ(row["views"].size(), 2u) << which;
    const double a = row["views"][0]["rmse"].get<double>(), b = row["views"][1]["rmse"].get<double>();
    EXPECT_NE(a, b) << which << ": two views see different images";
    EXPECT_DOUBLE_EQ(row["rmse"].get<double>(), std::max(a, b)) << which;
    EXPECT_DOUBLE_EQ(row["shadow_cost_ms"].get<double>(),
                     std::max(row["views"][0]["shadow_cost_ms"].get<double>(), row["views"][1]["shadow_cost_ms"].get<double>()));
  }
  // Each view's printed compare line reproduces that view.
  for (const nlohmann::json& v : j["recommended"]["views"]) {
    std::string command = v["command"].get<std::string>();
    ASSERT_NE(command.find("--camera " + v["camera"].get<std::string>()), std::string::npos) << command;
    command = command.substr(std::string("penumbra ").size()) + " --json --out cmp";
    const nlohmann::json c = jsonOf(command, dir);
    ASSERT_FALSE(c.is_null());
    EXPECT_NEAR(c["rmse"].get<double>(), v["rmse"].get<double>(),
                kReproduceFraction * v["rmse"].get<double>()) << command;
  }
  // The mean over the same views: the default's rows read back, averaged.
  const nlohmann::json m = jsonOf(views + " --aggregate mean", dir);
  ASSERT_FALSE(m.is_null());
  const nlohmann::json& d = m["default"];
  EXPECT_DOUBLE_EQ(d["rmse"].get<double>(), 0.5 * (d["views"][0]["rmse"].get<double>() + d["views"][1]["rmse"].get<double>()));
}

TEST(TuneCli, TunedCascadesBeatTheDefaultCascadesOnCityAtEqualMapMemory) {
  const std::string dir = freshDir("tune-city");
  // Only the cascades' count, split λ and blend band are searched; the maps' texels in all stay
  // the default's (4 cascades of 2048²), so a count moves each map's side, not the memory.
  const nlohmann::json j = jsonOf(
      "tune --scene city --projections csm --filters hard --params csm.cascades,csm.lambda,csm.blendBandM --size 160x90 "
      "--samples 16 --candidates 6 --cost model --out out --json",
      dir);
  ASSERT_FALSE(j.is_null());
  const nlohmann::json &rec = j["recommended"], &def = j["default"];
  ASSERT_FALSE(rec["params"].empty()) << "the default cascades were kept";
  for (const auto& [key, value] : rec["params"].items()) EXPECT_TRUE(key.starts_with("csm.")) << key;
  EXPECT_LT(rec["rmse"].get<double>(), def["rmse"].get<double>());
  EXPECT_LE(rec["shadow_memory_mb"].get<double>(), def["shadow_memory_mb"].get<double>());
  constexpr int64_t kDefaultTexels = int64_t{4} * 2048 * 2048;
  if (rec["params"].contains("csm.cascades")) {
    EXPECT_EQ(rec["shadow_budget"], kDefaultTexels);
    EXPECT_NE(rec["command"].get<std::string>().find("--shadow-budget " + std::to_string(kDefaultTexels)), std::string::npos);
  }
  std::printf("city cascades: %s RMSE %.5f against the default's %.5f, %.1f MiB both\n", rec["set"].get<std::string>().c_str(),
              rec["rmse"].get<double>(), def["rmse"].get<double>(), def["shadow_memory_mb"].get<double>());
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
  // Progress counts what is measured: the screen, read back whole, shows none; the next stage does.
  EXPECT_EQ(r.err.find("1/4 screen"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("2/4 full size: 1/"), std::string::npos) << r.err;
  EXPECT_TRUE(fs::exists(fs::path(dir) / "out" / "tune.json"));
}
