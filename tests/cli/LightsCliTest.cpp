// Lights on the command line: a bad light entry in a scene file stops the run with one line naming
// the light and the field (exit 1), and compare scores every light of a scene with several.
#include "CliSupport.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

using namespace penumbra::test;

TEST(LightsCli, BadLightEntryExitsOneNamingTheField) {
  const std::string dir = freshDir("bad-light");
  struct Case {
    const char* light;
    const char* message;
  };
  const Case cases[] = {
      {R"({"type": "area"})", "lights[1].type: unknown light type 'area'"},
      {R"({"type": "spot", "innerConeDeg": 40, "outerConeDeg": 30})", "lights[1].innerConeDeg: 40 is outside [0, 30]"},
      {R"({"type": "spot", "outerConeDeg": 95})", "lights[1].outerConeDeg: 95 is outside"},
      {R"({"type": "point", "range": -1})", "lights[1].range: -1 is outside"},
      {R"({"type": "point", "size": 0.3, "range": 0.2})", "lights[1].range: 0.2 m must exceed the light's size 0.3 m"},
      {R"({"type": "point", "position": [0, 1e39, 0]})", "lights[1].position: expected an array of 3 numbers"},
      {R"({"type": "point", "shadow": {"mapSize": 4}})", "lights[1].shadow.mapSize: 4 is outside [16, 16384]"},
  };
  for (const Case& c : cases) {
    std::ofstream(dir + "/light.json") << R"({"lights": [{"type": "sun"}, )" << c.light
                                       << R"(], "objects": [{"shape": "plane"}, {"shape": "box"}]})";
    const RunResult r = runPenumbra("render --scene light.json --size 32x32 --out out.png", dir);
    EXPECT_EQ(r.exitCode, 1) << c.light << ": " << r.err;
    EXPECT_NE(r.err.find("light.json: " + std::string(c.message)), std::string::npos) << c.light << " gave: " << r.err;
    EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << "one line: " << r.err;
  }
}

