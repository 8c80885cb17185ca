// penumbra bench as a user runs it: CSV and JSON carry the same rows; the HTML report opens in
// headless Chromium without console errors and shows its charts and image grid.
#include "CliSupport.h"

#include <penumbra/ImageIO.h>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>

using namespace penumbra::test;
namespace fs = std::filesystem;

namespace {

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// RFC 4180: fields separated by commas, records by CRLF or LF, quoted fields may hold both and
// "" for a quote.
std::vector<std::vector<std::string>> parseCsv(const std::string& text) {
  std::vector<std::vector<std::string>> rows(1, std::vector<std::string>(1));
  bool quoted = false;
  for (size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (quoted) {
      if (c == '"' && i + 1 < text.size() && text[i + 1] == '"') {
        rows.back().back() += '"';
        ++i;
      } else if (c == '"') {
        quoted = false;
      } else {
        rows.back().back() += c;
      }
    } else if (c == '"') {
      quoted = true;
    } else if (c == ',') {
      rows.back().emplace_back();
    } else if (c == '\n') {
      rows.emplace_back(1);
    } else if (c != '\r') {
      rows.back().back() += c;
    }
  }
  if (rows.back().size() == 1 && rows.back()[0].empty()) rows.pop_back();
  return rows;
}

// The first of Debian's and other distributions' Chromium binaries on PATH, or "".
std::string findChromium() {
  const char* path = std::getenv("PATH");
  std::stringstream dirs(path ? path : "");
  std::vector<std::string> folders;
  for (std::string d; std::getline(dirs, d, ':');) folders.push_back(d);
  for (const char* name : {"chromium", "chromium-browser", "google-chrome", "google-chrome-stable"})
    for (const std::string& d : folders)
      if (!d.empty() && fs::exists(fs::path(d) / name)) return (fs::path(d) / name).string();
  return {};
}

}  // namespace

