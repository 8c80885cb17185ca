// `penumbra view` under Xvfb: a script generated from the registry at run time switches through
// every filter and every projection, takes a screenshot of the 3D view after each, and the
// screenshots are checked here (not blank; different filters give different pictures). A second
// script switches techniques, and the filter options that make GL objects (pcf.hardwareCompare's
// sampler, ...), for 1000 frames and the live GL object count must not grow.
// Skipped, saying why, only where xvfb-run is missing (scripts/install-deps installs it).
#include "CliSupport.h"

#include "viewer/DebugDisplay.h"

#include <penumbra/ImageIO.h>
#include "techniques/Registry.h"
#include <penumbra/SceneIO.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>
#include <sys/wait.h>
#include <unistd.h>

using namespace penumbra;
using namespace penumbra::test;

namespace {

// Not blank: at least this many distinct grey levels, and this standard deviation (0..255).
constexpr int kMinGreyLevels = 24;
constexpr double kMinGreyStdDev = 8.0;
// Two pictures differ when at least this share of pixels differs by more than kPixelDeltaLevels
// in some channel. The same technique renders the same picture (0 pixels); every filter pair on
// `pen` with a 256² map differs in ≥ 0.05% of the view (69 pixels of 102 400 for vsm vs msm, the
// closest pair: over pen's single occluder Chebyshev's bound is already exact, so four moments
// change only the pencil's outline). One pair is exempt: hard vs second-depth, the same depth
// test against the nearest and the second-nearest surface. Under hard's default bias (the
// receiver's own plane at each texel, identicalWhenExact) both are exact on pen and differ in
// 0.01 % of the pixels, as they should.
constexpr int kPixelDeltaLevels = 8;
constexpr double kMinDifferingShare = 0.0003;
bool identicalWhenExact(const std::string& a, const std::string& b) {
  return (a == "hard" && b == "second-depth") || (a == "second-depth" && b == "hard");
}

bool haveXvfb() { return std::system("command -v xvfb-run > /dev/null 2>&1") == 0; }

#define SKIP_WITHOUT_XVFB()                                                                              \
  if (!haveXvfb()) GTEST_SKIP() << "xvfb-run is not installed, so the viewer cannot open a window here: " \
                                   "install the xvfb and xauth packages (scripts/install-deps)"

/// What runs `penumbra view` in a virtual X server, started in `dir`.
std::string viewerLauncher(const std::string& dir) {
  // -a takes the first free display from -n on; starting from a number that depends on the
  // process keeps tests that CTest runs in parallel from racing for the same one.
  const int firstDisplay = 100 + static_cast<int>(getpid() % 800);
  // The X authority file lives in the test's own folder (-f), so xvfb-run makes no temporary
  // folder of its own: removing that folder at exit once failed during a parallel test run, and
  // xvfb-run then exits 5 whatever the viewer returned.
  static int runs = 0;
  const std::string auth = dir + "/.Xauthority-" + std::to_string(runs++);
  { std::ofstream touch(auth); }  // xauth adds to an existing file without a warning
  return "xvfb-run -a -n " + std::to_string(firstDisplay) + " -f '" + auth + "' -s '-screen 0 1280x1024x24'";
}

/// Runs `penumbra view <args>` in a virtual X server.
RunResult runViewer(const std::string& args, const std::string& dir) { return runPenumbra("view " + args, dir, viewerLauncher(dir)); }

void writeScript(const std::string& path, const std::string& text) {
  std::ofstream(path) << text;
}

struct Grey {
  int levels = 0;
  double stdDev = 0.0;
  double mean = 0.0;
};

Grey greyStats(const std::vector<uint8_t>& rgba) {
  std::vector<bool> seen(256, false);
  double sum = 0.0, sum2 = 0.0;
  const size_t n = rgba.size() / 4;
  for (size_t i = 0; i < n; ++i) {
    const int g = (rgba[i * 4] + rgba[i * 4 + 1] + rgba[i * 4 + 2]) / 3;
    seen[static_cast<size_t>(g)] = true;
    sum += g;
    sum2 += double(g) * g;
  }
  const double mean = sum / double(n);
  return {static_cast<int>(std::count(seen.begin(), seen.end(), true)), std::sqrt(std::max(0.0, sum2 / double(n) - mean * mean)),
          mean};
}

double differingShare(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b) {
  size_t differ = 0;
  for (size_t i = 0; i + 3 < a.size(); i += 4)
    for (size_t c = 0; c < 3; ++c)
      if (std::abs(int(a[i + c]) - int(b[i + c])) > kPixelDeltaLevels) {
        ++differ;
        break;
      }
  return double(differ) / double(a.size() / 4);
}

// Bytes that differ between the viewer's screenshot `viewPng` and `penumbra render`'s `renderPng`
// (both in `dir`); fails the test if the sizes differ.
size_t differingBytes(const std::string& dir, const std::string& viewPng, const std::string& renderPng) {
  int w = 0, h = 0, w2 = 0, h2 = 0;
  const auto view = readPng(dir + "/" + viewPng, w, h);
  const auto render = readPng(dir + "/" + renderPng, w2, h2);
  EXPECT_EQ(w, w2);
  EXPECT_EQ(h, h2);
  if (view.size() != render.size()) return view.size() + render.size();
  size_t differing = 0;
  for (size_t i = 0; i < view.size(); ++i) differing += view[i] != render[i];
  return differing;
}

std::vector<int> glObjectCounts(const std::string& out) {
  std::vector<int> counts;
  std::istringstream in(out);
  for (std::string line; std::getline(in, line);)
    if (line.rfind("gl-objects ", 0) == 0) counts.push_back(std::stoi(line.substr(11)));
  return counts;
}

}  // namespace