// The issue's check: compare on `room` lists its point lamp and its spot, each with its metrics.
TEST(LightsCli, CompareListsEveryLightWithItsMetrics) {
  const std::string dir = freshDir("compare-room");
  const RunResult r = runPenumbra("compare --scene room --filter pcss --size 96x64 --shadow-map 1024 --samples 16 --json --no-cache --out imgs", dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  ASSERT_TRUE(j.contains("lights"));
  const nlohmann::json& lights = j["lights"];
  ASSERT_EQ(lights.size(), 2u);
  const char* types[] = {"point", "spot"};
  for (size_t i = 0; i < lights.size(); ++i) {
    const nlohmann::json& l = lights[i];
    for (const char* k : {"index", "type", "rmse", "mae", "leak_pct", "overdark_pct", "penumbra_rmse", "map_texels"})
      EXPECT_TRUE(l.contains(k)) << "lights[" << i << "]." << k;
    EXPECT_EQ(l["index"], i);
    EXPECT_EQ(l["type"], types[i]);
    const double rmse = l["rmse"];
    std::printf("room, pcss, light %zu (%s): RMSE %.4f over %d pixels\n", i, types[i], rmse, l.value("pixels", 0));
    EXPECT_TRUE(std::isfinite(rmse));
    EXPECT_GT(rmse, 0.0) << "a soft shadow map never matches the reference exactly";
    EXPECT_LT(rmse, 0.2);
    EXPECT_GT(l["map_texels"].get<double>(), 0.0);
  }
  // The point lamp renders six cube faces, the spot one view.
  EXPECT_EQ(lights[0].value("map_views", 0), 6);
  EXPECT_EQ(lights[1].value("map_views", 0), 1);
}

// A glTF file's own point and spot lights render (tests/data/models/lamps.gltf).
TEST(LightsCli, GltfLampsRender) {
  const RunResult r = runPenumbra("render --scene '" PENUMBRA_TEST_DATA "/models/lamps.gltf' --filter pcf --size 64x48 --out lamps.png");
  EXPECT_EQ(r.exitCode, 0) << r.err;
}

// A light's own shadow.params are checked at load against the technique they name, under any
// --filter (exit 1 naming the file, the light and the field), and wait for that technique: the
// docs' own examples (docs/lights.md: a point light with pcss.blockerSamples) render under the
// default filter, --verbose says what is not applied, and bench runs hard and pcss on one file.
TEST(LightsCli, LightParamsAreCheckedAtLoadAndAppliedWithTheirTechnique) {
  const std::string dir = freshDir("light-params");
  const auto scene = [&](const std::string& params) {
    std::ofstream(dir + "/lamp.json") << R"({"lights": [{"type": "sun", "direction": [0.3, -1, 0.2]},
      {"type": "point", "position": [0, 2.4, 0], "size": 0.05, "range": 8, "shadow": {"mapSize": 64, "params": {)"
                                      << params << R"(}}}], "objects": [{"shape": "plane"}, {"shape": "box"}]})";
  };
  scene(R"("pcss.blockerSamples": 32)");
  RunResult r = runPenumbra("render --scene lamp.json --size 24x16 --shadow-map 1024 --verbose --out a.png", dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.err.find("lamp.json: lights[1].shadow.params.pcss.blockerSamples=32 not applied: not a parameter of --projection "
                       "uniform or --filter hard"),
            std::string::npos) << r.err;
  r = runPenumbra("render --scene lamp.json --filter pcss --size 24x16 --shadow-map 1024 --verbose --out b.png", dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_EQ(r.err.find("not applied"), std::string::npos) << "pcss takes it: " << r.err;
  r = runPenumbra("bench --scenes lamp.json --filters hard,pcss --projections uniform --size 64x48 --shadow-map 1024 --samples 1 "
                  "--frames 1 --micro-rounds 1 --out bench",
                  dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.out.find("2 configurations measured, 0 skipped (0 failed)"), std::string::npos) << r.out;

  struct Case {
    std::string params, message;
  };
  for (const Case& c : std::vector<Case>{
           {R"("hard.constantBias": 5)", "lamp.json: lights[1].shadow.params.hard.constantBias: hard.constantBias=5 is out of range"},
           {R"("pcss.nosuch": 1)", "lamp.json: lights[1].shadow.params.pcss.nosuch: unknown parameter 'pcss.nosuch'"},
           {R"("blurry.radius": 1)", "lamp.json: lights[1].shadow.params.blurry.radius: no technique 'blurry'"},
           {R"("pcss.blockerSamples": "many")", "lamp.json: lights[1].shadow.params.pcss.blockerSamples: pcss.blockerSamples=many: not a number"},
       }) {
    scene(c.params);
    for (const char* filter : {"hard", "pcss"}) {
      r = runPenumbra("render --scene lamp.json --size 24x16 --out bad.png --filter " + std::string(filter), dir);
      EXPECT_EQ(r.exitCode, 1) << c.params << " under " << filter;
      EXPECT_NE(r.err.find(c.message), std::string::npos) << c.params << " under " << filter << ": " << r.err;
      EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << "one line: " << r.err;
    }
  }
  EXPECT_FALSE(std::filesystem::exists(dir + "/bad.png"));
}

// glTF lights are held to the scene files' rules, and --set light.size to the range it must stay
// below (each was accepted: compare then scored 0 pixels).
TEST(LightsCli, GltfLightsAndLightSizeKeepTheSceneFilesRules) {
  const std::string bad = std::string(PENUMBRA_TEST_DATA) + "/bad/";
  struct Case {
    std::string file, message;
  };
  for (const Case& c : std::vector<Case>{
           {"gltf_light_range_below_size.gltf", "extensions.KHR_lights_punctual.lights[0].range: 0.2 m must exceed the light's size 0.5 m"},
           {"gltf_light_negative_range.gltf", "extensions.KHR_lights_punctual.lights[0].range: must be in (0, 1000000] m"},
           {"gltf_light_intensity_text.gltf", "extensions.KHR_lights_punctual.lights[0].intensity: expected a number"},
           {"gltf_light_extension_array.gltf", "nodes[0].extensions.KHR_lights_punctual: expected an object"},
           {"gltf_animation_integer_times.gltf", "accessors[2]: componentType 5123 is not allowed for animations[0].samplers[0].input"},
       }) {
    const RunResult r = runPenumbra("render --size 16x16 --scene " + bad + c.file);
    EXPECT_EQ(r.exitCode, 1) << c.file;
    EXPECT_NE(r.err.find(c.file + ": " + c.message), std::string::npos) << c.file << ": " << r.err;
  }
  const RunResult r = runPenumbra("render --scene room --set light.size=10 --size 16x16");
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_NE(r.err.find("light.size=10: the first light's range is 6 m; its size (sphere radius) must stay below it"), std::string::npos)
      << r.err;
}

// A --shadow-budget below what the maps take at their smallest side (16² each) could only be
// exceeded, never kept: it is refused before any work, naming the maps and the least budget
// (night's eight lamps draw 28 maps: 4 spots, 4 point lights of 6 faces). The least is kept.
TEST(LightsCli, AShadowBudgetBelowTheMapsLeastIsRefused) {
  const std::string dir = freshDir("light-budget");
  RunResult r = runPenumbra("render --scene night --size 16x16 --shadow-budget 7167 --out below.png", dir);
  EXPECT_EQ(r.exitCode, 2) << r.err;
  EXPECT_NE(r.err.find("--shadow-budget 7167: the scene's 8 shadowed lights draw 28 maps, 7168 texels at the smallest side (16²); "
                       "give at least 7168"),
            std::string::npos) << r.err;
  EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << "one line: " << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir + "/below.png"));
  r = runPenumbra("compare --scene night --size 16x16 --samples 1 --shadow-budget 7168 --json --no-cache --out least", dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  int64_t texels = 0;
  for (const nlohmann::json& l : j["lights"]) {
    EXPECT_EQ(l["map_size"].get<int>(), 16) << l;
    texels += l["map_texels"].get<int64_t>();
  }
  EXPECT_EQ(texels, 7168);
}
