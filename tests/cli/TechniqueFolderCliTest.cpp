// Technique folders (docs/own-technique.md): the examples give the bits of the built-ins they
// rewrite, a GLSL error names the user's file and line and exits 2, a bad description names its
// field, and a folder's parameters reach --set and penumbra list like a built-in's.
#include "CliSupport.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

using namespace penumbra::test;

namespace {

const std::string kExamples = std::string(PENUMBRA_TEST_DATA) + "/../../examples/techniques";

std::string readFile(const std::filesystem::path& p) {
  std::ifstream f(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(f), {});
}

void writeFile(const std::filesystem::path& p, const std::string& text) {
  std::filesystem::create_directories(p.parent_path());
  std::ofstream(p, std::ios::binary) << text;
}

/// A folder made from an example, with its description and GLSL as given.
std::string folderFrom(const std::string& dir, const std::string& example, const std::string& json, const std::string& glsl) {
  const std::filesystem::path folder = std::filesystem::path(dir) / ("my-" + example);
  writeFile(folder / "technique.json", json.empty() ? readFile(kExamples + "/" + example + "/technique.json") : json);
  writeFile(folder / "visibility.glsl", glsl.empty() ? readFile(kExamples + "/" + example + "/visibility.glsl") : glsl);
  return folder.string();
}

/// `compare --json` of a filter on pen at a small size, with the technique image written.
nlohmann::json compareJson(const std::string& dir, const std::string& filter, const std::string& out, const std::string& extra = "") {
  const RunResult r = runPenumbra("compare --scene pen --size 96x64 --shadow-map 1024 --samples 8 --json --out " + out +
                                      " --filter " + filter + extra,
                                  dir, "env PENUMBRA_CACHE=" + dir + "/cache");
  EXPECT_EQ(r.exitCode, 0) << r.err;
  return r.exitCode == 0 ? nlohmann::json::parse(r.out) : nlohmann::json();
}

/// Every measurement of two compare runs is the same number, and their images the same bytes:
/// only the filter's name, the times and what describes the run's clock may differ.
/// `sets`: "name=value" set on both, as "<builtin>.name" and "<builtin>-folder.name".
void expectSameMetrics(const std::string& dir, const std::string& builtin, const std::string& folder,
                       const std::vector<std::string>& sets = {}) {
  std::string builtinSets, folderSets;
  for (const std::string& s : sets) {
    builtinSets += " --set " + builtin + "." + s;
    folderSets += " --set " + builtin + "-folder." + s;
  }
  const nlohmann::json a = compareJson(dir, builtin, "a", builtinSets), b = compareJson(dir, folder, "b", folderSets);
  ASSERT_FALSE(a.is_null());
  ASSERT_FALSE(b.is_null());
  int compared = 0;
  for (const auto& [key, value] : a.items()) {
    if (key == "filter" || key.find("ms") != std::string::npos || key == "clock" || key == "reference_seconds" || key == "reference_cached")
      continue;
    ASSERT_TRUE(b.contains(key)) << key;
    EXPECT_EQ(value, b[key]) << key;
    ++compared;
  }
  EXPECT_GE(compared, 10);
  EXPECT_GT(a["rmse"].get<double>(), 0.0);  // a shadow was measured
  EXPECT_EQ(b["filter"], builtin + "-folder");
  EXPECT_EQ(readFile(dir + "/a/technique.png"), readFile(dir + "/b/technique.png"));
}

}  // namespace

TEST(TechniqueFolderCli, ThePcfExampleGivesTheBuiltinsBits) {
  const std::string dir = freshDir("folder-pcf");
  expectSameMetrics(dir, "pcf", kExamples + "/pcf");
  // A compile-time parameter and a runtime one, set by their keys.
  expectSameMetrics(dir, "pcf", kExamples + "/pcf", {"kernel=box", "radiusTexels=1.5", "hardwareCompare=on"});
}

TEST(TechniqueFolderCli, TheVsmExampleGivesTheBuiltinsBits) {
  const std::string dir = freshDir("folder-vsm");
  expectSameMetrics(dir, "vsm", kExamples + "/vsm");
}

