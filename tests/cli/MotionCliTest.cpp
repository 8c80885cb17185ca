// Sequences from the command line: render --frames writes numbered PNGs (and says what happened
// to the MP4), compare --frames adds the error-over-time keys to the JSON.
#include "CliSupport.h"

#include <penumbra/ImageIO.h>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

using namespace penumbra;
using namespace penumbra::test;

namespace {

/// The ffmpeg on the PATH, or "".
std::string ffmpegOnPath() {
  std::stringstream dirs(std::getenv("PATH") ? std::getenv("PATH") : "");
  for (std::string d; std::getline(dirs, d, ':');)
    if (std::filesystem::is_regular_file(std::filesystem::path(d) / "ffmpeg")) return (std::filesystem::path(d) / "ffmpeg").string();
  return "";
}

/// A stand-in for ffmpeg in `bin`: writes its arguments, one a line, to `argsFile`, checks that
/// its -i pattern names the sequence's first frame, writes "....ftyp" into its last argument and
/// exits `status`.
void writeStandIn(const std::string& bin, const std::string& argsFile, int status) {
  std::filesystem::create_directories(bin);
  const std::string script = bin + "/ffmpeg";
  std::ofstream(script) << "#!/bin/sh\n: > '" << argsFile << "'\n" << R"(prev=
for a in "$@"; do
  printf '%s\n' "$a" >> ")" << argsFile << R"("
  [ "$prev" = -i ] && input=$a
  prev=$a
done
first=$(printf "$input" 0)
[ -f "$first" ] || { echo "ffmpeg stand-in: no first frame '$first'" >&2; exit 3; }
printf '\000\000\000\040ftyp' > "$prev"
exit )" << status << "\n";
  std::filesystem::permissions(script, std::filesystem::perms::owner_all);
}

std::vector<std::string> lines(const std::string& file) {
  std::ifstream in(file);
  std::vector<std::string> out;
  for (std::string l; std::getline(in, l);) out.push_back(l);
  return out;
}

}  // namespace

