// The bench's pure parts: sweep parsing and expansion, statistics, the Pareto front, CSV
// quoting and the SVG charts (no GL).
#include "bench/BenchPlan.h"
#include "bench/BenchResults.h"
#include "report/HtmlReport.h"
#include "bench/ResultsIO.h"
#include "report/SvgChart.h"

#include <penumbra/Error.h>
#include "techniques/Registry.h"

#include <gtest/gtest.h>

#include <algorithm>

namespace penumbra::report {
namespace {

TEST(BenchPlan, SweepParsesAndSpacesValuesEvenly) {
  const Sweep s = parseSweep("light.size=0.02:0.2:4");
  EXPECT_EQ(s.key, "light.size");
  const ParamDesc numeric{"light.size", "", "", "m", 0.0f, 0.0f, 10.0f, 0.0f};
  const std::vector<float> v = s.values(numeric);
  ASSERT_EQ(v.size(), 4u);
  EXPECT_FLOAT_EQ(v[0], 0.02f);
  EXPECT_FLOAT_EQ(v[1], 0.08f);
  EXPECT_FLOAT_EQ(v[3], 0.2f);
  // Integer parameters round and drop repeats: 1, 1.5, 2, 2.5, 3 → 1, 2, 3.
  const ParamDesc integer{"x.n", "", "", "taps", 1.0f, 1.0f, 64.0f, 1.0f};
  EXPECT_EQ(parseSweep("x.n=1:3:5").values(integer), (std::vector<float>{1.0f, 2.0f, 3.0f}));
}

TEST(BenchPlan, SweepTakesAListOfValues) {
  const Sweep s = parseSweep("light.count=1,2,4,8");
  EXPECT_EQ(s.key, "light.count");
  const ParamDesc integer{"light.count", "", "", "lights", 0.0f, 0.0f, 16.0f, 1.0f};
  EXPECT_EQ(s.values(integer), (std::vector<float>{1.0f, 2.0f, 4.0f, 8.0f}));
  EXPECT_EQ(parseSweep("x.n=3,2.6,7").values(integer), (std::vector<float>{3.0f, 7.0f}));  // rounded, repeats dropped
  EXPECT_EQ(parseSweep("light.size=0.5").values(ParamDesc{"light.size", "", "", "m", 0.0f, 0.0f, 10.0f, 0.0f}),
            (std::vector<float>{0.5f}));
}

TEST(BenchPlan, BadSweepsAreUsageErrors) {
  for (const char* bad : {"light.count=1,,2", "light.count=1,2,", "light.count=a,2", "light.count=", "light.size", "light.size=0.1:0.2", "light.size=a:0.2:3", "light.size=0.1:0.2:0",
                          "=0:1:2", "light.size=0.1:0.2:3:4", "light.size=0.1:0.2:100000"}) {
    try {
      parseSweep(bad);
      ADD_FAILURE() << bad << " was accepted";
    } catch (const Error& e) {
      EXPECT_EQ(e.kind(), ErrorKind::Usage) << bad;
    }
  }
}

// A choice is swept by its names (the re-time command of a recommendation writes them so); a
// name the parameter does not have is a usage error naming the sweep.
TEST(BenchPlan, ChoicesAreSweptByName) {
  const BenchPlan plan{.name = "custom", .scenes = {"glass"}, .projections = {"uniform"}, .filters = {"pcf"},
                       .sweeps = {parseSweep("translucent.shadows=on"), parseSweep("translucent.method=map,stochastic")}};
  const std::vector<BenchConfig> configs = expandPlans({plan});
  ASSERT_EQ(configs.size(), 2u);
  EXPECT_EQ(configs[0].paramsText(), "translucent.shadows=on;translucent.method=map");
  EXPECT_EQ(configs[1].paramsText(), "translucent.shadows=on;translucent.method=stochastic");
  BenchPlan bad = plan;
  bad.sweeps = {parseSweep("translucent.method=map,dither")};
  try {
    expandPlans({bad});
    ADD_FAILURE() << "translucent.method=dither was accepted";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Usage);
    EXPECT_NE(std::string(e.what()).find("--sweep translucent.method"), std::string::npos) << e.what();
  }
}

// A scene with translucent casters gets the three techniques that shadow through them, on the
// run's filters among hard, pcf and msm; a scene without gets nothing more.
TEST(BenchPlan, TranslucentCastersGetTheTechniquesThatShadowThroughThem) {
  const BenchPlan run{.name = "custom", .scenes = {"boxes", "glass"}, .projections = {"uniform", "csm"},
                      .filters = {"hard", "pcf", "pcss", "msm"}, .sweeps = {}};
  std::vector<std::string> rows;
  for (const BenchConfig& c : expandPlans(translucentPlans(run)))
    rows.push_back(c.scene + " " + c.projection + " " + c.filter + " " + c.paramsText() + (c.inGrid ? " (grid)" : ""));
  EXPECT_EQ(rows, (std::vector<std::string>{
                      "glass uniform hard translucent.shadows=on (grid)", "glass uniform pcf translucent.shadows=on (grid)",
                      "glass uniform msm translucent.shadows=on (grid)", "glass uniform msm msm.translucent=on (grid)",
                      "glass uniform pcf translucent.shadows=on;translucent.method=stochastic;temporal.accumulate=on (grid)"}));
  EXPECT_TRUE(translucentPlans({.name = "custom", .scenes = {"boxes"}, .projections = {"uniform"}, .filters = {"pcf"}, .sweeps = {}}).empty());
  EXPECT_TRUE(translucentPlans({.name = "custom", .scenes = {"glass"}, .projections = {"uniform"}, .filters = {"pcss"}, .sweeps = {}}).empty());
}

TEST(BenchPlan, SweepAppliesOnlyToTechniquesThatDeclareTheKey) {
  const BenchPlan plan{.name = "custom", .scenes = {"boxes"}, .projections = {"uniform"}, .filters = {"hard", "pcf"},
                       .sweeps = {parseSweep("pcf.radiusTexels=1:4:4"), parseSweep("light.size=0.01:0.03:2")}};
  const std::vector<BenchConfig> configs = expandPlans({plan});
  const auto count = [&](const std::string& filter) {
    return std::count_if(configs.begin(), configs.end(), [&](const BenchConfig& c) { return c.filter == filter; });
  };
  EXPECT_EQ(count("hard"), 2);      // the light sweep only
  EXPECT_EQ(count("pcf"), 4 * 2);   // both sweeps
  // A technique's swept values run one after the other (one curve, timed close together).
  const auto isPcf = [](const BenchConfig& c) { return c.filter == "pcf"; };
  const auto first = std::find_if(configs.begin(), configs.end(), isPcf);
  const auto last = std::find_if(configs.rbegin(), configs.rend(), isPcf).base();
  EXPECT_EQ(last - first, 8);
  // One grid row per filter.
  EXPECT_EQ(std::count_if(configs.begin(), configs.end(), [](const BenchConfig& c) { return c.inGrid; }), 2);
}

TEST(BenchPlan, UnknownSweepKeysAndOutOfRangeValuesAreRefused) {
  BenchPlan plan{.name = "custom", .scenes = {"boxes"}, .projections = {"uniform"}, .filters = {"hard"},
                 .sweeps = {parseSweep("pcf.radiusTexels=1:4:4")}};
  EXPECT_THROW(expandPlans({plan}), Error);  // no technique of the plan has it
  plan.sweeps = {parseSweep("hard.slopeBias=-1:2:2")};
  EXPECT_THROW(expandPlans({plan}), Error);  // below the parameter's minimum
  plan.sweeps = {};
  plan.scenes = {"no-such-scene"};
  EXPECT_THROW(expandPlans({plan}), Error);
}

TEST(BenchPlan, ConfigurationsOfOneSceneAreContiguous) {
  const BenchPlan a{.name = "a", .scenes = {"boxes", "pen"}, .projections = {"uniform"}, .filters = {"hard"}, .sweeps = {}};
  const BenchPlan b{.name = "b", .scenes = {"pen", "boxes"}, .projections = {"uniform"}, .filters = {"pcf"},
                    .sweeps = {parseSweep("light.size=0.01:0.03:3")}};
  const std::vector<BenchConfig> configs = expandPlans({a, b});
  ASSERT_EQ(configs.size(), 2u + 6u);
  std::vector<std::string> scenes;
  for (const BenchConfig& c : configs)
    if (scenes.empty() || scenes.back() != c.scene) scenes.push_back(c.scene);
  EXPECT_EQ(scenes, (std::vector<std::string>{"boxes", "pen"}));
  EXPECT_EQ(configs[0].plan, "a");  // plan order inside a scene
  EXPECT_EQ(configs[1].params, (std::vector<std::pair<std::string, std::string>>{{"light.size", "0.01"}}));
  EXPECT_EQ(configs[2].params, (std::vector<std::pair<std::string, std::string>>{{"light.size", "0.02"}}));
}

TEST(BenchPlan, DefaultRunCoversEveryFilterProjectionAndScene) {
  BenchSettings settings;
  const std::vector<BenchConfig> configs = expandPlans(defaultPlans(false, settings));
  for (const std::string& f : filterIds())
    for (const std::string& p : projectionIds())
      EXPECT_TRUE(std::any_of(configs.begin(), configs.end(), [&](const BenchConfig& c) {
        return c.filter == f && c.projection == p && c.scene == "city";
      })) << f << " " << p;
  BenchSettings quick;
  EXPECT_LT(expandPlans(defaultPlans(true, quick)).size(), configs.size());
  EXPECT_LT(quick.width * quick.height, settings.width * settings.height);
}

TEST(BenchStats, MedianAndPercentilesInterpolate) {
  const std::vector<double> s = {5, 1, 4, 2, 3};  // sorted 1..5
  const TimeStats t = timeStats(s);
  EXPECT_DOUBLE_EQ(t.median, 3.0);
  EXPECT_DOUBLE_EQ(t.p10, 1.4);  // position 0.4 between 1 and 2
  EXPECT_DOUBLE_EQ(t.p90, 4.6);
  const std::vector<double> one = {7};
  EXPECT_DOUBLE_EQ(timeStats(one).p10, 7.0);
  EXPECT_DOUBLE_EQ(timeStats({}).median, 0.0);
}

TEST(BenchStats, ShadowCostIsTheQuantileOfPerFrameSumsOfTheCorePasses) {
  // Three frames: one with a slow shadow pass, one with a slow visibility pass. The passes'
  // medians (1 + 0 + 1 = 2 ms) miss that two of the three frames cost 11 ms; the per-frame sums
  // {2, 11, 11} do not. The G-buffer and lit passes are not the technique's.
  const FrameSamples frames = {{"gbuffer", {100, 100, 100}}, {"shadow", {1, 10, 1}}, {"prefilter", {0, 0, 0}},
                               {"visibility", {1, 1, 10}}, {"lit", {50, 50, 50}}};
  const TimeStats cost = shadowCostStats(frames);
  EXPECT_DOUBLE_EQ(cost.median, 11.0);
  EXPECT_DOUBLE_EQ(cost.p10, 2.0 + 0.2 * 9.0);  // position 0.2 between 2 and 11
  EXPECT_DOUBLE_EQ(cost.p90, 11.0);
  EXPECT_DOUBLE_EQ(shadowCostStats({}).median, 0.0);
}

TEST(BenchStats, ParetoFrontKeepsOnlyUndominatedPoints) {
  //                          0    1    2    3    4
  const std::vector<double> x = {1.0, 2.0, 3.0, 2.5, 0.5};
  const std::vector<double> y = {0.5, 0.3, 0.1, 0.4, 0.9};
  // 3 is dominated by 1 (faster and better); the others trade time for error.
  EXPECT_EQ(paretoFront(x, y), (std::vector<size_t>{4, 0, 1, 2}));
}

TEST(BenchResultsIO, CsvQuotesTextAndRoundTripsNumbers) {
  BenchResults r;
  r.machine.glRenderer = "llvmpipe (LLVM 15, 256 bits)";  // a comma: must be quoted
  r.machine.clock = "glFinish+steady_clock";
  BenchRow row;
  row.config = {.plan = "custom", .scene = "boxes", .projection = "uniform", .filter = "hard",
                .params = {{"hard.bias", "slope"}, {"light.size", "0.1"}}, .inGrid = false};
  row.metrics.rmse = 0.1 + 0.2;  // 0.30000000000000004: needs all 17 digits
  row.metrics.leakPct = 1.25;
  row.metrics.umbraLeakPct = 0.375;  // its own column, not confused with leak_pct
  row.lightSize = 0.12f;         // written as 0.12, the float's shortest text
  row.passes = {{"visibility", {1.5, 1.0, 2.0}}, {kTotalPass, {3.0, 2.0, 4.0}}};
  r.rows.push_back(row);
  const std::string csv = resultsCsv(r);
  EXPECT_NE(csv.find("\"llvmpipe (LLVM 15, 256 bits)\""), std::string::npos) << csv;
  EXPECT_NE(csv.find("hard.bias=slope;light.size=0.1"), std::string::npos);
  EXPECT_NE(csv.find("0.30000000000000004"), std::string::npos);
  EXPECT_NE(csv.find("visibility_ms_p90"), std::string::npos);
  const nlohmann::json j = resultsJson(r);
  EXPECT_EQ(j["rows"][0]["rmse"].get<double>(), 0.1 + 0.2);
  EXPECT_EQ(j["rows"][0]["visibility_ms_median"].get<double>(), 1.5);
  EXPECT_EQ(j["rows"][0]["light_size"].get<double>(), 0.12);
  EXPECT_EQ(j["rows"][0]["leak_pct"].get<double>(), 1.25);
  EXPECT_EQ(j["rows"][0]["umbra_leak_pct"].get<double>(), 0.375);
}

// pages_drawn: a paged row's mean pages drawn a frame over its motion; empty for a row that does
// not page and for a still row.
TEST(BenchResultsIO, PagesDrawnIsTheMotionsMeanForPagedRowsOnly) {
  BenchResults r;
  BenchRow paged;
  paged.config = {.plan = "custom", .scene = "city", .projection = "virtual", .filter = "hard", .params = {}, .inGrid = false};
  paged.motion = MotionScore{.what = kAnimationMotion, .fps = kMotionFps, .frames = {{}, {}, {}, {}}, .colourFrames = {}, .flicker = {}, .pagesDrawn = {0, 4, 3, 3}};
  BenchRow cascaded = paged;
  cascaded.config.projection = "csm";
  cascaded.motion->pagesDrawn.clear();
  BenchRow still = paged;
  still.motion.reset();
  r.rows = {paged, cascaded, still};
  const nlohmann::json j = resultsJson(r);
  EXPECT_EQ(j["rows"][0]["pages_drawn"].get<double>(), 2.5);
  EXPECT_TRUE(j["rows"][1]["pages_drawn"].is_null());
  EXPECT_TRUE(j["rows"][2]["pages_drawn"].is_null());
  const std::vector<std::string> columns = tableColumns(r);
  EXPECT_NE(std::find(columns.begin(), columns.end(), "pages_drawn"), columns.end());
}

// A micro-benchmark that failed is kept with its error: in the JSON and in the page's table,
// with no ratio drawn against it. The page names each row's baseline.
TEST(BenchResultsIO, FailedMicroBenchmarkIsReportedNotLost) {
  BenchResults r;
  r.micro.push_back({"copy SAT table, 2 moments", "a copy", "", TimeStats{}, 0, "GL_INVALID_VALUE in glDispatchCompute", {}});
  r.micro.push_back({"SAT build, 2 moments", "the build", "copy SAT table, 2 moments", {2.0, 1.0, 3.0}, 3, "", {}});
  const nlohmann::json j = resultsJson(r);
  EXPECT_EQ(j["micro"][0]["error"].get<std::string>(), "GL_INVALID_VALUE in glDispatchCompute");
  EXPECT_EQ(j["micro"][1]["error"].get<std::string>(), "");
  const std::string html = microHtml(r);
  EXPECT_EQ(htmlReport(r).find("SAT build"), std::string::npos) << "the building blocks are a page of their own";
  EXPECT_NE(html.find("failed: GL_INVALID_VALUE in glDispatchCompute"), std::string::npos);
  EXPECT_EQ(html.find(" × <small>"), std::string::npos) << "a ratio against a failed baseline";
  EXPECT_NE(html.find("<td class=\"l\">SAT build, 2 moments</td><td class=\"l wrap\">copy SAT table, 2 moments</td>"),
            std::string::npos)
      << "the build's row names its baseline";
}

TEST(SvgChart, TicksAreRoundNumbersInsideTheRange) {
  const std::vector<double> lin = axisTicks(0.0, 0.13, false);
  ASSERT_GE(lin.size(), 3u);
  EXPECT_DOUBLE_EQ(lin[0], 0.0);
  EXPECT_NEAR(lin[1] - lin[0], 0.02, 1e-12);
  EXPECT_LE(lin.back(), 0.13);
  EXPECT_EQ(axisTicks(0.3, 40.0, true), (std::vector<double>{0.5, 1, 2, 5, 10, 20}));
  EXPECT_EQ(axisTicks(0.05, 5000.0, true), (std::vector<double>{0.1, 1, 10, 100, 1000}));
  // A narrow log axis (tune's costs: 24 … 46 ms) holds no 1-2-5 value: round linear steps label it.
  EXPECT_EQ(axisTicks(24.0, 46.0, true), (std::vector<double>{25, 30, 35, 40, 45}));
  EXPECT_GE(axisTicks(0.0141, 0.0227, true).size(), 3u);
}

TEST(SvgChart, DrawsOneMarkerPerPointAndEscapesText) {
  Chart c;
  c.title = "a < b & c";
  c.series.push_back({.color = "#123456", .marker = Marker::Square, .connect = true,
                      .points = {{1, 2, 1.5, 2.5, "p1", true}, {2, 3, NAN, NAN, "p2", false}}});
  c.legend.push_back({"hard", "#123456", Marker::Square, false, false});
  const std::string svg = svgChart(c);
  EXPECT_EQ(svg.rfind("<svg", 0), 0u);
  EXPECT_NE(svg.find("a &lt; b &amp; c"), std::string::npos);
  size_t rects = 0;
  for (size_t p = svg.find("<rect"); p != std::string::npos; p = svg.find("<rect", p + 1)) ++rects;
  EXPECT_EQ(rects, 1u /* frame */ + 2u /* markers */ + 1u /* legend */);
  EXPECT_NE(svg.find("<polyline"), std::string::npos);
  EXPECT_NE(svg.find("<title>p1</title>"), std::string::npos);
}

}  // namespace
}  // namespace penumbra::report