TEST(TechniqueFolderCli, AGlslErrorExits2NamingTheFileAndLine) {
  const std::string dir = freshDir("folder-glsl-error");
  std::string glsl = readFile(kExamples + "/pcf/visibility.glsl");
  const std::string line = "  float radiusTexels =";
  const size_t at = glsl.find(line);
  ASSERT_NE(at, std::string::npos);
  glsl.insert(at, "  undeclaredThing += 1.0;\n");
  int lineNo = 1;
  for (size_t i = 0; i < at; ++i) lineNo += glsl[i] == '\n';
  const std::string folder = folderFrom(dir, "pcf", "", glsl);
  const RunResult r = runPenumbra("render --scene pen --size 32x32 --shadow-map 1024 --out x.png --filter " + folder, dir);
  EXPECT_EQ(r.exitCode, 2) << r.err;
  const std::string file = (std::filesystem::canonical(folder) / "visibility.glsl").string();
  EXPECT_NE(r.err.find(file + ":" + std::to_string(lineNo) + ":"), std::string::npos) << r.err << "\nexpected " << file << ":" << lineNo;
  EXPECT_NE(r.err.find("undeclaredThing"), std::string::npos) << r.err;
}

TEST(TechniqueFolderCli, ABadDescriptionNamesTheField) {
  const std::string dir = freshDir("folder-bad-json");
  std::string json = readFile(kExamples + "/pcf/technique.json");
  struct Case {
    std::string from, to, field;
  };
  const Case cases[] = {
      {"\"default\": 2, \"range\": [0, 32]", "\"default\": 40, \"range\": [0, 32]", "params[1].default"},
      {"\"range\": [0, 32]", "\"range\": [32]", "params[1].range"},
      {"\"name\": \"samples\"", "\"name\": \"sam ples\"", "params[2].name"},
      {"\"maps\": [\"depth\"]", "\"maps\": [\"depth\", \"shadows\"]", "maps[1]"},
      {"\"id\": \"pcf-folder\"", "\"id\": \"pcf\"", "id"},
      {"\"unit\": \"texels\", \"default\": 2", "\"units\": \"texels\", \"default\": 2", "params[1].units"},
      {"\"meaning\": \"kernel radius", "\"meanin\": \"kernel radius", "params[1].meanin"},
  };
  for (const Case& c : cases) {
    std::string broken = json;
    const size_t at = broken.find(c.from);
    ASSERT_NE(at, std::string::npos) << c.from;
    broken.replace(at, c.from.size(), c.to);
    const std::string folder = folderFrom(dir, "pcf", broken, "");
    const RunResult r = runPenumbra("render --scene pen --size 32x32 --shadow-map 1024 --out x.png --filter " + folder, dir);
    EXPECT_EQ(r.exitCode, 2) << c.field << ": " << r.err;
    EXPECT_NE(r.err.find("technique.json: " + c.field + ":"), std::string::npos) << c.field << ": " << r.err;
  }
}

TEST(TechniqueFolderCli, ParametersAreListedAndSetLikeABuiltins) {
  const std::string dir = freshDir("folder-list");
  const RunResult r = runPenumbra("list --json --filter " + kExamples + "/vsm", dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  bool found = false;
  for (const nlohmann::json& f : j["filters"]) {
    if (f["id"] != "vsm-folder") continue;
    found = true;
    EXPECT_NE(f["folder"].get<std::string>().find("examples/techniques/vsm"), std::string::npos);
    ASSERT_EQ(f["params"].size(), 5u);
    EXPECT_EQ(f["params"][0]["key"], "vsm-folder.minVariance");
    EXPECT_EQ(f["params"][0]["unit"], "texels²");
    EXPECT_EQ(f["params"][0]["max"], 64.0);
    EXPECT_EQ(f["params"][3]["choices"], nlohmann::json::array({"off", "on"}));
  }
  EXPECT_TRUE(found) << r.out;
  // Out of range and unknown keys are refused as a built-in's are.
  const RunResult bad = runPenumbra("render --scene pen --size 32x32 --shadow-map 1024 --out x.png --filter " + kExamples +
                                        "/vsm --set vsm-folder.anisotropy=99",
                                    dir);
  EXPECT_EQ(bad.exitCode, 2);
  EXPECT_NE(bad.err.find("vsm-folder.anisotropy"), std::string::npos) << bad.err;
}
