// Bad numbers everywhere a number goes in: NaN, ±infinity, huge and negative values fed to every
// numeric option of every subcommand (found in each subcommand's --help, so that a new option is
// covered the day it is added), to the options whose text holds numbers (--size, --camera, --set,
// --map-updates, --max-memory, --shard, --sweep, PENUMBRA_CACHE_MAX_MB), and to every numeric light
// field of a scene file and of a glTF file. Each run must exit 1 or 2 with one line naming the
// option or the field, and write nothing: options are checked before any scene is loaded or any GL
// work, files as they load. Runs go four at a time; the test takes seconds.
#include "CliSupport.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <future>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

using namespace penumbra::test;
namespace fs = std::filesystem;

namespace {

struct Case {
  std::string args;                ///< the whole command line after `penumbra`
  std::vector<std::string> names;  ///< what the message must name (the option, or the file and the field)
  int exit = 2;                    ///< the exit code: 2 for a usage error, 1 for a bad file
  std::string env = {};            ///< variables before the binary
  std::string inputName = {}, input = {};  ///< a file the run reads, written to in/ first
};

/// What the run left in `dir` besides its captured output and its input folder.
std::vector<std::string> written(const std::string& dir) {
  std::vector<std::string> out;
  for (const auto& e : fs::directory_iterator(dir)) {
    const std::string name = e.path().filename().string();
    if (name != ".stdout" && name != ".stderr" && name != "in") out.push_back(name);
  }
  return out;
}

/// Runs every case (four at a time), each in its own folder, with PENUMBRA_CACHE in that folder
/// (a cache written would count as written).
void expectAllRefused(const std::string& name, const std::vector<Case>& cases) {
  const std::string root = freshDir(name);
  constexpr size_t kParallelRuns = 4;
  for (size_t first = 0; first < cases.size(); first += kParallelRuns) {
    std::vector<std::future<std::pair<std::string, RunResult>>> runs;
    for (size_t i = first; i < std::min(cases.size(), first + kParallelRuns); ++i)
      runs.push_back(std::async(std::launch::async, [&, i] {
        const std::string dir = root + "/" + std::to_string(i);
        fs::create_directories(dir + "/in");
        if (!cases[i].inputName.empty()) std::ofstream(dir + "/in/" + cases[i].inputName) << cases[i].input;
        const std::string env = "PENUMBRA_CACHE='" + dir + "/cache' " + cases[i].env;
        return std::pair(dir, runPenumbra(cases[i].args, dir, env + " timeout 60"));
      }));
    for (size_t i = first; i < first + runs.size(); ++i) {
      const auto [dir, r] = runs[i - first].get();
      const Case& c = cases[i];
      EXPECT_EQ(r.exitCode, c.exit) << c.args << " " << c.input << ": stderr: " << r.err;
      for (const std::string& n : c.names)
        EXPECT_NE(r.err.find(n), std::string::npos) << c.args << " " << c.input << ": the message does not name " << n << ": " << r.err;
      EXPECT_TRUE(!r.err.empty() && r.err.find('\n') == r.err.size() - 1) << c.args << ": not one line: " << r.err;
      EXPECT_EQ(written(dir), std::vector<std::string>{}) << c.args << " wrote files";
    }
  }
}

// What is fed: NaN, ±infinity, a huge value (an integer past 64 bits where the option is one, a
// double past any range where it is not) and a negative one (-1 where the range excludes it,
// else far below the range).
std::vector<std::string> optionValues(bool integer, bool negativeValid) {
  return {"nan", "inf", "-inf", integer ? "99999999999999999999" : "1e300", negativeValid ? "-1e300" : "-1"};
}
// In JSON: Python's json module writes NaN and Infinity bare; 1e400 overflows a double.
std::vector<std::string> jsonValues(bool negativeValid) { return {"NaN", "Infinity", "-Infinity", "1e400", negativeValid ? "-1e300" : "-1"}; }

/// The cheapest valid run of each subcommand, option by option (a tested option replaces its own).
const std::vector<std::pair<std::string, std::vector<std::pair<std::string, std::string>>>> kBase = {
    {"render", {{"--scene", "boxes"}, {"--size", "16x16"}, {"--shadow-map", "1024"}, {"--out", "o.png"}}},
    {"compare", {{"--scene", "boxes"}, {"--size", "16x16"}, {"--shadow-map", "1024"}, {"--samples", "1"}, {"--out", "c"}}},
    {"bench", {{"--quick", ""}, {"--scenes", "pen"}, {"--filters", "hard"}, {"--projections", "uniform"}, {"--size", "16x16"},
               {"--shadow-map", "1024"}, {"--samples", "1"}, {"--frames", "1"}, {"--micro-rounds", "1"}, {"--out", "b"}}},
    {"tune", {{"--scene", "pen"}, {"--filters", "hard"}, {"--size", "32x32"}, {"--shadow-map", "1024"}, {"--samples", "1"},
              {"--candidates", "1"}, {"--max-minutes", "0.01"}, {"--out", "t"}}},
    {"view", {{"--size", "16x16"}, {"--frames", "1"}}},
    {"cache", {}},
};

/// `penumbra SUB BASE… OPTION=VALUE`, the base without OPTION; --fps needs --frames.
std::string command(const std::string& sub, const std::vector<std::pair<std::string, std::string>>& base, const std::string& option,
                    const std::string& value, const std::string& extra = "") {
  std::string args = sub;
  for (const auto& [o, v] : base)
    if (o != option) args += " " + o + (v.empty() ? "" : " '" + v + "'");
  if (option == "--fps" && sub != "bench") args += " --frames 2";
  return args + " " + extra + " '" + option + "=" + value + "'";
}

struct NumericOption {
  std::string name;
  double lo = -1e308;    ///< from --help's range, where it shows one
  bool integer = false;  ///< INT or UINT
};

/// The options of `sub` whose --help type is a number (INT, UINT, FLOAT), with their lower bound.
std::vector<NumericOption> numericOptions(const std::string& sub) {
  const RunResult help = runPenumbra(sub + " --help");
  EXPECT_EQ(help.exitCode, 0) << help.err;
  std::vector<NumericOption> out;
  const std::regex option(R"(^\s+(--[a-z-]+) (INT|UINT|FLOAT)\b(:\S+ in [\[(](\S+) - )?)");
  std::stringstream lines(help.out);
  for (std::string line; std::getline(lines, line);) {
    std::smatch m;
    if (!std::regex_search(line, m, option)) continue;
    NumericOption o{m[1], -1e308, m[2] != "FLOAT"};
    if (m[4].matched) o.lo = std::stod(m[4]);
    if (line.find(":POSITIVE") != std::string::npos || line.find(":NONNEGATIVE") != std::string::npos || m[2] == "UINT") o.lo = 0;
    out.push_back(o);
  }
  return out;
}

}  // namespace

