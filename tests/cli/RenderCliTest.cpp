#include "CliSupport.h"

#include <penumbra/Exr.h>
#include <penumbra/ImageIO.h>

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>

using namespace penumbra;
using namespace penumbra::test;

namespace {
size_t countLines(const std::string& s) {
  size_t n = 0;
  for (char c : s) n += c == '\n';
  return n;
}
}  // namespace

TEST(RenderCli, NoArgumentsWritesANonBlankPng) {
  const std::string dir = freshDir("noargs");
  const RunResult r = runPenumbra("", dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  int w = 0, h = 0;
  const std::vector<uint8_t> rgba = readPng(dir + "/penumbra.png", w, h);
  EXPECT_EQ(w, 640);
  EXPECT_EQ(h, 360);
  // Non-blank: many distinct grey levels, and both shadowed and lit pixels.
  std::vector<bool> seen(256, false);
  for (size_t i = 0; i < rgba.size(); i += 4) seen[rgba[i + 1]] = true;
  EXPECT_GT(std::count(seen.begin(), seen.end(), true), 40);
  // No temporary file left behind.
  for (const auto& e : std::filesystem::directory_iterator(dir))
    EXPECT_EQ(e.path().filename().string().find(".tmp"), std::string::npos) << e.path();
}

TEST(RenderCli, MissingSceneFileExits1NamingIt) {
  const RunResult r = runPenumbra("render --scene /no/such/scene.json");
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_NE(r.err.find("/no/such/scene.json"), std::string::npos) << r.err;
  EXPECT_EQ(countLines(r.err), 1u) << r.err;
}

// The issue's reproduction: `printf 'v nan 0 0\n...' > t.obj; penumbra render --scene t.obj` exited 0.
TEST(RenderCli, ObjWithNanExits1NamingTheLine) {
  const std::string dir = freshDir("obj-nan");
  std::ofstream(dir + "/t.obj") << "v nan 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  const RunResult r = runPenumbra("render --scene t.obj --size 16x16", dir);
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_EQ(r.err, "penumbra: t.obj: line 1: v: 'nan' is not a finite number\n");
  EXPECT_FALSE(std::filesystem::exists(dir + "/penumbra.png"));
}

// A model's memory is estimated from its counts before anything is built: one that would take
// more than --max-memory (or the memory available) is refused, exit 1, with the estimate; the
// same model loads under a limit it fits. A size that does not parse is a usage error.
TEST(RenderCli, MaxMemoryRefusesAModelThatWouldNotFit) {
  const std::string dir = freshDir("max-memory");
  {
    std::ofstream obj(dir + "/grid.obj");
    constexpr int kGrid = 100;  // 20 000 triangles: about 0.7 MiB of meshes and GL buffers
    for (int i = 0; i <= kGrid; ++i)
      for (int j = 0; j <= kGrid; ++j) obj << "v " << i << " " << (i * j) % 3 << " " << j << "\n";
    for (int i = 0; i < kGrid; ++i)
      for (int j = 0; j < kGrid; ++j) {
        const int a = i * (kGrid + 1) + j + 1;
        obj << "f " << a << " " << a + kGrid + 1 << " " << a + kGrid + 2 << " " << a + 1 << "\n";
      }
  }
  const RunResult refused = runPenumbra("render --scene grid.obj --size 16x16 --max-memory 256K", dir);
  EXPECT_EQ(refused.exitCode, 1);
  EXPECT_NE(refused.err.find("penumbra: grid.obj: 20000 triangles and about 10201 vertices need about"), std::string::npos)
      << refused.err;
  EXPECT_NE(refused.err.find("more than the --max-memory limit of 256 KiB (this machine has "), std::string::npos) << refused.err;
  EXPECT_FALSE(std::filesystem::exists(dir + "/penumbra.png"));
  EXPECT_EQ(runPenumbra("render --scene grid.obj --size 16x16 --shadow-map 1024 --max-memory 2M", dir).exitCode, 0);
  const RunResult bad = runPenumbra("render --scene grid.obj --max-memory lots", dir);
  EXPECT_EQ(bad.exitCode, 2);
  EXPECT_NE(bad.err.find("--max-memory: 'lots' is not a size"), std::string::npos) << bad.err;
}

// A scene file's shadow.filter or shadow.params that the registry refuses is bad input in that
// file (exit 1 naming file and field, as docs/scenes.md says), not a bad command line (exit 2).
TEST(RenderCli, SceneFileTechniqueErrorsExit1NamingFileAndField) {
  const std::string bad = std::string(PENUMBRA_TEST_DATA) + "/bad/";
  RunResult r = runPenumbra("render --size 16x16 --scene " + bad + "scene_bad_filter.json");
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_NE(r.err.find("scene_bad_filter.json: shadow.filter: unknown filter 'blurry'"), std::string::npos) << r.err;
  r = runPenumbra("render --size 16x16 --scene " + bad + "scene_param_out_of_range.json");
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_NE(r.err.find("scene_param_out_of_range.json: shadow.params.hard.slopeBias: "), std::string::npos) << r.err;
  // The same mistakes on the command line stay usage errors.
  EXPECT_EQ(runPenumbra("render --size 16x16 --set hard.slopeBias=99").exitCode, 2);
}

// `--scene DIR` printed a libstdc++ text without the file.
TEST(RenderCli, SceneThatIsAFolderIsNamed) {
  const std::string dir = freshDir("scene-folder");
  std::filesystem::create_directories(dir + "/models.json");
  const RunResult r = runPenumbra("render --size 16x16 --scene models.json", dir);
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_EQ(r.err, "penumbra: models.json: is a folder, not a scene or model file\n");
}

// Messages quote what files hold; a terminal escape or a newline in a glTF string reached the
// terminal as it was.
TEST(RenderCli, MessagesCarryNoControlCharacters) {
  const RunResult r = runPenumbra("render --size 16x16 --scene " + std::string(PENUMBRA_TEST_DATA) + "/bad/control_chars.gltf");
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_NE(r.err.find("alphaMode: '\\x1b[2J\\x0aOPAQUE' is not OPAQUE"), std::string::npos) << r.err;
  EXPECT_EQ(countLines(r.err), 1u) << r.err;
}

// msm at a 16384² map said "framebuffer incomplete" where vssm said out of memory with advice.
// An address-space limit makes llvmpipe's allocation fail at once (a GPU's memory is not bound
// by it, so the test runs on software renderers only).
TEST(RenderCli, ShadowMapThatDoesNotFitSaysOutOfMemory) {
  const RunResult probe = runPenumbra("render --size 16x16 --verbose");
  if (probe.err.find("llvmpipe") == std::string::npos) GTEST_SKIP() << "not a software renderer: " << probe.err;
  constexpr const char* kLimit = "ulimit -v 3000000 &&";  // KiB: 3 GB, a 16384² moment map needs 4 GiB
  const RunResult r = runPenumbra("render --size 16x16 --filter msm --shadow-map 16384", "", kLimit);
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_NE(r.err.find("GL_OUT_OF_MEMORY (the shadow maps, the filter's tables or the image do not fit: try smaller maps "
                       "(Technique::mapSize, or a light's shadow.mapSize in its scene file"),
            std::string::npos) << r.err;
  EXPECT_NE(r.err.find("[--shadow-map"),
            std::string::npos) << r.err;
  EXPECT_EQ(countLines(r.err), 1u) << r.err;
  // A scene file's own 16384² point cube (six maps) fails where the maps are made, naming them,
  // and the advice names the light's shadow.mapSize beside --shadow-map, which did not ask for it.
  const std::string dir = freshDir("render-cube-oom");
  std::ofstream(dir + "/cube.json") << R"({"lights": [{"type": "point", "position": [0, 3, 0], "shadow": {"mapSize": 16384}}],
    "objects": [{"shape": "plane"}, {"shape": "box"}]})";
  const RunResult cube = runPenumbra("render --scene cube.json --size 16x16 --out cube.png", dir, kLimit);
  EXPECT_EQ(cube.exitCode, 1) << cube.err;
  EXPECT_NE(cube.err.find("the hard shadow map: 6 maps of 16384²: GL_OUT_OF_MEMORY"), std::string::npos) << cube.err;
  EXPECT_NE(cube.err.find("a light's shadow.mapSize in its scene file"), std::string::npos) << cube.err;
  EXPECT_EQ(countLines(cube.err), 1u) << cube.err;
  EXPECT_FALSE(std::filesystem::exists(dir + "/cube.png"));
}

