#include "CliSupport.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>

using namespace penumbra::test;

TEST(CompareCli, JsonHasTheDocumentedKeysAndImagesAreWritten) {
  const std::string dir = freshDir("compare");
  const RunResult r = runPenumbra("compare --scene pen --size 96x64 --shadow-map 1024 --samples 16 --json --no-cache --out imgs", dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  for (const char* k : {"scene", "filter", "projection", "rmse", "mae", "leak_pct", "overdark_pct", "penumbra_rmse",
                        "approximation_rmse", "timings_ms", "reference_seconds", "texel_density_median",
                        "texel_density_p95", "texel_density_near_median", "undersampled_pct"})
    EXPECT_TRUE(j.contains(k)) << k;
  EXPECT_EQ(j["scene"], "pen");
  EXPECT_EQ(j["filter"], "hard");
  EXPECT_TRUE(j["timings_ms"].contains("visibility"));
  EXPECT_GT(j["rmse"].get<double>(), 0.0);
  EXPECT_LT(j["rmse"].get<double>(), 0.5);
  for (const char* f : {"technique.png", "reference.png", "heatmap.png", "approximation.png", "sheet.png"})
    EXPECT_TRUE(std::filesystem::exists(dir + "/imgs/" + f)) << f;
}

// The JSON names the camera as a --camera argument; given back, it repeats the run's numbers.
TEST(CompareCli, CameraInTheJsonRepeatsTheRun) {
  const std::string dir = freshDir("compare-camera");
  const std::string common = "compare --scene boxes --size 96x64 --shadow-map 512 --samples 4 --json --out imgs";
  RunResult r = runPenumbra(common + " --camera 3,2.5,4:0,0.4,0:35", dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const nlohmann::json first = nlohmann::json::parse(r.out);
  ASSERT_TRUE(first.contains("camera"));
  r = runPenumbra(common + " --camera " + first["camera"].get<std::string>(), dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const nlohmann::json again = nlohmann::json::parse(r.out);
  EXPECT_EQ(again["camera"], first["camera"]);
  EXPECT_EQ(again["rmse"], first["rmse"]);
  EXPECT_EQ(again["pixels"], first["pixels"]);
  r = runPenumbra(common, dir);  // the scene's own camera sees something else
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(nlohmann::json::parse(r.out)["camera"], first["camera"]);
}

TEST(CompareCli, ShimmerReportsAPercentage) {
  const RunResult r = runPenumbra("compare --scene boxes --projection csm --size 96x64 --shadow-map 512 --samples 4 --shimmer 5 --json --out imgs");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  ASSERT_TRUE(j.contains("shimmer_pct"));
  EXPECT_GE(j["shimmer_pct"].get<double>(), 0.0);
  EXPECT_LE(j["shimmer_pct"].get<double>(), 100.0);
  EXPECT_EQ(j["shimmer_steps"], 5);
}

TEST(CompareCli, BadSamplesIsAUsageError) {
  const RunResult r = runPenumbra("compare --samples 0");
  EXPECT_EQ(r.exitCode, 2);
}