TEST(BadNumbersCli, EveryNumericOptionOfEverySubcommandRefusesThemBeforeAnyWork) {
  std::vector<Case> cases;
  size_t options = 0;
  for (const auto& [sub, base] : kBase) {
    const std::vector<NumericOption> found = numericOptions(sub);
    EXPECT_FALSE(found.empty() && sub != "cache") << sub << ": no numeric option found in --help";
    for (const NumericOption& o : found) {
      ++options;
      for (const std::string& v : optionValues(o.integer, o.lo <= -1)) cases.push_back({.args = command(sub, base, o.name, v), .names = {o.name}});
    }
  }
  EXPECT_GE(options, 30u) << "render, compare, bench, tune, view and cache have about 32 numeric options";
  // Options whose text holds numbers, by hand: (subcommand, option, pattern with {} for the value,
  // what the message names, whether -1 is a valid value there).
  struct TextOption {
    std::string sub, option, pattern, names, extra;
    bool negativeValid = false;
  };
  const std::vector<TextOption> textOptions = {
      {"render", "--size", "{}x16", "--size", ""},
      {"render", "--size", "16x{}", "--size", ""},
      {"render", "--camera", "{},1,1:0,0,0", "--camera", "", true},
      {"render", "--camera", "1,1,1:0,{},0", "--camera", "", true},
      {"render", "--camera", "1,1,1:0,0,0:{}", "--camera", ""},
      {"render", "--set", "light.size={}", "light.size", ""},
      {"render", "--set", "light.count={}", "light.count", ""},
      {"render", "--set", "pcf.radiusTexels={}", "pcf.radiusTexels", "--filter pcf"},
      {"render", "--set", "contact.lengthM={}", "contact.lengthM", ""},
      {"render", "--map-updates", "{}", "--map-updates", ""},
      {"render", "--max-memory", "{}", "--max-memory", ""},
      {"compare", "--max-memory", "{}G", "--max-memory", ""},
      {"compare", "--map-updates", "{}", "--map-updates", ""},
      {"compare", "--camera", "1,1,1:0,0,0:{}", "--camera", ""},
      {"view", "--size", "{}x16", "--size", ""},
      {"bench", "--size", "16x{}", "--size", ""},
      {"bench", "--camera", "{},1,1:0,0,0", "--camera", "", true},
      {"bench", "--sweep", "light.size={}:0.1:2", "--sweep", ""},
      {"bench", "--sweep", "light.size=0:0.1:{}", "--sweep", ""},
      {"bench", "--sweep", "pcf.radiusTexels={},2", "--sweep", "--filters pcf"},
      {"tune", "--size", "{}x32", "--size", ""},
      {"tune", "--shard", "{}/2", "--shard", ""},
  };
  for (const TextOption& t : textOptions) {
    const auto& base = std::find_if(kBase.begin(), kBase.end(), [&](const auto& b) { return b.first == t.sub; })->second;
    std::vector<std::pair<std::string, std::string>> without = base;
    if (!t.extra.empty()) std::erase_if(without, [&](const auto& o) { return t.extra.starts_with(o.first + " "); });
    for (const std::string& v : optionValues(false, t.negativeValid)) {
      std::string pattern = t.pattern;
      pattern.replace(pattern.find("{}"), 2, v);
      cases.push_back({.args = command(t.sub, without, t.option, pattern, t.extra), .names = {t.names}});
    }
  }
  for (const std::string& v : optionValues(true, false))
    cases.push_back({.args = "cache", .names = {"PENUMBRA_CACHE_MAX_MB"}, .env = "PENUMBRA_CACHE_MAX_MB='" + v + "'"});
  std::printf("%zu runs over %zu numeric options and %zu options holding numbers\n", cases.size(), options, textOptions.size());
  expectAllRefused("bad-numbers-options", cases);
}