// A 2 M-triangle load took 12 s without a word: a large model file is announced when it starts
// and when it is loaded (with a bar between them on a terminal).
TEST(RenderCli, LargeModelLoadsAreAnnounced) {
  const std::string dir = freshDir("large-obj");
  constexpr int kGrid = 600;  // 360 000 quads, ~17 MiB of OBJ: just above the 16 MiB announced
  {
    std::ofstream obj(dir + "/big.obj");
    obj << "# " << std::string(1 << 20, '-') << "\n";  // a comment pads the file past the size announced
    for (int i = 0; i <= kGrid; ++i)
      for (int j = 0; j <= kGrid; ++j) obj << "v " << i * 0.01 << " " << (i * 7 + j * 3) % 5 * 0.02 << " " << j * 0.01 << "\n";
    for (int i = 0; i < kGrid; ++i)
      for (int j = 0; j < kGrid; ++j) {
        const int a = i * (kGrid + 1) + j + 1;
        obj << "f " << a << " " << a + kGrid + 1 << " " << a + kGrid + 2 << " " << a + 1 << "\n";
      }
  }
  ASSERT_GE(std::filesystem::file_size(dir + "/big.obj"), 16u << 20);
  const RunResult r = runPenumbra("render --scene big.obj --size 16x16 --shadow-map 1024", dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.err.find("penumbra: loading big.obj ("), std::string::npos) << r.err;
  EXPECT_NE(r.err.find(" MiB)\npenumbra: loaded big.obj in "), std::string::npos) << r.err;
  // Small files load without progress lines (the one line box.obj prints is its added ground).
  const std::string small = runPenumbra("render --scene " + std::string(PENUMBRA_TEST_DATA) + "/models/box.obj --size 16x16").err;
  EXPECT_EQ(small.find("loading"), std::string::npos) << small;
  EXPECT_EQ(small.find("loaded"), std::string::npos) << small;
}