TEST(ViewerCli, ScreenshotsOfEveryFilterAndProjectionAreNotBlankAndFiltersDiffer) {
  SKIP_WITHOUT_XVFB();
  const std::string dir = freshDir("viewer-techniques");
  // pen: a spot light of radius 0.12 m over a leaning pencil, so hard, filtered and soft
  // shadows must all look different; a coarse 256² map also separates the hard depth tests
  // (biased or not). Projections are switched under the baseline filter.
  // The light's own map size: the command line's --shadow-map starts at 1024².
  std::string script = "scene pen\nlight set 0 mapSize 256\n";
  for (const std::string& f : filterIds()) script += "filter " + f + "\nscreenshot filter-" + f + ".png\n";
  script += "filter hard\n";
  for (const std::string& p : projectionIds()) script += "projection " + p + "\nscreenshot projection-" + p + ".png\n";
  writeScript(dir + "/techniques.txt", script);
  const RunResult r = runViewer("--size 640x320 --shadow-map 1024 --script techniques.txt", dir);
  ASSERT_EQ(r.exitCode, 0) << r.err << r.out;

  // A refused pair keeps the previous technique: its picture proves nothing, so say which.
  std::map<std::string, std::string> refused;
  const std::regex refusedLine("refused (filter|projection)=(\\S+): (.*)");
  std::istringstream lines(r.out);
  for (std::string line; std::getline(lines, line);)
    if (std::smatch m; std::regex_match(line, m, refusedLine)) refused[m[1].str() + "-" + m[2].str()] = m[3];

  std::map<std::string, std::vector<uint8_t>> filters;
  auto check = [&](const std::string& name) -> std::vector<uint8_t> {
    int w = 0, h = 0;
    std::vector<uint8_t> rgba = readPng(dir + "/" + name + ".png", w, h);
    EXPECT_EQ(w, 320) << name;  // the 3D view: the window less the panels (half of 640)
    EXPECT_EQ(h, 320) << name;
    const Grey g = greyStats(rgba);
    EXPECT_GE(g.levels, kMinGreyLevels) << name << " looks blank";
    EXPECT_GE(g.stdDev, kMinGreyStdDev) << name << " looks blank";
    return rgba;
  };
  for (const std::string& f : filterIds()) {
    std::vector<uint8_t> img = check("filter-" + f);
    if (refused.count("filter-" + f)) ADD_FAILURE() << "filter " << f << " was refused on pen/uniform: " << refused["filter-" + f];
    else filters[f] = std::move(img);
  }
  const Light penLight = makeBuiltinScene("pen").light();
  for (const std::string& p : projectionIds()) {
    check("projection-" + p);
    // A projection that cannot shadow pen's spot light is refused, with its reason.
    if (projectionIncompatibility(p, penLight).empty())
      EXPECT_FALSE(refused.count("projection-" + p)) << "projection " << p << " refused: " << refused["projection-" + p];
    else
      EXPECT_TRUE(refused.count("projection-" + p)) << "projection " << p << " cannot shadow a spot light, yet was not refused";
  }
  for (auto a = filters.begin(); a != filters.end(); ++a)
    for (auto b = std::next(a); b != filters.end(); ++b) {
      const double share = differingShare(a->second, b->second);
      if (!identicalWhenExact(a->first, b->first)) {
        EXPECT_GE(share, kMinDifferingShare) << "filters " << a->first << " and " << b->first << " give the same picture";
      }
      std::printf("differing pixels %-12s vs %-12s %6.2f%%\n", a->first.c_str(), b->first.c_str(), 100.0 * share);
    }
}

