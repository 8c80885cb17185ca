// Sequences from the command line: render --frames writes numbered PNGs (and says what happened
// to the MP4), compare --frames adds the error-over-time keys to the JSON.
#include "CliSupport.h"

#include <penumbra/ImageIO.h>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>

using namespace penumbra;
using namespace penumbra::test;

TEST(MotionCli, RenderFramesWritesANumberedSequence) {
  const std::string dir = freshDir("frames-seq");
  const RunResult r = runPenumbra("render --scene boxes --size 48x32 --shadow-map 256 --frames 3 --fps 0.5 --out seq.png", dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  for (const char* f : {"seq-0000.png", "seq-0001.png", "seq-0002.png"}) EXPECT_TRUE(std::filesystem::exists(dir + "/" + f)) << f;
  EXPECT_FALSE(std::filesystem::exists(dir + "/seq-0003.png"));
  EXPECT_TRUE(std::filesystem::exists(dir + "/seq.mp4") || r.out.find("ffmpeg is not on the PATH") != std::string::npos) << r.out;
  int w = 0, h = 0;
  const std::vector<uint8_t> first = readPng(dir + "/seq-0000.png", w, h), last = readPng(dir + "/seq-0002.png", w, h);
  EXPECT_NE(first, last) << "the ball rolled and the sun moved in 4 s";
  // The first frame is the still frame (the sun's direction comes back from its azimuth and
  // elevation within a float's rounding: a texel on an edge may differ).
  ASSERT_EQ(runPenumbra("render --scene boxes --size 48x32 --shadow-map 256 --out still.png", dir).exitCode, 0);
  const std::vector<uint8_t> still = readPng(dir + "/still.png", w, h);
  ASSERT_EQ(still.size(), first.size());
  size_t differ = 0;
  for (size_t i = 0; i < still.size(); i += 4) differ += still[i] != first[i] || still[i + 1] != first[i + 1] || still[i + 2] != first[i + 2];
  EXPECT_LE(differ, still.size() / 4 / 100) << "pixels of frame 0 that differ from the still frame";
}

TEST(MotionCli, FramesExcludesTheSingleFrameOptions) {
  EXPECT_EQ(runPenumbra("render --frames 2 --repeat 2").exitCode, 2);
  EXPECT_EQ(runPenumbra("render --frames 0").exitCode, 2);
  EXPECT_EQ(runPenumbra("render --frames 2 --fps 0").exitCode, 2);
}

TEST(MotionCli, CompareFramesJsonHasTheTimeKeys) {
  const std::string dir = freshDir("compare-frames");
  const RunResult r = runPenumbra("compare --scene boxes --size 48x32 --shadow-map 256 --samples 4 --frames 3 --fps 1 --json --out imgs", dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  for (const char* k : {"frames", "flicker_pct", "rmse_mean", "rmse_worst_frame", "frame_rmse", "lag_rmse", "ghost_pct", "lag_pixels"})
    EXPECT_TRUE(j.contains(k)) << k;
  EXPECT_EQ(j["frames"], 3);
  EXPECT_EQ(j["frame_rmse"].size(), 3u);
  EXPECT_GE(j["flicker_pct"].get<double>(), 0.0);
  EXPECT_LT(j["rmse_worst_frame"].get<int>(), 3);
  EXPECT_NEAR(j["frame_rmse"][0].get<double>(), j["rmse"].get<double>(), 1e-9) << "frame 0 is the compared frame";
}

// --map-updates: with the boxes' sweeping sun every map is invalid in every frame, so 'invalid'
// draws each frame's map, and a budget of 1 map a frame with a single map updates it every
// frame; --verbose says so. A budget below 1 is a usage error.
TEST(MotionCli, MapUpdatesCountTheMapsAndRefuseABadPolicy) {
  const std::string dir = freshDir("frames-cache");
  const std::string common = "render --scene boxes --size 48x32 --shadow-map 256 --frames 3 --fps 1 --verbose";
  RunResult r = runPenumbra(common + " --map-updates invalid --out cached.png", dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.err.find("cached maps: 0 restored, 3 drawn, 0 kept (--map-updates invalid); staleness max 0"), std::string::npos) << r.err;
  r = runPenumbra(common + " --map-updates 1 --out budget.png", dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.err.find("3 drawn, 0 kept (--map-updates budget 1); staleness max 0"), std::string::npos) << r.err;
  // A still sun over a rolling ball (tests/data/scenes/rolling-ball.json): the map's static
  // casters are restored in every frame after the first.
  r = runPenumbra("render --scene '" PENUMBRA_TEST_DATA "/scenes/rolling-ball.json' --size 48x32 --shadow-map 256 --frames 3 --verbose "
                  "--map-updates invalid --out ball.png",
                  dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.err.find("cached maps: 2 restored, 1 drawn, 0 kept"), std::string::npos) << r.err;
  for (const char* bad : {"0", "sometimes", "2x"}) {
    r = runPenumbra(common + " --map-updates " + bad + " --out bad.png", dir);
    EXPECT_NE(r.exitCode, 0) << bad;
    EXPECT_NE(r.err.find("expected every, invalid or a number of maps per frame >= 1"), std::string::npos) << r.err;
  }
}

// compare --map-updates N: the JSON names the policy and what it did over every frame rendered
// (the warm-up and timed still frames, then the sequence): csm's 4 cascades, 2 updated a frame
// after the first, 2 kept, none older than 1 frame.
TEST(MotionCli, CompareReportsTheMapBudgetsStaleness) {
  const std::string dir = freshDir("compare-budget");
  const RunResult r = runPenumbra("compare --scene boxes --projection csm --size 48x32 --shadow-map 256 --samples 4 --frames 3 --fps 1 "
                                  "--map-updates 2 --json --out imgs",
                                  dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["map_updates"], "budget 2");
  const int frames = j["warmup_frames"].get<int>() + j["timed_frames"].get<int>() + 3;  // still, then --frames 3
  EXPECT_EQ(j["maps_kept"], 2 * (frames - 1));
  EXPECT_EQ(j["staleness_max"], 1);
  // 2 maps kept at 1 frame old on every frame after the first, of 4 maps a frame.
  EXPECT_NEAR(j["staleness_mean"].get<double>(), 2.0 * (frames - 1) / (4.0 * frames), 1e-9);
}

// A light's own map updates from the scene file, and each light's flicker and lag: two suns over
// a rolling ball (tests/data/scenes/two-suns.json) with csm's 4 cascades, the first with a
// budget of its own of 1 map a frame, the second following --map-updates invalid. compare --json says per light which policy it followed,
// how many of its maps the compared frame kept, and its own flicker and lag over the sequence.
TEST(MotionCli, EachLightHasItsOwnMapUpdatesAndFlicker) {
  const std::string dir = freshDir("per-light-updates");
  const RunResult r = runPenumbra("compare --scene '" PENUMBRA_TEST_DATA "/scenes/two-suns.json' --projection csm --size 48x32 --shadow-map 256 --samples 4 --frames 3 "
                                  "--fps 1 --map-updates invalid --json --out imgs",
                                  dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  ASSERT_EQ(j["lights"].size(), 2u);
  const nlohmann::json& own = j["lights"][0];
  const nlohmann::json& shared = j["lights"][1];
  EXPECT_EQ(own["map_updates"], "budget 1");
  // The per-light map keys are of the compared still frame (as every key but the sequence's),
  // the last timed one: 3 of 4 cascades kept, one map drawn a frame in turn after the first
  // frame drew all four, so the oldest is 3 frames old from the fourth frame on.
  const int still = j["warmup_frames"].get<int>() + j["timed_frames"].get<int>();
  ASSERT_GE(still, 4);
  EXPECT_EQ(own["maps_kept"], 3);
  EXPECT_EQ(own["staleness"], 3);
  EXPECT_EQ(shared["map_updates"], "invalid");
  EXPECT_EQ(shared["maps_kept"], 0);
  EXPECT_EQ(shared["staleness"], 0);
  for (const nlohmann::json& l : j["lights"])
    for (const char* key : {"flicker_pct", "lag_rmse", "ghost_pct"}) EXPECT_TRUE(l.contains(key)) << key;
}