// --size 16384x16384 was accepted where 8192² already took 66 s and 3.8 GB: the size is checked
// against the driver and the memory before anything is allocated, with a size that would fit.
// The limits here are llvmpipe's (one texture ≤ 1 GiB, textures in host memory); a GPU with the
// memory would render these sizes.
TEST(RenderCli, ImageSizeThatCannotFitIsRefusedBeforeRendering) {
  const RunResult probe = runPenumbra("render --size 16x16 --verbose");
  if (probe.err.find("llvmpipe") == std::string::npos) GTEST_SKIP() << "not llvmpipe: " << probe.err;
  RunResult r = runPenumbra("render --size 16384x16384");
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_NE(r.err.find("--size 16384x16384: llvmpipe"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("cannot make a render target that large"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("8192x8192 or smaller would fit"), std::string::npos) << r.err;
  constexpr const char* kLimit = "ulimit -v 3000000 &&";  // KiB: 3 GB, 8192² needs 4.5 GiB
  r = runPenumbra("render --size 8192x8192", "", kLimit);
  EXPECT_EQ(r.exitCode, 1);
  // Renderer::screenBytes (its targets) plus the read-backs: 4.5 GiB at 8192² (72 B per pixel).
  EXPECT_NE(r.err.find("--size 8192x8192: the image needs about 4.5 GiB"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("or smaller would fit"), std::string::npos) << r.err;
  EXPECT_EQ(countLines(r.err), 1u) << r.err;
  r = runPenumbra("compare --size 4096x4096 --samples 1", "", kLimit);  // compare reads back far more
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_NE(r.err.find("--size 4096x4096: the image needs about"), std::string::npos) << r.err;
}

TEST(RenderCli, UnknownFilterExits2) {
  const RunResult r = runPenumbra("render --filter blurry");
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_NE(r.err.find("blurry"), std::string::npos) << r.err;
  EXPECT_EQ(countLines(r.err), 1u) << r.err;
}

TEST(RenderCli, BadSetIsAUsageError) {
  RunResult r = runPenumbra("render --set hard.nothing=1");
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_NE(r.err.find("hard.nothing"), std::string::npos) << r.err;
  r = runPenumbra("render --set hard.slopeBias=99");
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_NE(r.err.find("out of range"), std::string::npos) << r.err;
  r = runPenumbra("render --set light.size=5");  // boxes has a sun: its size is an angle, <= 0.5 rad
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_NE(r.err.find("sun"), std::string::npos) << r.err;
  r = runPenumbra("render --size 10by10");
  EXPECT_EQ(r.exitCode, 2);
  r = runPenumbra("render --no-such-option");
  EXPECT_EQ(r.exitCode, 2);
}

TEST(RenderCli, ShadowMapBeyondTheLimitIsAClearError) {
  const std::string why = "a map side is 1024..16384: below 1024 a texel grows wider than the built-in scenes' casters";
  const RunResult r = runPenumbra("render --shadow-map 1000000 --size 32x32");
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_NE(r.err.find("1000000 texels: " + why), std::string::npos) << r.err;
  // Below the least size at which the default bias and filters hold, every command that takes
  // --shadow-map refuses it, naming that size and why, and its --help says so.
  for (const std::string command : {"render", "compare", "view", "bench", "tune"}) {
    const RunResult small = runPenumbra(command + " --shadow-map 512 --size 32x32");
    EXPECT_EQ(small.exitCode, 2) << command;
    EXPECT_NE(small.err.find("512 texels: " + why), std::string::npos) << command << ": " << small.err;
    const RunResult help = runPenumbra(command + " --help");
    EXPECT_NE(help.out.find("INT in [1024 - 16384]"), std::string::npos) << command << ": " << help.out;
  }
  EXPECT_EQ(runPenumbra("render --shadow-map 1024 --size 16x16 --out small.png", freshDir("render-least-map")).exitCode, 0);
}

// A scene file may ask for smaller maps (an experiment with the texel): it renders, and the
// command line says once that the defaults no longer hold there, naming the fields; --shadow-map
// replaces the file's shadow.mapSize, so then only the light's own size is named.
TEST(RenderCli, SceneFileMapsBelowTheLeastAreRenderedWithANotice) {
  const std::string dir = freshDir("render-small-scene-maps");
  std::ofstream(dir + "/small.json") << R"({"lights": [{"type": "sun", "direction": [-0.4, -1, -0.3]},
      {"type": "spot", "position": [0, 4, 0], "direction": [0, -1, 0], "shadow": {"mapSize": 512}}],
    "objects": [{"shape": "plane"}, {"shape": "box"}], "shadow": {"mapSize": 256}})";
  const std::string why = "below 1024²: the default bias and filters are held to no acne and no detached shadow from 1024² up";
  RunResult r = runPenumbra("render --scene small.json --size 16x16 --out a.png", dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.err.find("small.json: shadow.mapSize 256, lights[1].shadow.mapSize 512 " + why), std::string::npos) << r.err;
  EXPECT_EQ(countLines(r.err), 1u) << r.err;
  r = runPenumbra("render --scene small.json --shadow-map 2048 --size 16x16 --out b.png", dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.err.find("small.json: lights[1].shadow.mapSize 512 " + why), std::string::npos) << r.err;
  r = runPenumbra("render --size 16x16 --out c.png", dir);  // boxes: 2048² maps, nothing said
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_EQ(r.err.find(why), std::string::npos) << r.err;
}