TEST(ViewerCli, NoGlObjectGrowthOver1000FramesOfTechniqueSwitching) {
  SKIP_WITHOUT_XVFB();
  const std::string dir = freshDir("viewer-objects");
  // One frame per technique pair: the first cycle creates every program the later ones use
  // (the shader cache keeps programs for the whole run, by design).
  // The virtual projection refuses most filters (the prefiltered ones cannot read pages): its
  // pairs would mostly be refused, not shown.
  std::vector<std::pair<std::string, std::string>> pairs;
  for (const std::string& p : projectionIds())
    if (p != "virtual")
      for (const std::string& f : filterIds()) pairs.emplace_back(p, f);
  // Options with which a filter makes GL objects of its own (the hardware comparison sampler,
  // SAT vs mip textures, another storage format, other program variants). Each filter's value
  // follows the projection it is shown with, so every cycle goes through every value and the
  // script repeats exactly from one cycle to the next. sdf.resolution rebakes the field: too slow.
  const std::map<std::string, std::vector<std::string>> kObjectOptions = {
      {"pcf", {"pcf.hardwareCompare=on", "pcf.hardwareCompare=off"}},
      {"pcss", {"pcss.hardwareCompare=on", "pcss.hardwareCompare=off"}},
      {"vssm", {"vssm.source=mip", "vssm.source=sat"}},
      {"msm", {"msm.storage=quantized16", "msm.storage=float32"}},
  };
  const size_t filterCount = filterIds().size();
  auto step = [&](size_t i) {
    const auto& [p, f] = pairs[i % pairs.size()];
    std::string text = "projection " + p + "\nfilter " + f + "\n";
    if (auto it = kObjectOptions.find(f); it != kObjectOptions.end()) {
      const size_t projectionIndex = (i % pairs.size()) / filterCount;
      text += "set " + it->second[projectionIndex % it->second.size()] + "\n";
    }
    return text + "wait 1\n";
  };
  // At least 1000 frames after the first cycle, in whole cycles. The first cycle fills the shader
  // cache, so the count after it is compared with the count after the last one (the same
  // technique shown), and the count after every frame of the second cycle with the count after
  // the same frame of the last: every technique and option owns as many objects as it did then.
  constexpr size_t kMinFrames = 1000;
  const size_t kFrames = (kMinFrames + pairs.size() - 1) / pairs.size() * pairs.size();
  std::string script = "scene pen\ninset visibility\n";
  for (size_t i = 0; i < pairs.size(); ++i) script += step(i);
  script += "print gl-objects\n";
  for (size_t i = 0; i < kFrames; ++i)
    script += step(i) + (i < pairs.size() || i + pairs.size() >= kFrames ? "print gl-objects\n" : "");
  writeScript(dir + "/switch.txt", script);
  const auto start = std::chrono::steady_clock::now();
  const RunResult r = runViewer("--size 160x120 --shadow-map 1024 --script switch.txt", dir);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_EQ(r.out.find("refused"), std::string::npos) << "a refused pair skips its options: " << r.out;
  const std::vector<int> counts = glObjectCounts(r.out);
  ASSERT_EQ(counts.size(), 1 + 2 * pairs.size()) << r.out;
  EXPECT_GT(counts[0], 0);
  EXPECT_EQ(counts.back(), counts[0]) << "live GL objects after the first cycle vs after " << kFrames << " more frames";
  const int* second = &counts[1];
  const int* last = &counts[1 + pairs.size()];
  for (size_t i = 0; i < pairs.size(); ++i)
    EXPECT_EQ(last[i], second[i]) << "live GL objects with " << pairs[i].first << "/" << pairs[i].second
                                  << " in the second cycle vs the last";
  std::string perPair;
  for (size_t i = 0; i < pairs.size(); ++i) perPair += " " + pairs[i].first + "/" + pairs[i].second + "=" + std::to_string(last[i]);
  std::printf("gl objects per pair:%s\n", perPair.c_str());
  std::printf("gl objects after the first cycle %d, after %zu more frames %d (%zu technique pairs, %.1f s)\n", counts[0],
              kFrames, counts.back(), pairs.size(), seconds);
}

TEST(ViewerCli, ScriptMistakesAreUsageErrorsNamingTheLine) {
  // The script is checked before a window opens: no X server needed.
  const std::string dir = freshDir("viewer-script-errors");
  writeScript(dir + "/bad.txt", "scene pen\nwait two\n");
  RunResult r = runPenumbra("view --script bad.txt", dir);
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_NE(r.err.find("bad.txt:2"), std::string::npos) << r.err;
  writeScript(dir + "/bad2.txt", "\n# fine\nzoom 3\n");
  r = runPenumbra("view --script bad2.txt", dir);
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_NE(r.err.find("bad2.txt:3: unknown action 'zoom'"), std::string::npos) << r.err;
  r = runPenumbra("view --script no-such-file.txt", dir);
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_NE(r.err.find("no-such-file.txt"), std::string::npos) << r.err;
}