TEST(MotionCli, RenderFramesWritesANumberedSequence) {
  const std::string dir = freshDir("frames-seq");
  const RunResult r = runPenumbra("render --scene boxes --size 48x32 --shadow-map 1024 --frames 3 --fps 0.5 --out seq.png", dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  for (const char* f : {"seq-0000.png", "seq-0001.png", "seq-0002.png"}) EXPECT_TRUE(std::filesystem::exists(dir + "/" + f)) << f;
  EXPECT_FALSE(std::filesystem::exists(dir + "/seq-0003.png"));
  EXPECT_TRUE(std::filesystem::exists(dir + "/seq.mp4") || r.out.find("ffmpeg is not on the PATH") != std::string::npos) << r.out;
  int w = 0, h = 0;
  const std::vector<uint8_t> first = readPng(dir + "/seq-0000.png", w, h), last = readPng(dir + "/seq-0002.png", w, h);
  EXPECT_NE(first, last) << "the ball rolled and the sun moved in 4 s";
  // The first frame is the still frame (the sun's direction comes back from its azimuth and
  // elevation within a float's rounding: a texel on an edge may differ).
  ASSERT_EQ(runPenumbra("render --scene boxes --size 48x32 --shadow-map 1024 --out still.png", dir).exitCode, 0);
  const std::vector<uint8_t> still = readPng(dir + "/still.png", w, h);
  ASSERT_EQ(still.size(), first.size());
  size_t differ = 0;
  for (size_t i = 0; i < still.size(); i += 4) differ += still[i] != first[i] || still[i + 1] != first[i + 1] || still[i + 2] != first[i + 2];
  EXPECT_LE(differ, still.size() / 4 / 100) << "pixels of frame 0 that differ from the still frame";
}

// render --frames makes its MP4 through ffmpeg run without a shell: a name with a space, quotes,
// parentheses and a '%' reaches it whole (the pattern's own '%' doubled), the pad filter's
// parentheses too. Through the real ffmpeg where one is installed (the file is an MP4), else
// through a stand-in on the PATH that checks its arguments; a failing ffmpeg exits 1 naming it
// and leaves no MP4, the frames written.
TEST(MotionCli, FramesMakeAnMp4ThroughFfmpegWithoutAShell) {
  const std::string dir = freshDir("frames-mp4");
  const std::string real = ffmpegOnPath(), args = dir + "/args.txt";
  const std::string path = "PATH='" + dir + "/bin:" + std::getenv("PATH") + "'";
  if (real.empty()) writeStandIn(dir + "/bin", args, 0);
  const std::string render = "render --scene boxes --size 47x31 --shadow-map 1024 --frames 2 --fps 2.5 --out \"my 'clip' (50%).png\"";
  RunResult r = runPenumbra(render, dir, path);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.out.find("and my 'clip' (50%).mp4"), std::string::npos) << r.out;
  std::ifstream video(dir + "/my 'clip' (50%).mp4", std::ios::binary);
  std::string head(8, '\0');
  video.read(head.data(), 8);
  EXPECT_EQ(head.substr(4), "ftyp") << "an MP4 begins with its ftyp box";
  for (const auto& e : std::filesystem::directory_iterator(dir))
    EXPECT_EQ(e.path().filename().string().find(".tmp."), std::string::npos) << "a temporary file is left: " << e.path();
  if (!real.empty()) return;

  const std::vector<std::string> got = lines(args);
  const std::vector<std::string> expected = {"-y", "-loglevel", "error", "-framerate", "2.5", "-i", "my 'clip' (50%%)-%04d.png",
                                             "-vf", "pad=ceil(iw/2)*2:ceil(ih/2)*2", "-c:v", "libx264", "-pix_fmt", "yuv420p", "-f", "mp4"};
  ASSERT_EQ(got.size(), expected.size() + 1) << r.out;
  for (size_t i = 0; i < expected.size(); ++i) EXPECT_EQ(got[i], expected[i]) << "argument " << i + 1;
  EXPECT_EQ(got.back().rfind("my 'clip' (50%).mp4.", 0), 0u) << "a temporary name beside the MP4: " << got.back();

  writeStandIn(dir + "/bin", args, 1);
  std::filesystem::remove(dir + "/my 'clip' (50%).mp4");
  r = runPenumbra(render, dir, path);
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_NE(r.err.find("ffmpeg failed to write my 'clip' (50%).mp4: it exited with status 1 (the PNG frames are written"),
            std::string::npos) << r.err;
  EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << "one line: " << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir + "/my 'clip' (50%).mp4"));
  EXPECT_TRUE(std::filesystem::exists(dir + "/my 'clip' (50%)-0001.png"));
}

TEST(MotionCli, FramesExcludesTheSingleFrameOptions) {
  EXPECT_EQ(runPenumbra("render --frames 2 --repeat 2").exitCode, 2);
  EXPECT_EQ(runPenumbra("render --frames 0").exitCode, 2);
  EXPECT_EQ(runPenumbra("render --frames 2 --fps 0").exitCode, 2);
  // --fps alone was ignored without a word.
  for (const char* command : {"render", "compare"}) {
    const RunResult r = runPenumbra(std::string(command) + " --fps 10 --size 16x16");
    EXPECT_EQ(r.exitCode, 2) << command;
    EXPECT_EQ(r.err, "penumbra: --fps requires --frames (see penumbra --help)\n") << command;
  }
}