TEST(BenchCli, CsvAndJsonCarryTheSameRows) {
  const std::string dir = freshDir("bench-rows");
  const RunResult r = runPenumbra(
      "bench --scenes boxes --filters hard,pcf --projections uniform,csm --sweep pcf.radiusTexels=1:2:2 "
      "--size 64x48 --shadow-map 1024 --frames 2 --samples 4 --no-cache --out out",
      dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const std::vector<std::vector<std::string>> csv = parseCsv(slurp(dir + "/out/results.csv"));
  const nlohmann::json json = nlohmann::json::parse(slurp(dir + "/out/results.json"));
  ASSERT_FALSE(csv.empty());
  const std::vector<std::string>& header = csv[0];
  EXPECT_EQ(header, json["columns"].get<std::vector<std::string>>());
  // hard on 2 projections + pcf on 2 projections × 2 radii.
  ASSERT_EQ(csv.size() - 1, 6u);
  ASSERT_EQ(json["rows"].size(), 6u);
  for (size_t i = 1; i < csv.size(); ++i) {
    const nlohmann::json& row = json["rows"][i - 1];
    ASSERT_EQ(csv[i].size(), header.size()) << "CSV line " << i;
    for (size_t c = 0; c < header.size(); ++c) {
      const std::string& cell = csv[i][c];
      const nlohmann::json& value = row.at(header[c]);
      if (value.is_null()) {
        EXPECT_TRUE(cell.empty()) << header[c];
      } else if (value.is_number()) {
        // The CSV's shortest round-trip text reads back as the very same double.
        EXPECT_EQ(std::strtod(cell.c_str(), nullptr), value.get<double>()) << header[c] << " row " << i;
      } else {
        EXPECT_EQ(cell, value.get<std::string>()) << header[c] << " row " << i;
      }
    }
  }
  // The numbers are measurements, not placeholders.
  for (const nlohmann::json& row : json["rows"]) {
    EXPECT_GT(row["visibility_ms_median"].get<double>(), 0.0);
    EXPECT_LE(row["visibility_ms_p10"].get<double>(), row["visibility_ms_median"].get<double>());
    EXPECT_GE(row["visibility_ms_p90"].get<double>(), row["visibility_ms_median"].get<double>());
    EXPECT_GT(row["pixels"].get<double>(), 0.0);
    EXPECT_LT(row["rmse"].get<double>(), 0.5);
  }
  EXPECT_EQ(json["rows"][0]["gl_renderer"], json["machine"]["gl_renderer"]);
}

// The whole cost of every row of the quick run: shadow_cost_ms_* are the quantiles of the
// per-frame sum of the shadow, prefilter and visibility passes, and the contact pass where contact
// shadows are on (docs/bench.md states the rule),
// recomputed here from the frame samples frames.json carries; shadow_memory_mb is there for
// every row; one-off costs only where a technique made something once (sdf's bake).
TEST(BenchCli, QuickRunWritesTheWholeCostMemoryAndOneOffCostsOfEveryRow) {
  const std::string dir = freshDir("bench-cost");
  const RunResult r = runPenumbra("bench --quick --out out", dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const nlohmann::json json = nlohmann::json::parse(slurp(dir + "/out/results.json"));
  const nlohmann::json& rows = json["rows"];
  ASSERT_GT(rows.size(), 0u);
  ASSERT_EQ(json["per_frame"], "frames.json");
  const nlohmann::json perFrame = nlohmann::json::parse(slurp(dir + "/out/frames.json"));
  ASSERT_EQ(perFrame["frame_ms"].size(), rows.size());
  // The report's own interpolation rule (BenchResults.h timeStats): linear between ranks.
  auto quantile = [](std::vector<double> v, double q) {
    std::sort(v.begin(), v.end());
    const double pos = q * static_cast<double>(v.size() - 1);
    const size_t lo = static_cast<size_t>(pos), hi = std::min(lo + 1, v.size() - 1);
    return v[lo] + (v[hi] - v[lo]) * (pos - static_cast<double>(lo));
  };
  constexpr double kRounding = 1e-9;  // ms: the sums are formed in another order here
  size_t sdfRows = 0;
  for (size_t i = 0; i < rows.size(); ++i) {
    const nlohmann::json& row = rows[i];
    const nlohmann::json& frames = perFrame["frame_ms"][i];
    const std::string what = row["scene"].get<std::string>() + " " + row["projection"].get<std::string>() + " " +
                             row["filter"].get<std::string>() + " " + row["params"].get<std::string>();
    std::vector<double> sums(static_cast<size_t>(row["frames"].get<double>()), 0.0);
    for (const char* pass : {"shadow", "prefilter", "visibility", "contact"}) {
      if (std::string(pass) == "contact" && !frames.contains(pass)) continue;  // contact shadows off
      const std::vector<double> ms = frames.at(pass).get<std::vector<double>>();
      ASSERT_EQ(ms.size(), sums.size()) << what << " " << pass;
      for (size_t f = 0; f < ms.size(); ++f) sums[f] += ms[f];
      // The samples are those behind the pass's own columns.
      EXPECT_NEAR(quantile(ms, 0.5), row[std::string(pass) + "_ms_median"].get<double>(), kRounding) << what << " " << pass;
    }
    EXPECT_NEAR(row["shadow_cost_ms_median"].get<double>(), quantile(sums, 0.5), kRounding) << what;
    EXPECT_NEAR(row["shadow_cost_ms_p10"].get<double>(), quantile(sums, 0.1), kRounding) << what;
    EXPECT_NEAR(row["shadow_cost_ms_p90"].get<double>(), quantile(sums, 0.9), kRounding) << what;
    EXPECT_GT(row["shadow_cost_ms_median"].get<double>(), 0.0) << what;

    ASSERT_TRUE(row["shadow_memory_mb"].is_number()) << what;
    EXPECT_GT(row["shadow_memory_mb"].get<double>(), 0.0) << what << ": every technique keeps a map or a field";
    if (row["filter"] == "hard" && row["projection"] == "uniform" && row["params"] == "") {  // no add-on's map
      const double map = row["shadow_map"].get<double>();
      EXPECT_DOUBLE_EQ(row["shadow_memory_mb"].get<double>(), map * map * 4.0 / (1024.0 * 1024.0))
          << "hard keeps one 32-bit depth map";
    }
    if (row["filter"] == "sdf") {
      ++sdfRows;
      EXPECT_GT(row["one_off_s"].get<double>(), 0.0) << what;
      EXPECT_NE(row["one_off_what"].get<std::string>().find("static casters only"), std::string::npos) << what;
    } else {
      EXPECT_TRUE(row["one_off_s"].is_null()) << what;
    }
  }
  EXPECT_GT(sdfRows, 0u) << "the quick run has sdf rows";
}

// Each row carries the compare command that reproduces it: run as printed, compare measures the
// same pixels with the same map and reference, and prints the row's metrics to the fourth digit
// (the frames are deterministic, so in fact to every digit).
TEST(BenchCli, EveryRowReproducesWithItsCompareCommand) {
  const std::string dir = freshDir("bench-reproduce");
  const RunResult r = runPenumbra("bench --scenes pen --filters hard,pcss,vssm --projections uniform,csm "
                                  "--sweep light.size=0.05:0.1:2 --size 96x64 --shadow-map 1024 --samples 16 --frames 1 "
                                  "--out out",
                                  dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const nlohmann::json json = nlohmann::json::parse(slurp(dir + "/out/results.json"));
  ASSERT_EQ(json["rows"].size(), 3u * 2u * 2u);
  auto fourDigits = [](double v) { return std::lround(v * 1e4); };
  for (const nlohmann::json& row : json["rows"]) {
    const std::string command = row["compare_command"].get<std::string>();
    ASSERT_EQ(command.rfind("penumbra compare ", 0), 0u) << command;
    const RunResult c = runPenumbra(command.substr(std::string("penumbra ").size()) + " --json --out imgs", dir);
    ASSERT_EQ(c.exitCode, 0) << command << "\n" << c.err;
    const nlohmann::json cmp = nlohmann::json::parse(c.out);
    for (const char* metric : {"rmse", "penumbra_rmse", "leak_pct", "overdark_pct", "umbra_leak_pct"})
      EXPECT_EQ(fourDigits(cmp[metric].get<double>()), fourDigits(row[metric].get<double>())) << command << ": " << metric;
    EXPECT_EQ(cmp["pixels"].get<double>(), row["pixels"].get<double>()) << command;
    EXPECT_EQ(cmp["shadow_map"].get<double>(), row["shadow_map"].get<double>()) << command;
  }
}

// With no size, map or sample options, bench measures what render and compare show by default:
// the same image size, each scene's own map and the same reference samples.
TEST(BenchCli, DefaultsAreThoseOfCompare) {
  const std::string dir = freshDir("bench-defaults");
  const RunResult r = runPenumbra("bench --scenes pen --filters hard --projections uniform --frames 1 --out out", dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const nlohmann::json row = nlohmann::json::parse(slurp(dir + "/out/results.json"))["rows"][0];
  const RunResult c = runPenumbra("compare --scene pen --filter hard --projection uniform --json --out imgs", dir);
  ASSERT_EQ(c.exitCode, 0) << c.err;
  const nlohmann::json cmp = nlohmann::json::parse(c.out);
  for (const char* key : {"width", "height", "shadow_map", "rmse", "pixels"})
    EXPECT_EQ(cmp[key].get<double>(), row[key].get<double>()) << key;
  EXPECT_NE(row["compare_command"].get<std::string>().find("--samples " + std::to_string(cmp["reference_samples"].get<int>())),
            std::string::npos);
}

// The recommendation of the quick run, checked against its own rows: for every situation the
// rule (Recommendation.h) recomputed here from results.json — candidates, motion, the flicker
// limit, acceptable, the contenders timed again in interleaved rounds, the picks with their ties
// — and the page and the report show them; a quick run's page says it is a quick look, the run
// prints its picks, and a log gets progress lines.
TEST(BenchCli, QuickRecommendationFollowsItsRuleInMotionAndThroughNoise) {
  const std::string dir = freshDir("bench-recommend");
  // On the process CPU clock, which the page's Run: line must carry to be repeated.
  const RunResult r = runPenumbra("bench --quick --out out --choosing choosing.md", dir, "env PENUMBRA_CLOCK=cpu");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const nlohmann::json json = nlohmann::json::parse(slurp(dir + "/out/results.json"));
  const nlohmann::json& rows = json["rows"];
  const nlohmann::json perFrame = nlohmann::json::parse(slurp(dir + "/out/frames.json"));
  const nlohmann::json& motion = perFrame["samples"];
  ASSERT_EQ(motion.size(), rows.size());
  const std::string html = slurp(dir + "/out/report.html"), page = slurp(dir + "/choosing.md");
  EXPECT_FALSE(fs::exists(dir + "/out/choosing.md")) << "--choosing moves the page";
  EXPECT_NE(page.find("](out/report.html)"), std::string::npos) << "the page links the report relative to itself";
  EXPECT_EQ(page.rfind("# Which shadow technique? A quick look, not for decisions", 0), 0u) << "a quick run's page says so";
  EXPECT_NE(r.out.find("picks (a quick look, not for decisions"), std::string::npos) << "the run prints its picks: " << r.out;
  EXPECT_NE(r.err.find("penumbra bench: configurations: "), std::string::npos) << "progress in a log: " << r.err;
  EXPECT_NE(page.find("| flicker % |"), std::string::npos) << "the flicker column";
  EXPECT_NE(page.find("- Run: `PENUMBRA_CLOCK=cpu "), std::string::npos) << "the clock the run was timed with";
  ASSERT_EQ(json["recommendations"].size(), 5u) << "contact-hardening, wide sun, thin casters, static, translucent";
  for (const nlohmann::json& rec : json["recommendations"]) {
    const std::string situation = rec["situation"], scene = rec["scene"], metric = rec["metric"];
    const bool staticCasters = rec["static_casters"];
    // Candidates: the scene's rows at its own light; one-off work only where casters are static;
    // the contact plan's off row is the plain row measured again, which stands for it.
    const auto plainTwin = [&](const nlohmann::json& row) {
      return std::any_of(rows.begin(), rows.end(), [&](const nlohmann::json& o) {
        return o["scene"] == row["scene"] && o["filter"] == row["filter"] && o["projection"] == row["projection"] &&
               o["params"].get<std::string>().empty();
      });
    };
    std::vector<size_t> candidates;
    for (size_t i = 0; i < rows.size(); ++i) {
      const nlohmann::json& row = rows[i];
      if (row["scene"] != scene || row["params"].get<std::string>().find("light.") != std::string::npos) continue;
      if (!staticCasters && !row["one_off_s"].is_null()) continue;
      if (row["params"] == "contact.shadows=off" && plainTwin(row)) continue;
      candidates.push_back(i);
    }
    ASSERT_FALSE(candidates.empty()) << situation << ": the quick run measures " << scene;
    EXPECT_EQ(rec["candidates"].get<std::vector<size_t>>(), candidates) << situation;
    // Every candidate was scored in motion: the still frame and 2 more; the static situation over a walk.
    for (const size_t i : candidates) {
      ASSERT_FALSE(motion[i]["motion"].is_null()) << situation << " row " << i;
      EXPECT_EQ(motion[i]["motion"][metric].size(), 3u) << situation;
      if (staticCasters) {
        EXPECT_EQ(motion[i]["motion"]["what"], "a camera walk") << situation;
      }
      const std::vector<double> frames = motion[i]["motion"][metric];
      // The still frame first; a row that accumulates V over frames goes on accumulating, so its
      // first motion frame is the still frame one frame later.
      if (rows[i]["params"].get<std::string>().find("temporal.accumulate=on") == std::string::npos)
        EXPECT_DOUBLE_EQ(frames.front(), rows[i][metric].get<double>()) << "the still frame first";
      else
        EXPECT_NEAR(frames.front(), rows[i][metric].get<double>(), 0.1 * rows[i][metric].get<double>()) << "the still frame first";
    }
    const auto error = [&](size_t i) {
      const std::vector<double> e = motion[i]["motion"][metric];
      double sum = 0.0;
      for (const double v : e) sum += v;
      return sum / static_cast<double>(e.size());
    };
    const auto flicker = [&](size_t i) { return rows[i]["flicker_pct"].get<double>(); };
    const double maxFlicker = rec["max_flicker_pct"];
    EXPECT_DOUBLE_EQ(maxFlicker, 0.1);
    std::vector<size_t> steady, flickering;
    for (const size_t i : candidates) (flicker(i) > maxFlicker ? flickering : steady).push_back(i);
    EXPECT_EQ(rec["flickering"].get<std::vector<size_t>>(), flickering) << situation;
    for (const size_t i : flickering) {  // the page says why each was left out
      const std::string params = rows[i]["params"];
      EXPECT_NE(page.find(fmt::format("{} · {}{} ({:.3f} %)", rows[i]["filter"].get<std::string>(),
                                      rows[i]["projection"].get<std::string>(), params.empty() ? "" : " · " + params, flicker(i))),
                std::string::npos)
          << situation << " row " << i;
    }
    if (steady.empty()) continue;
    double best = error(steady[0]);
    for (const size_t i : steady) best = std::min(best, error(i));
    EXPECT_NEAR(rec["best_error"].get<double>(), best, 1e-12) << situation;
    std::vector<size_t> acceptable;
    for (const size_t i : steady)
      if (error(i) <= 2.0 * best) acceptable.push_back(i);
    EXPECT_EQ(rec["acceptable"].get<std::vector<size_t>>(), acceptable) << situation;
    // Contenders: acceptable and not beaten clearly; with two or more, every one timed in rounds.
    const std::vector<size_t> contenders = rec["contenders"];
    for (const size_t i : contenders) EXPECT_NE(std::find(acceptable.begin(), acceptable.end(), i), acceptable.end());
    const auto costOf = [&](size_t i) {
      return contenders.size() > 1 ? rows[i]["rounds_cost_ms_median"].get<double>() : rows[i]["shadow_cost_ms_median"].get<double>();
    };
    if (contenders.size() > 1)
      for (const size_t i : contenders) {
        ASSERT_FALSE(motion[i]["rounds"].is_null()) << situation << " contender " << i;
        EXPECT_EQ(motion[i]["rounds"]["ms"].size(), 3u) << "--quick's rounds";
      }
    // The picks among the contenders: the cheapest (or the simplest of a tie), the most accurate
    // (or the cheapest of a tie); every pick acceptable.
    double cheapest = 1e300, lowest = 1e300;
    for (const size_t i : contenders) {
      cheapest = std::min(cheapest, costOf(i));
      lowest = std::min(lowest, error(i));
    }
    for (const char* budget : {"cheapest_acceptable", "balanced", "best"}) {
      ASSERT_TRUE(rec[budget].is_number()) << situation << " " << budget;
      const size_t pick = rec[budget].get<size_t>();
      const std::string name = situation + " " + budget + ": " + rows[pick]["filter"].get<std::string>() + " · " +
                               rows[pick]["projection"].get<std::string>();
      EXPECT_NE(rows[pick]["params"], "contact.shadows=off") << name << ": named after a parameter at its default";
      EXPECT_NE(std::find(contenders.begin(), contenders.end(), pick), contenders.end()) << name;
      EXPECT_LE(flicker(pick), maxFlicker) << name;
      EXPECT_LE(error(pick), 2.0 * best) << name;
      // The report and the page name the pick with its reproducing command.
      const std::string command = rows[pick]["compare_command"].get<std::string>();
      EXPECT_NE(page.find(command), std::string::npos) << name;
      EXPECT_NE(html.find(command), std::string::npos) << name;
    }
    const size_t cheap = rec["cheapest_acceptable"], top = rec["best"];
    if (rec["cheapest_tie"].is_null()) {
      EXPECT_DOUBLE_EQ(costOf(cheap), cheapest) << situation;
    } else {
      EXPECT_NE(page.find("Tie for the cheapest acceptable"), std::string::npos) << situation;
    }
    if (rec["best_tie"].is_null()) {
      EXPECT_DOUBLE_EQ(error(top), lowest) << situation;
    } else {
      EXPECT_NE(page.find("Tie for the best"), std::string::npos) << situation;
    }
    EXPECT_NE(html.find("id=\"choose-" + situation + "\""), std::string::npos) << situation;
    EXPECT_NE(page.find("<a id=\"" + situation + "\">"), std::string::npos) << situation;
  }
  EXPECT_NE(page.find(json["machine"]["gl_renderer"].get<std::string>()), std::string::npos) << "the machine is named";
}

// bench --micro-only: the micro table alone, in micro.csv and results.json alike. Every block runs
// (each lookup kernel passed its check against its pass), and each visibility pass has its
// ratio to its kernel: the table the visibility shaders are measured with (docs/bench.md). A pass
// measured again against the kernel of its own taps repeats the pass's times exactly; vsm and msm
// without their footprint are measured against the one-tap kernels of their default rows.
TEST(BenchCli, MicroOnlyReportsEachPassOverItsKernel) {
  const std::string dir = freshDir("bench-micro");
  const RunResult r = runPenumbra("bench --micro-only --size 64x48 --shadow-map 1024 --micro-rounds 3 --out out", dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const nlohmann::json json = nlohmann::json::parse(slurp(dir + "/out/results.json"));
  EXPECT_TRUE(json["rows"].empty());
  const std::vector<std::vector<std::string>> csv = parseCsv(slurp(dir + "/out/micro.csv"));
  ASSERT_EQ(csv.size() - 1, json["micro"].size());
  const std::vector<std::string>& header = csv[0];
  auto column = [&](const std::string& name) { return static_cast<size_t>(std::find(header.begin(), header.end(), name) - header.begin()); };
  size_t passes = 0, ownTaps = 0;
  std::map<std::string, double> passMs;
  for (size_t i = 0; i < json["micro"].size(); ++i) {
    const nlohmann::json& m = json["micro"][i];
    const std::string name = m["name"];
    EXPECT_EQ(m["error"], "") << name;
    EXPECT_EQ(csv[i + 1][column("name")], name);
    EXPECT_GT(m["ms"]["median"].get<double>(), 0.0) << name;
    if (m["baseline"] == "") {
      EXPECT_TRUE(m["ratio"].is_null()) << name;
      EXPECT_TRUE(csv[i + 1][column("ratio_median")].empty()) << name;
      continue;
    }
    ASSERT_TRUE(m["ratio"].is_object()) << name;
    EXPECT_GT(m["ratio"]["median"].get<double>(), 0.0) << name;
    EXPECT_LE(m["ratio"]["p10"].get<double>(), m["ratio"]["median"].get<double>()) << name;
    EXPECT_EQ(std::strtod(csv[i + 1][column("ratio_median")].c_str(), nullptr), m["ratio"]["median"].get<double>()) << name;
    if (name.starts_with("visibility: ")) {
      EXPECT_TRUE(m["baseline"].get<std::string>().starts_with("lookup: ")) << name;
      const size_t suffix = name.find(", against the kernel of its own taps");
      if (suffix == std::string::npos) {
        ++passes;
        passMs[name] = m["ms"]["median"].get<double>();
      } else {
        ++ownTaps;
        ASSERT_TRUE(passMs.contains(name.substr(0, suffix))) << name << ": its pass comes first";
        EXPECT_EQ(m["ms"]["median"].get<double>(), passMs[name.substr(0, suffix)]) << name;
      }
    }
  }
  EXPECT_EQ(passes, 9u) << "hard, pcf, pcf with hardware compare, vsm, vssm, smrt, msm, vsm and msm with footprint=off";
  for (const char* pass : {"visibility: vsm, footprint=off", "visibility: msm, footprint=off"})
    EXPECT_TRUE(passMs.contains(pass)) << pass;
  EXPECT_EQ(ownTaps, 3u) << "pcf's Poisson disk, vsm's and msm's footprints";
  EXPECT_NE(json["machine"]["clock"], "");
}

TEST(BenchCli, UnknownSweepKeyIsAUsageError) {
  const RunResult r = runPenumbra("bench --filters hard --sweep pcss.filterSamples=4:8:2");
  EXPECT_EQ(r.exitCode, 2) << r.err;
  EXPECT_NE(r.err.find("pcss.filterSamples"), std::string::npos) << r.err;
}

// bench --camera measures the scene from that view: the row is compare's from the same camera
// (same reference samples and map), the camera is recorded, and it belongs to one scene only.
TEST(BenchCli, CameraMeasuresTheSceneFromThatView) {
  const std::string dir = freshDir("bench-camera");
  const std::string camera = "3,2.5,4:0,0.4,0:35";
  RunResult r = runPenumbra("bench --scenes boxes --filters hard --projections uniform --camera " + camera +
                                " --size 96x64 --shadow-map 1024 --frames 1 --samples 4 --out out",
                            dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const nlohmann::json json = nlohmann::json::parse(slurp(dir + "/out/results.json"));
  EXPECT_EQ(json["settings"]["camera"], camera);
  ASSERT_EQ(json["rows"].size(), 1u);
  EXPECT_NE(slurp(dir + "/out/report.html").find("--camera " + camera), std::string::npos);
  const std::string compare = "compare --scene boxes --filter hard --projection uniform --size 96x64 --shadow-map 1024 "
                              "--samples 4 --json --out imgs";
  r = runPenumbra(compare + " --camera " + camera, dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const nlohmann::json fromView = nlohmann::json::parse(r.out);
  EXPECT_EQ(json["rows"][0]["rmse"], fromView["rmse"]);
  EXPECT_EQ(json["rows"][0]["pixels"], fromView["pixels"]);
  r = runPenumbra(compare, dir);  // the scene's own camera: another image
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(nlohmann::json::parse(r.out)["pixels"], fromView["pixels"]);

  r = runPenumbra("bench --scenes boxes,pen --filters hard --camera " + camera);
  EXPECT_EQ(r.exitCode, 2) << r.err;
  EXPECT_NE(r.err.find("--scenes NAME"), std::string::npos) << r.err;
  r = runPenumbra("bench --scenes boxes --filters hard --camera 1,2,3");
  EXPECT_EQ(r.exitCode, 2) << r.err;
  EXPECT_NE(r.err.find("expected X,Y,Z:TX,TY,TZ[:FOV]"), std::string::npos) << r.err;
}

TEST(BenchCli, QuickReportOpensInChromiumWithChartsAndImageGrid) {
  const std::string chromium = findChromium();
  if (chromium.empty())
    GTEST_SKIP() << "Chromium not found on PATH (Debian: apt-get install chromium, or scripts/install-deps); "
                    "the report was not checked in a browser";
  const std::string dir = freshDir("bench-quick");
  const RunResult r = runPenumbra("bench --quick --no-cache --out out", dir);
  // Every configuration of the quick plan renders (1 would mean one failed; the report is
  // written either way).
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const fs::path report = fs::path(dir) / "out" / "report.html";
  ASSERT_TRUE(fs::exists(report));

  const std::string flags = "--headless --no-sandbox --disable-gpu --disable-quic --no-first-run "
                            "--disable-background-networking --disable-component-update --disable-sync "
                            "--user-data-dir='" + dir + "/profile' ";
  const std::string url = "file://" + report.string();
  const std::string shot = dir + "/shot.png";
  const std::string shotCmd = "'" + chromium + "' " + flags + "--screenshot='" + shot +
                              "' --window-size=1280,2000 '" + url + "' > '" + dir + "/shot.log' 2>&1";
  ASSERT_EQ(std::system(shotCmd.c_str()), 0) << slurp(dir + "/shot.log");
  int w = 0, h = 0;
  const std::vector<uint8_t> pixels = penumbra::readPng(shot, w, h);
  ASSERT_EQ(w, 1280);
  // Not a blank page: the charts and text leave many non-white pixels.
  size_t ink = 0;
  for (size_t i = 0; i + 3 < pixels.size(); i += 4)
    if (pixels[i] < 200 || pixels[i + 1] < 200 || pixels[i + 2] < 200) ++ink;
  EXPECT_GT(static_cast<double>(ink) / (static_cast<double>(w) * h), 0.02);

  const std::string domCmd = "'" + chromium + "' " + flags + "--enable-logging=stderr --v=0 --dump-dom '" + url +
                             "' > '" + dir + "/dom.html' 2> '" + dir + "/dom.log'";
  ASSERT_EQ(std::system(domCmd.c_str()), 0) << slurp(dir + "/dom.log");
  const std::string dom = slurp(dir + "/dom.html"), log = slurp(dir + "/dom.log");
  // Chromium logs every console message as ":CONSOLE"; the page has no script, so any is an error.
  EXPECT_EQ(log.find(":CONSOLE"), std::string::npos) << log;
  const std::regex svg("<svg[^>]*class=\"chart\""), img("<img src=\"([^\"]+)\"");
  const auto charts = std::distance(std::sregex_iterator(dom.begin(), dom.end(), svg), std::sregex_iterator());
  EXPECT_GE(charts, 4) << "quality-vs-cost per scene and cost/error against light size";
  EXPECT_NE(dom.find("class=\"grid\""), std::string::npos);
  size_t images = 0;
  for (auto it = std::sregex_iterator(dom.begin(), dom.end(), img); it != std::sregex_iterator(); ++it, ++images)
    EXPECT_TRUE(fs::exists(report.parent_path() / (*it)[1].str())) << (*it)[1].str();
  EXPECT_GE(images, 3u * 2u) << "technique | reference | heatmap for at least two filters";
}