TEST(RenderCli, VisibilityExrAndDump) {
  const std::string dir = freshDir("dump");
  const RunResult r = runPenumbra("render --size 64x48 --shadow-map 1024 --visibility v.exr --dump d --out c.png", dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  int w = 0, h = 0;
  const std::vector<float> v = readExr(dir + "/v.exr", w, h);
  EXPECT_EQ(w, 64);
  EXPECT_EQ(h, 48);
  EXPECT_GT(*std::max_element(v.begin(), v.end()), 0.9f);
  EXPECT_LT(*std::min_element(v.begin(), v.end()), 0.1f);
  for (const char* f : {"color.png", "visibility.exr", "gbuffer-normal.png", "gbuffer-albedo.png", "shadow-map.exr", "shadow-map.png"})
    EXPECT_TRUE(std::filesystem::exists(dir + "/d/" + f)) << f;
}

// --repeat renders the same frame several times and writes the last, the same image as one
// render; --verbose then times the renders after the first (the first compiles the shaders).
TEST(RenderCli, RepeatWritesTheSameImageAndTimesTheWarmFrames) {
  const std::string dir = freshDir("frames");
  RunResult r = runPenumbra("render --size 64x48 --shadow-map 1024 --filter vsm --out one.png", dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  r = runPenumbra("render --size 64x48 --shadow-map 1024 --filter vsm --repeat 3 --verbose --out three.png", dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  int w = 0, h = 0;
  EXPECT_EQ(readPng(dir + "/one.png", w, h), readPng(dir + "/three.png", w, h));
  EXPECT_NE(r.err.find("medians of the 2 frames after the first"), std::string::npos) << r.err;
  for (const char* pass : {"gbuffer", "shadow", "prefilter", "visibility", "lit"})
    EXPECT_NE(r.err.find(std::string("penumbra: ") + pass), std::string::npos) << pass << "\n" << r.err;
  EXPECT_EQ(runPenumbra("render --repeat 0").exitCode, 2);
}

// The distance field's bake reports its time and memory; a second run reads the cache silently.
TEST(RenderCli, SdfBakePrintsTimeAndMemoryOnce) {
  const std::string cache = freshDir("sdf-cache");
  const std::string env = "PENUMBRA_CACHE='" + cache + "'";
  RunResult r = runPenumbra("render --scene pen --filter sdf --size 64x48 --out a.png", cache, env);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.err.find("sdf: baked"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find(" s "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("MiB"), std::string::npos) << r.err;
  r = runPenumbra("render --scene pen --filter sdf --size 64x48 --out b.png", cache, env);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_EQ(r.err.find("sdf: baked"), std::string::npos) << r.err;
}

// --camera places the camera (position:target[:fov]) on any scene; the picture changes, and
// anything but three numbers, three numbers and an optional field of view is a usage error.
TEST(RenderCli, CameraOptionMovesTheView) {
  const std::string dir = freshDir("camera");
  RunResult r = runPenumbra("render --size 64x36 --out own.png", dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  r = runPenumbra("render --size 64x36 --camera -2,1.5,3:0,0.5,0:30 --out moved.png", dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  int w = 0, h = 0;
  const std::vector<uint8_t> own = readPng(dir + "/own.png", w, h), moved = readPng(dir + "/moved.png", w, h);
  ASSERT_EQ(own.size(), moved.size());
  size_t differing = 0;
  for (size_t i = 0; i < own.size(); ++i) differing += own[i] != moved[i];
  EXPECT_GT(differing, own.size() / 4) << "the view did not move";
  for (const char* bad : {"1,2:0,0,0", "1,2,3:1,2,3", "0,5,0:0,0,0", "1,2,3:0,0,0:200", "nan,1,2:0,0,0",
                          "1,2,3,4:0,0,0", "1,2,3:0,0,0:30:4", "1,2,3", "a,b,c:0,0,0"}) {
    r = runPenumbra(std::string("render --size 16x16 --camera ") + bad);
    EXPECT_EQ(r.exitCode, 2) << bad;
    EXPECT_NE(r.err.find(std::string("--camera ") + bad), std::string::npos) << r.err;
    EXPECT_EQ(countLines(r.err), 1u) << r.err;
  }
}

TEST(RenderCli, HelpOnEverySubcommand) {
  for (const char* sub : {"", "render", "compare", "view", "bench", "list"}) {
    const RunResult r = runPenumbra(std::string(sub) + " --help");
    EXPECT_EQ(r.exitCode, 0) << sub;
    EXPECT_NE(r.out.find("--"), std::string::npos) << sub;
  }
}

TEST(ListCli, JsonListsEveryTechniqueAndParameter) {
  const RunResult r = runPenumbra("list --json");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  for (const char* s : {"\"scenes\"", "\"boxes\"", "\"pen\"", "\"fence\"", "\"grazing\"", "\"uniform\"", "\"hard\"", "hard.bias", "light.size"})
    EXPECT_NE(r.out.find(s), std::string::npos) << s;
}

// --version names the build; a model given alone says, in one stderr line, that a ground was
// added under it (box.obj has no floor), and renders.
TEST(RenderCli, VersionAndALoneModelsGround) {
  const RunResult v = runPenumbra("--version");
  EXPECT_EQ(v.exitCode, 0) << v.err;
  EXPECT_TRUE(std::regex_match(v.out, std::regex("penumbra [0-9]+\\.[0-9]+\\.[0-9]+\n"))) << v.out;
  const RunResult r = runPenumbra("render --scene " + std::string(PENUMBRA_TEST_DATA) + "/models/box.obj --size 16x16",
                                  freshDir("render-lone-model"));
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_EQ(r.err.rfind("penumbra: box.obj: no floor in the model, so a ", 0), 0u) << r.err;
  EXPECT_EQ(countLines(r.err), 1u) << r.err;
}