namespace {

/// A scene file whose second light is `light` (the first is a plain sun), over a plane and a box.
std::string sceneWithLight(const std::string& light) {
  return R"({"lights": [{"type": "sun"}, )" + light + R"(], "objects": [{"shape": "plane"}, {"shape": "box"}]})";
}

/// A glTF triangle under a KHR_lights_punctual light whose object is `light`.
std::string gltfWithLight(const std::string& light) {
  return R"({"asset": {"version": "2.0"},
  "buffers": [{"byteLength": 42, "uri": "data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAAAAABAAIA"}],
  "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36}, {"buffer": 0, "byteOffset": 36, "byteLength": 6}],
  "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]},
                {"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"}],
  "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
  "nodes": [{"mesh": 0}, {"translation": [0, 3, 0], "extensions": {"KHR_lights_punctual": {"light": 0}}}],
  "scenes": [{"nodes": [0, 1]}], "scene": 0,
  "extensions": {"KHR_lights_punctual": {"lights": [)" + light + "]}}}";
}

}  // namespace

// Every numeric field of a scene file's light (one component of each vector) and of a glTF
// light: each value refused with exit 1 naming the file and the field. -1 only where the field
// cannot be negative (a coordinate can).
TEST(BadNumbersCli, EveryNumericLightFieldOfASceneFileAndAGltfFileRefusesThem) {
  struct Field {
    std::string file;     ///< "scene" or "gltf"
    std::string pattern;  ///< the light (scene: lights[1]; glTF: lights[0]) with {} for the value
    std::string names;    ///< the field the message must name
    bool negativeValid = false;
  };
  const std::string keys = R"("keys": [{"timeS": 0, "rotateDeg": [0, 0, 0]}, {"timeS": 1, )";
  const std::vector<Field> fields = {
      {"scene", R"({"type": "point", "position": [0, {}, 0]})", "lights[1].position", true},
      {"scene", R"({"type": "spot", "direction": [0, {}, 0.1]})", "lights[1].direction", true},
      {"scene", R"({"type": "spot", "target": [0, {}, 1]})", "lights[1].target", true},
      {"scene", R"({"type": "point", "size": {}})", "lights[1].size"},
      {"scene", R"({"type": "sun", "size": {}})", "lights[1].size"},
      {"scene", R"({"type": "point", "range": {}})", "lights[1].range"},
      {"scene", R"({"type": "spot", "outerConeDeg": {}})", "lights[1].outerConeDeg"},
      {"scene", R"({"type": "spot", "coneAngleDeg": {}})", "lights[1].coneAngleDeg"},
      {"scene", R"({"type": "spot", "innerConeDeg": {}})", "lights[1].innerConeDeg"},
      {"scene", R"({"type": "point", "color": [1, {}, 1]})", "lights[1].color"},
      {"scene", R"({"type": "point", "intensity": {}})", "lights[1].intensity"},
      {"scene", R"({"type": "point", "shadow": {"mapSize": {}}})", "lights[1].shadow.mapSize"},
      {"scene", R"({"type": "point", "shadow": {"updates": {}}})", "lights[1].shadow.updates"},
      {"scene", R"({"type": "point", "shadow": {"params": {"pcf.radiusTexels": {}}}})", "lights[1].shadow.params.pcf.radiusTexels"},
      {"scene", R"({"type": "spot", "animation": {"pivot": [0, {}, 0], )" + keys + R"("rotateDeg": [0, 0, 10]}]}})",
       "lights[1].animation.pivot", true},
      {"scene", R"({"type": "spot", "animation": {)" + keys + R"("translate": [0, {}, 0]}]}})", "lights[1].animation.keys[1].translate", true},
      {"scene", R"({"type": "spot", "animation": {)" + keys + R"("rotateDeg": [0, {}, 0]}]}})", "lights[1].animation.keys[1].rotateDeg", true},
      {"scene", R"({"type": "spot", "animation": {"keys": [{"timeS": {}, "rotateDeg": [0, 0, 0]}]}})", "lights[1].animation.keys[0].timeS", true},
      {"scene", R"({"type": "sun", "sunPath": {"keys": [{"timeS": 0, "azimuthDeg": {}, "elevationDeg": 30}]}})",
       "lights[1].sunPath.keys[0].azimuthDeg", true},
      {"scene", R"({"type": "sun", "sunPath": {"keys": [{"timeS": 0, "azimuthDeg": 0, "elevationDeg": {}}]}})",
       "lights[1].sunPath.keys[0].elevationDeg", true},
      {"gltf", R"({"type": "point", "intensity": {}})", "KHR_lights_punctual.lights[0].intensity"},
      {"gltf", R"({"type": "point", "range": {}})", "KHR_lights_punctual.lights[0].range"},
      {"gltf", R"({"type": "point", "color": [1, {}, 1]})", "KHR_lights_punctual.lights[0].color"},
      {"gltf", R"({"type": "spot", "spot": {"innerConeAngle": {}}})", "KHR_lights_punctual.lights[0].spot.innerConeAngle"},
      {"gltf", R"({"type": "spot", "spot": {"outerConeAngle": {}}})", "KHR_lights_punctual.lights[0].spot.outerConeAngle"},
      {"gltf", R"({"type": "point", "extras": {"size": {}}})", "KHR_lights_punctual.lights[0].extras.size"},
  };
  std::vector<Case> cases;
  for (const Field& f : fields)
    for (const std::string& v : jsonValues(f.negativeValid)) {
      std::string light = f.pattern;
      light.replace(light.find("{}"), 2, v);
      const std::string name = f.file == "scene" ? "light.json" : "light.gltf";
      cases.push_back({.args = "render --scene in/" + name + " --size 16x16 --shadow-map 1024 --out o.png",
                       .names = {"in/" + name + ": ", f.names},
                       .exit = 1,
                       .inputName = name,
                       .input = f.file == "scene" ? sceneWithLight(light) : gltfWithLight(light)});
    }
  std::printf("%zu runs over %zu light fields\n", cases.size(), fields.size());
  expectAllRefused("bad-numbers-lights", cases);
}
