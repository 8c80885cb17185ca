// Lights on the command line: a bad light entry in a scene file stops the run with one line naming
// the light and the field (exit 1), and compare scores every light of a scene with several.
#include "CliSupport.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>
#include <string>

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
  const RunResult r = runPenumbra("compare --scene room --filter pcss --size 96x64 --shadow-map 512 --samples 16 --json --no-cache --out imgs", dir);
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