TEST(ViewerCli, UnknownFilterInAScriptStopsWithExit2) {
  SKIP_WITHOUT_XVFB();
  const std::string dir = freshDir("viewer-unknown");
  writeScript(dir + "/s.txt", "filter blurry\n");
  const RunResult r = runViewer("--size 160x120 --shadow-map 1024 --script s.txt", dir);
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_NE(r.err.find("s.txt:1"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("blurry"), std::string::npos) << r.err;
}

// room has a point lamp and a spot: the reference view is lit by both lights' V_ref (the heatmap
// and its numbers are the first light's), so it looks like the technique's frame.
TEST(ViewerCli, HeatmapAndReferenceViewOfASceneWithTwoLights) {
  SKIP_WITHOUT_XVFB();
  const std::string dir = freshDir("viewer-heatmap-lights");
  writeScript(dir + "/s.txt", "scene room\nheatmap 16\nwait-heatmap\nview shaded\nflip\nwait 1\nscreenshot reference.png\n"
                              "flip\nwait 1\nscreenshot technique.png\n");
  const RunResult r = runViewer("--size 160x120 --shadow-map 1024 --filter pcss --script s.txt", dir);
  ASSERT_EQ(r.exitCode, 0) << r.err << r.out;
  EXPECT_NE(r.out.find("heatmap: RMSE"), std::string::npos) << r.out;
  int w = 0, h = 0;
  const Grey reference = greyStats(readPng(dir + "/reference.png", w, h));
  const Grey technique = greyStats(readPng(dir + "/technique.png", w, h));
  std::printf("mean grey: reference %.2f, technique %.2f\n", reference.mean, technique.mean);
  EXPECT_NEAR(reference.mean, technique.mean, 0.05 * technique.mean);
}

TEST(ViewerCli, DebugViewsHeatmapAndSavedSettings) {
  SKIP_WITHOUT_XVFB();
  const std::string dir = freshDir("viewer-views");
  writeScript(dir + "/s.txt",
              "scene pen\nset light.size=0.2\nscreenshot shaded.png\nview shadow-map\nscreenshot map.png\n"
              "view visibility\nscreenshot visibility.png\nview shaded\nheatmap 4\nwait-heatmap\nscreenshot heatmap.png\n"
              "save saved.json\nscreenshot-window window.png\nview texel-density\nscreenshot density.png\n"
              "projection csm\nview cascades\nscreenshot cascades.png\n");
  const RunResult r = runViewer("--size 480x240 --shadow-map 1024 --filter pcss --script s.txt", dir);
  ASSERT_EQ(r.exitCode, 0) << r.err << r.out;
  EXPECT_NE(r.out.find("heatmap: RMSE"), std::string::npos) << r.out;
  int w = 0, h = 0;
  const auto shaded = readPng(dir + "/shaded.png", w, h);
  for (const char* name : {"map", "visibility", "heatmap", "density", "cascades"}) {
    const auto img = readPng(dir + "/" + name + ".png", w, h);
    EXPECT_GE(greyStats(img).stdDev, kMinGreyStdDev) << name << " looks blank";
    EXPECT_GE(differingShare(shaded, img), kMinDifferingShare) << name << " looks like the shaded view";
  }
  readPng(dir + "/window.png", w, h);
  EXPECT_EQ(w, 480);
  EXPECT_EQ(h, 240);
  // The saved settings render as a scene of their own, with the technique and light size kept.
  const RunResult render = runPenumbra("render --scene saved.json --size 64x32 --shadow-map 1024 --out again.png", dir);
  EXPECT_EQ(render.exitCode, 0) << render.err;
  EXPECT_NE(render.out.find("--filter pcss"), std::string::npos) << render.out;
  std::ifstream saved(dir + "/saved.json");
  const std::string text((std::istreambuf_iterator<char>(saved)), {});
  EXPECT_NE(text.find("\"size\": 0.2"), std::string::npos) << text;
}

TEST(ViewerCli, ThreeDViewShowsExactlyWhatRenderWrites) {
  SKIP_WITHOUT_XVFB();
  // With the panels hidden the view is the whole window: the display pass must pass the colour
  // output through unchanged (no filtering, no gamma, no flip).
  const std::string dir = freshDir("viewer-exact");
  writeScript(dir + "/s.txt", "screenshot view.png\n");
  const std::string technique = "--scene pen --filter pcf --size 320x200 --shadow-map 1024";
  const RunResult v = runViewer(technique + " --hide-ui --script s.txt", dir);
  ASSERT_EQ(v.exitCode, 0) << v.err;
  const RunResult r = runPenumbra("render " + technique + " --out render.png", dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_EQ(differingBytes(dir, "view.png", "render.png"), 0u)
      << "bytes that differ between the viewer's screenshot and penumbra render";
}

// A view found in the viewer is the same image from `penumbra render`: the screenshot's status
// line carries the camera as a --camera argument.
TEST(ViewerCli, ScreenshotCameraRendersTheSameImage) {
  SKIP_WITHOUT_XVFB();
  const std::string dir = freshDir("viewer-camera");
  writeScript(dir + "/s.txt", "camera orbit 40 25 3\nscreenshot view.png\n");
  const std::string technique = "--scene pen --filter pcf --size 320x200 --shadow-map 1024";
  const RunResult v = runViewer(technique + " --hide-ui --script s.txt", dir);
  ASSERT_EQ(v.exitCode, 0) << v.err;
  const size_t at = v.out.find("--camera ");
  ASSERT_NE(at, std::string::npos) << v.out;
  const std::string camera = v.out.substr(at, v.out.find_first_of(" \n", at + 9) - at);
  const RunResult r = runPenumbra("render " + technique + " " + camera + " --out render.png", dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_EQ(differingBytes(dir, "view.png", "render.png"), 0u) << camera;
  const RunResult own = runPenumbra("render " + technique + " --out own.png", dir);
  ASSERT_EQ(own.exitCode, 0) << own.err;
  EXPECT_GT(differingBytes(dir, "view.png", "own.png"), 1000u) << "the orbit did not move the camera";
}

// Time: `time T` poses the scene as `render --time T` does (the rolling ball on boxes; city's
// walking camera, which the view follows), and `play` moves the time on by 1/30 s per scripted
// frame at the speed asked.
TEST(ViewerCli, TimePosesTheSceneAsRenderDoes) {
  SKIP_WITHOUT_XVFB();
  const std::string dir = freshDir("viewer-time");
  writeScript(dir + "/s.txt",
              "time 2\nscreenshot boxes.png\nplay 2\nwait 15\npause\nprint time\n"
              "scene city\ntime 4\nscreenshot city.png\nprint time\n");
  const std::string technique = "--projection uniform --filter pcf --size 320x200 --shadow-map 1024";
  const RunResult v = runViewer("--scene boxes " + technique + " --hide-ui --script s.txt", dir);
  ASSERT_EQ(v.exitCode, 0) << v.err;
  const std::smatch m = [&] {
    std::smatch match;
    std::regex_search(v.out, match, std::regex(R"(time ([0-9.]+) of 4\.000 s paused)"));
    return match;
  }();
  ASSERT_FALSE(m.empty()) << v.out;
  // 15 frames of 1/30 s at 2x: 1 s on from 2 s (a frame either way: where the actions fall).
  EXPECT_NEAR(std::stod(m[1].str()), 3.0, 2.0 * 2.0 / 30.0 + 1e-3) << v.out;
  EXPECT_NE(v.out.find("time 4.000 of 4.000 s paused"), std::string::npos) << v.out;
  for (const auto& [scene, time] : {std::pair<std::string, std::string>{"boxes", "2"}, {"city", "4"}}) {
    const RunResult r = runPenumbra("render --scene " + scene + " " + technique + " --time " + time + " --out r-" + scene + ".png", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(differingBytes(dir, scene + ".png", "r-" + scene + ".png"), 0u) << scene << " at " << time << " s";
    const RunResult still = runPenumbra("render --scene " + scene + " " + technique + " --out s-" + scene + ".png", dir);
    ASSERT_EQ(still.exitCode, 0) << still.err;
    EXPECT_GT(differingBytes(dir, scene + ".png", "s-" + scene + ".png"), 100u) << scene << ": nothing moved";
  }
}

namespace {

// A room lit by a spot (light 0) and a point lamp (light 1) with something in every direction of
// the lamp, so that each of its six cube faces sees depth that varies across the face. A face's
// map holds depth along its axis, so a plane square to that axis would look flat: the ceiling
// slopes, and the floor casts no shadow (the -Y face sees the objects' tops).
constexpr const char* kTwoLightRoom = R"({"name": "two-lights", "shadow": {"mapSize": 256},
  "camera": {"position": [0, 2.2, 4.5], "target": [0, 0.8, 0]},
  "lights": [
    {"type": "spot", "position": [2, 2.6, 2], "target": [0, 0, 0], "outerConeDeg": 40, "innerConeDeg": 30,
     "size": 0.05, "intensity": 20},
    {"type": "point", "position": [0, 1.2, 0], "size": 0.03, "range": 12, "intensity": 6}],
  "objects": [
    {"name": "floor", "shape": "plane", "size": [8, 8], "castsShadow": false},
    {"name": "ceiling", "shape": "box", "size": [8, 0.1, 8], "translate": [0, 3, 0], "rotateDeg": [0, 0, 10]},
    {"name": "box", "shape": "box", "size": [0.6, 1.0, 0.6], "translate": [1.6, 0.5, 0], "rotateDeg": [0, 30, 0]},
    {"name": "ball", "shape": "sphere", "radius": 0.4, "translate": [-1.5, 0.6, 0.3]},
    {"name": "post", "shape": "cylinder", "radius": 0.2, "height": 1.8, "translate": [0.4, 0, 1.4]},
    {"name": "cone", "shape": "cone", "radius": 0.5, "height": 1.4, "translate": [-0.3, 0, -1.6]}]})";

// A cell's grey statistics, a few pixels inside its edges (labels and letterbox bars aside).
constexpr int kCellInsetPx = 4;
// A face shows its scene when it has at least this many grey levels and this deviation (0..255).
constexpr int kMinFaceGreyLevels = 8;
constexpr double kMinFaceStdDev = 4.0;

std::vector<uint8_t> cellPixels(const std::vector<uint8_t>& rgba, int width, int height, const glm::ivec4& cell) {
  std::vector<uint8_t> out;
  const int top = height - (cell.y + cell.w);  // window y grows upward, PNG rows downward
  for (int y = top + kCellInsetPx; y < top + cell.w - kCellInsetPx; ++y)
    for (int x = cell.x + kCellInsetPx; x < cell.x + cell.z - kCellInsetPx; ++x)
      if (x >= 0 && x < width && y >= 0 && y < height)
        out.insert(out.end(), rgba.begin() + (size_t(y) * size_t(width) + size_t(x)) * 4,
                   rgba.begin() + (size_t(y) * size_t(width) + size_t(x)) * 4 + 4);
  return out;
}

}  // namespace

// The light list in a script: a scene of a spot and a point lamp, the lamp selected, its shadow
// map shown as six cube faces; each face must show depth, not a flat colour, and the faces must
// differ from each other. Then lights are added, edited and removed, and mistakes name the light.
TEST(ViewerCli, SelectedPointLightShowsItsSixCubeFaces) {
  SKIP_WITHOUT_XVFB();
  const std::string dir = freshDir("viewer-lights");
  std::ofstream(dir + "/room.json") << kTwoLightRoom;
  writeScript(dir + "/s.txt",
              "print lights\nlight select 1\nprint lights\nview shadow-map\nscreenshot faces.png\n"
              "screenshot-window faces-window.png\nview shaded\nlight add sun\nlight set 2 castsShadow off\n"
              "light set 1 position 0.2 1.3 0\nlight set 0 mapSize 256\nprint lights\nlight remove 0\nprint lights\n"
              "screenshot after.png\nsave saved.json\n");
  constexpr int kMapSize = 256;  // the scene file's own (the command line's --shadow-map starts at 1024²)
  const RunResult r = runViewer("--scene room.json --size 800x400 --script s.txt", dir);
  ASSERT_EQ(r.exitCode, 0) << r.err << r.out;
  EXPECT_NE(r.out.find("lights 2 selected 0: 0=spot 1=point\n"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("lights 2 selected 1: 0=spot 1=point\n"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("lights 3 selected 2: 0=spot 1=point 2=sun\n"), std::string::npos) << r.out;
  // Removing light 0 keeps the sun selected, now light 1.
  EXPECT_NE(r.out.find("lights 2 selected 1: 0=point 1=sun\n"), std::string::npos) << r.out;

  int w = 0, h = 0;
  const std::vector<uint8_t> faces = readPng(dir + "/faces.png", w, h);
  ASSERT_GT(w, 200);  // the view: the window less the panels
  const std::vector<glm::ivec4> cells = viewer::layerCells({0, 0, w, h}, kMapSize, kMapSize, 6);
  ASSERT_EQ(cells.size(), 6u);
  std::vector<std::vector<uint8_t>> faceImages;
  for (size_t i = 0; i < cells.size(); ++i) {
    faceImages.push_back(cellPixels(faces, w, h, cells[i]));
    const Grey g = greyStats(faceImages.back());
    std::printf("face %zu at %d,%d %dx%d: %d grey levels, deviation %.1f\n", i, cells[i].x, cells[i].y, cells[i].z, cells[i].w,
                g.levels, g.stdDev);
    EXPECT_GE(g.levels, kMinFaceGreyLevels) << "cube face " << i << " looks flat";
    EXPECT_GE(g.stdDev, kMinFaceStdDev) << "cube face " << i << " looks flat";
  }
  for (size_t a = 0; a < faceImages.size(); ++a)
    for (size_t b = a + 1; b < faceImages.size(); ++b)
      EXPECT_GE(differingShare(faceImages[a], faceImages[b]), kMinDifferingShare) << "cube faces " << a << " and " << b << " look alike";

  // The saved scene holds the edits: the moved lamp, and the sun that casts no shadow.
  const Scene saved = loadSceneFile(dir + "/saved.json");
  ASSERT_EQ(saved.lights.size(), 2u);
  EXPECT_EQ(saved.lights[0].type, LightType::Point);
  EXPECT_NEAR(glm::length(saved.lights[0].position - glm::vec3(0.2f, 1.3f, 0.0f)), 0.0f, 1e-5f);
  EXPECT_EQ(saved.lights[1].type, LightType::Directional);
  EXPECT_FALSE(saved.lights[1].castsShadow);

  // Mistakes that only the scene can reveal stop the script with the line and the light.
  writeScript(dir + "/bad.txt", "light select 1\nlight select 5\n");
  RunResult bad = runViewer("--scene room.json --size 160x120 --shadow-map 1024 --script bad.txt", dir);
  EXPECT_EQ(bad.exitCode, 2);
  EXPECT_NE(bad.err.find("bad.txt:2: light: there is no light 5: the scene has 2 (0..1)"), std::string::npos) << bad.err;
  writeScript(dir + "/bad2.txt", "light set 1 direction 0 -1 0\n");
  bad = runViewer("--scene room.json --size 160x120 --shadow-map 1024 --script bad2.txt", dir);
  EXPECT_EQ(bad.exitCode, 2);
  EXPECT_NE(bad.err.find("bad2.txt:1: light: direction: the light is a point"), std::string::npos) << bad.err;
}

// The viewer at 1280×720: each panel group (one tab each) fits without scrolling, with the
// technique that has the most parameters (csm × evsm-soft, and every other filter on csm) and
// the Lights tab with the most widgets (six lights listed, a spot selected); the
// font has every glyph the labels, units and legends use ("Split λ", "texels²", "ΔV"); an
// inset survives a filter that lacks its image; the split view shows two techniques; R flips
// to the reference.
TEST(ViewerCli, At1280x720EveryPanelFitsAndTheViewsCompare) {
  SKIP_WITHOUT_XVFB();
  const std::string dir = freshDir("viewer-panels");
  std::string script = "scene city\nprojection csm\nfilter evsm-soft\ninset shadow-map\nwait 2\n";
  const std::vector<std::string> panels = {"technique", "filter", "lights", "camera", "views", "timings", "tools"};
  for (const std::string& p : panels) script += "panel " + p + "\nwait 2\nprint layout\nscreenshot-window panel-" + p + ".png\n";
  script += "panel filter\n";
  for (const std::string& f : filterIds()) script += "filter " + f + "\nwait 2\nprint layout\n";
  // sdf keeps no shadow-map: the inset waits for the next filter that has one.
  script += "filter sdf\nwait 1\nfilter pcss\nwait 1\nscreenshot plain.png\nsplit vsm\nwait 1\nscreenshot split.png\nsplit off\n"
            "heatmap 4\nwait-heatmap\nview shaded\nflip\nwait 1\nscreenshot reference.png\nflip\nwait 1\nscreenshot technique.png\n";
  // The Lights tab at its tallest: room (a point lamp and a spot) and four more spots, a spot
  // selected (cones and range: every widget the editor has).
  script += "projection uniform\nscene room\nlight add spot\nlight add spot\nlight add spot\nlight add spot\nlight select 1\n"
            "panel lights\nwait 2\nprint lights\nprint layout\nscreenshot-window panel-lights-room.png\n";
  writeScript(dir + "/s.txt", script);
  const RunResult r = runViewer("--size 1280x720 --shadow-map 1024 --script s.txt", dir);
  ASSERT_EQ(r.exitCode, 0) << r.err << r.out;

  const std::regex layout("layout panel=(\\S+) content-bottom=(\\d+) window-height=(\\d+) scroll-max=(\\d+) font=\"([^\"]*)\" "
                          "missing-glyphs=(\\d+)(.*)");
  std::istringstream lines(r.out);
  size_t layouts = 0;
  for (std::string line; std::getline(lines, line);) {
    std::smatch m;
    if (!std::regex_match(line, m, layout)) continue;
    ++layouts;
    EXPECT_EQ(m[3].str(), "720") << line;
    EXPECT_LE(std::stoi(m[2].str()), 720) << "the panel's content runs past the window: " << line;
    EXPECT_EQ(m[4].str(), "0") << "the panel scrolls: " << line;
    EXPECT_EQ(m[6].str(), "0") << "glyphs the labels use are missing from the font:" << m[7].str();
    EXPECT_NE(m[5].str().find("DejaVu"), std::string::npos) << line;
  }
  EXPECT_EQ(layouts, panels.size() + filterIds().size() + 1) << r.out;
  EXPECT_NE(r.out.find("lights 6 selected 1: 0=point 1=spot 2=spot 3=spot 4=spot 5=spot\n"), std::string::npos) << r.out;

  // Every panel is on screen: the sidebar (left of the 3D view) differs from panel to panel and
  // carries text.
  std::map<std::string, std::vector<uint8_t>> sidebars;
  constexpr int kSidebarPx = 300;  // inside the sidebar whatever its exact width
  for (const std::string& p : panels) {
    int w = 0, h = 0;
    const std::vector<uint8_t> rgba = readPng(dir + "/panel-" + p + ".png", w, h);
    ASSERT_EQ(w, 1280);
    ASSERT_EQ(h, 720);
    std::vector<uint8_t>& side = sidebars[p];
    for (int y = 0; y < h; ++y)
      side.insert(side.end(), rgba.begin() + (static_cast<ptrdiff_t>(y) * w) * 4, rgba.begin() + (static_cast<ptrdiff_t>(y) * w + kSidebarPx) * 4);
    EXPECT_GE(greyStats(side).levels, kMinGreyLevels) << p << ": no text in the sidebar";
  }
  for (size_t a = 0; a < panels.size(); ++a)
    for (size_t b = a + 1; b < panels.size(); ++b)
      EXPECT_GE(differingShare(sidebars[panels[a]], sidebars[panels[b]]), 0.01) << panels[a] << " and " << panels[b] << " look alike";

  // Split: the left half is pcss as before, the right half another filter's picture.
  int w = 0, h = 0;
  const std::vector<uint8_t> plain = readPng(dir + "/plain.png", w, h), split = readPng(dir + "/split.png", w, h);
  auto half = [&](const std::vector<uint8_t>& img, bool right) {
    std::vector<uint8_t> out;
    for (int y = 0; y < h; ++y) {
      const ptrdiff_t x0 = right ? w / 2 + 2 : 0, x1 = right ? w : w / 2 - 2;  // off the divider
      out.insert(out.end(), img.begin() + (y * w + x0) * 4, img.begin() + (y * w + x1) * 4);
    }
    return out;
  };
  EXPECT_EQ(differingShare(half(plain, false), half(split, false)), 0.0) << "the left half is the technique itself";
  EXPECT_GE(differingShare(half(plain, true), half(split, true)), kMinDifferingShare) << "the right half shows vsm";
  // R: the same frame lit with V_ref, then back to the technique's own picture.
  const std::vector<uint8_t> reference = readPng(dir + "/reference.png", w, h), technique = readPng(dir + "/technique.png", w, h);
  EXPECT_GE(differingShare(reference, technique), kMinDifferingShare) << "the reference looks like the technique";
  EXPECT_EQ(differingShare(technique, plain), 0.0) << "flipping back shows the technique again";
}

// A technique folder's technique.json saved while the viewer runs (docs/viewer.md, "Hot
// reload"): the description is read again, its new parameter and its new default reach the
// technique and the picture; a broken save is reported naming the file and the field, and the
// last good description keeps running (the same picture). The test edits the file when the
// viewer's script prints its parameters, and the script's wait-reload waits for the reload.
TEST(ViewerCli, SavedTechniqueDescriptionIsReloadedAndABrokenOneKeepsTheLastGood) {
  SKIP_WITHOUT_XVFB();
  const std::string dir = freshDir("viewer-description-reload");
  std::filesystem::copy(std::string(PENUMBRA_TEST_DATA) + "/../../examples/techniques/pcf", dir + "/pcf");
  const std::filesystem::path file = std::filesystem::canonical(dir + "/pcf/technique.json");
  std::string original;
  {
    std::ifstream in(file);
    original.assign(std::istreambuf_iterator<char>(in), {});
  }
  const std::string radius = R"("unit": "texels", "default": 2, "range": [0, 32],)";
  ASSERT_NE(original.find(radius), std::string::npos) << "the pcf example's radius is not where the test edits it";
  // A new first parameter (the GLSL does not read it), a wider kernel by default, a map declared.
  const std::string wider = R"("unit": "texels", "default": 6, "range": [0, 32],)";
  std::string edited = original;
  edited.replace(edited.find(radius), radius.size(), wider);
  const std::string maps = R"("maps": ["depth"])";
  ASSERT_NE(edited.find(maps), std::string::npos);
  edited.replace(edited.find(maps), maps.size(), R"("maps": ["depth", "min-depth"])");
  edited.insert(edited.find("\"params\": [") + 11,
                R"({"name": "gain", "label": "Gain", "unit": "", "default": 1, "range": [0, 2], "meaning": "a parameter of the test"},)");
  std::string broken = edited;  // the radius's range upside down: params[2] now
  broken.replace(broken.find(wider), wider.size(), R"("unit": "texels", "default": 6, "range": [32, 0],)");
  auto save = [&](const std::string& text, int secondsAhead) {
    std::ofstream(file, std::ios::binary | std::ios::trunc) << text;
    // File times may be coarse: one that differs from the last for sure.
    std::filesystem::last_write_time(file, std::filesystem::file_time_type::clock::now() + std::chrono::seconds(secondsAhead));
  };

  writeScript(dir + "/s.txt",
              "panel filter\nscreenshot before.png\nprint params\nwait-reload\nscreenshot after.png\n"
              "screenshot-window panel.png\ninset min-depth\nscreenshot-inset min-depth.png\ninset none\nprint params\n"
              "wait-reload\nscreenshot kept.png\nprint params\n");
  const std::string command = "cd '" + dir + "' && " + viewerLauncher(dir) + " '" PENUMBRA_BINARY
                              "' view --filter ./pcf --scene pen --size 480x270 --shadow-map 1024 --script s.txt 2> err.txt < /dev/null";
  FILE* viewer = popen(command.c_str(), "r");
  ASSERT_NE(viewer, nullptr);
  std::string out;
  std::vector<std::string> params;
  char buffer[4096];
  while (std::fgets(buffer, sizeof(buffer), viewer)) {
    const std::string line = buffer;
    out += line;
    if (line.rfind("params ", 0) != 0) continue;
    params.push_back(line);
    if (params.size() == 1) save(edited, 2);
    if (params.size() == 2) save(broken, 4);
  }
  const int status = pclose(viewer);
  std::ifstream errIn(dir + "/err.txt");
  const std::string err((std::istreambuf_iterator<char>(errIn)), {});
  ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << err << out;
  ASSERT_EQ(params.size(), 3u) << out;

  EXPECT_NE(params[0].find(" pcf-folder.radiusTexels=2 "), std::string::npos) << params[0];
  EXPECT_EQ(params[0].find("pcf-folder.gain"), std::string::npos) << params[0];
  EXPECT_NE(params[1].find(" pcf-folder.gain=1 "), std::string::npos) << params[1];
  EXPECT_NE(params[1].find(" pcf-folder.radiusTexels=6 "), std::string::npos) << params[1];
  EXPECT_NE(out.find("reloaded " + file.string() + ": pcf-folder, 8 parameters; new: pcf-folder.gain"), std::string::npos) << out;
  // The broken save: the file and the field in the status line, the last good description kept.
  EXPECT_NE(err.find(file.string() + ": params[2].range: min 32 must be below max 0 (the last good description keeps running)"),
            std::string::npos)
      << err;
  EXPECT_EQ(params[2], params[1]);
  int w = 0, h = 0;
  const std::vector<uint8_t> before = readPng(dir + "/before.png", w, h), after = readPng(dir + "/after.png", w, h),
                             kept = readPng(dir + "/kept.png", w, h);
  EXPECT_GE(differingShare(before, after), kMinDifferingShare) << "a radius of 6 texels looks like one of 2";
  EXPECT_EQ(after, kept) << "the last good description no longer draws the same picture";
  // The declared map is built: the lights made their filters again from the new description.
  const std::vector<uint8_t> minDepth = readPng(dir + "/min-depth.png", w, h);
  EXPECT_GE(greyStats(minDepth).stdDev, kMinGreyStdDev) << "the min-depth map looks blank";
}