// Animation is held to the still pose's rules: keys that point the camera down its up vector or
// carry geometry past ±1e6 m are refused at load with the time and the still check's words, and
// a sequence checks every frame's time before its first frame (here the camera passes straight
// above its target between two keys that are fine): nothing is written.
TEST(MotionCli, AnimationThatLeavesTheStillPosesBoundsIsRefusedBeforeAnyFrame) {
  const std::string bad = std::string(PENUMBRA_TEST_DATA) + "/bad/";
  struct Case {
    std::string file, message;
  };
  for (const Case& c : std::vector<Case>{
           {"scene_camera_animated_down.json", "at 1 s: camera: the view is along the up vector (0, 1, 0)"},
           {"scene_animated_scale_huge.json", "at 2 s: object 1: world-space coordinate -50000000 is not finite or beyond ±1000000 m"},
           {"gltf_animation_far.gltf", "at 1 s: nodes[0]: world-space coordinate 1e+30 is not finite or beyond ±1000000 m"},
       }) {
    const RunResult r = runPenumbra("render --size 16x16 --scene " + bad + c.file);
    EXPECT_EQ(r.exitCode, 1) << c.file;
    EXPECT_NE(r.err.find(c.file + ": " + c.message), std::string::npos) << r.err;
  }

  const std::string dir = freshDir("frames-checked");
  std::ofstream(dir + "/overhead.json") << R"({"camera": {"position": [-5, 9, 0], "target": [0, 0, 0],
    "animation": {"keys": [{"timeS": 0, "position": [-5, 9, 0]}, {"timeS": 2, "position": [5, 9, 0]}]}},
    "lights": [{"type": "sun"}], "objects": [{"shape": "plane"}, {"shape": "box"}]})";
  const std::string common = " --scene overhead.json --size 16x16 --shadow-map 1024";
  for (const std::string args : {"render --frames 3 --fps 1 --out f.png", "compare --frames 3 --fps 1 --samples 1 --out c", "render --time 1",
                                  "compare --time 1 --samples 1 --out c"}) {
    const RunResult r = runPenumbra(args + common, dir);
    EXPECT_EQ(r.exitCode, 1) << args;
    EXPECT_EQ(r.err, "penumbra: overhead.json: at 1 s: camera: the view is along the up vector (0, 1, 0): no direction is up in the image\n")
        << args;
  }
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir), std::filesystem::directory_iterator()), 3) << "nothing written";
  EXPECT_EQ(runPenumbra("render --frames 2 --fps 2 --out ok.png" + common, dir).exitCode, 0) << "0 s and 0.5 s are fine";
}

TEST(MotionCli, CompareFramesJsonHasTheTimeKeys) {
  const std::string dir = freshDir("compare-frames");
  const RunResult r = runPenumbra("compare --scene boxes --size 48x32 --shadow-map 1024 --samples 4 --frames 3 --fps 1 --json --out imgs", dir);
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
  const std::string common = "render --scene boxes --size 48x32 --shadow-map 1024 --frames 3 --fps 1 --verbose";
  RunResult r = runPenumbra(common + " --map-updates invalid --out cached.png", dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.err.find("cached maps: 0 restored, 3 drawn, 0 kept (--map-updates invalid); staleness max 0"), std::string::npos) << r.err;
  r = runPenumbra(common + " --map-updates 1 --out budget.png", dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.err.find("3 drawn, 0 kept (--map-updates budget 1); staleness max 0"), std::string::npos) << r.err;
  // A still sun over a rolling ball (tests/data/scenes/rolling-ball.json): the map's static
  // casters are restored in every frame after the first.
  r = runPenumbra("render --scene '" PENUMBRA_TEST_DATA "/scenes/rolling-ball.json' --size 48x32 --shadow-map 1024 --frames 3 --verbose "
                  "--map-updates invalid --out ball.png",
                  dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.err.find("cached maps: 2 restored, 1 drawn, 0 kept"), std::string::npos) << r.err;
  for (const char* bad : {"0", "sometimes", "2x", "1000001", "99999999999"}) {
    r = runPenumbra(common + " --map-updates " + bad + " --out bad.png", dir);
    EXPECT_EQ(r.exitCode, 2) << bad;
    EXPECT_NE(r.err.find("expected every, invalid or a number of maps per frame in [1, 1000000]"), std::string::npos) << r.err;
  }
}

// compare --map-updates N: the JSON names the policy and what it did over every frame rendered
// (the warm-up and timed still frames, then the sequence): csm's 4 cascades, 2 updated a frame
// after the first, 2 kept, none older than 1 frame.
TEST(MotionCli, CompareReportsTheMapBudgetsStaleness) {
  const std::string dir = freshDir("compare-budget");
  const RunResult r = runPenumbra("compare --scene boxes --projection csm --size 48x32 --shadow-map 1024 --samples 4 --frames 3 --fps 1 "
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
  const RunResult r = runPenumbra("compare --scene '" PENUMBRA_TEST_DATA "/scenes/two-suns.json' --projection csm --size 48x32 --shadow-map 1024 --samples 4 --frames 3 "
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
