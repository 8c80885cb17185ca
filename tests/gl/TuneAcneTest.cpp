// `penumbra tune --objective acne` against the hard-shadow tests' own measures: on the grazing
// scene with the hard filter, the bias the search returns leaves at most 0.1 % acne on the floor
// (acneFraction) and keeps the box's shadow within 2 texels of its contact (contactGapTexels).
#include "GlFixture.h"
#include "TestGeometry.h"

#include "tuner/TuneRunner.h"

#include <filesystem>

using namespace penumbra;
using namespace penumbra::test;

namespace {

constexpr int kSize = 256;       // as the hard-shadow tests
constexpr int kMapSize = 2048;   // grazing's own map
constexpr double kMaxAcneFraction = 0.001;  // the 0.1 %
constexpr double kMaxContactGapTexels = 2.0;

report::BenchSetup setupFor(const report::BenchConfig& c, const std::string& /*camera: the scene's own*/) {
  report::BenchSetup s{makeBuiltinScene(c.scene), Technique(c.projection, c.filter)};
  applySettings(c.params, s.scene, s.technique);
  return s;
}

}  // namespace

TEST(TuneAcne, GrazingHardBiasHasNoAcneAndKeepsContact) {
  const std::filesystem::path out = std::filesystem::temp_directory_path() / "penumbra-tune-acne-gl";
  std::filesystem::remove_all(out);
  std::filesystem::create_directories(out);
  report::TuneRequest req;
  req.views = {{.scene = "grazing", .camera = ""}};
  req.projections = {"uniform"};
  req.filters = {"hard"};
  req.objective = report::TuneObjective::Acne;
  req.settings.width = kSize;
  req.settings.height = kSize;
  req.settings.shadowMapSize = kMapSize;
  req.settings.referenceSamples = 1;  // the sun is a point (size 0): one ray is exact
  req.candidates = 8;
  req.maxMinutes = 2.0;
  req.outDir = out;
  const report::TuneResults res = report::runTune(glContext(), req, setupFor);
  ASSERT_TRUE(res.recommended.has_value());
  const report::TuneRow& rec = res.confirmed[*res.recommended];
  EXPECT_LE(rec.metrics.acnePct, report::kMaxAcnePct);

  Scene scene = makeBuiltinScene("grazing");
  const double acne = acneFraction(scene, renderScene(scene, "uniform", "hard", rec.params, kSize, kSize, kMapSize));
  scene.camera.position = {2.6f, 1.6f, 2.2f};  // the box's shadow, as SlopeBiasShadowStillTouchesTheBox
  scene.camera.target = {0.9f, 0.0f, 0.0f};
  const double gap = contactGapTexels(scene, renderScene(scene, "uniform", "hard", rec.params, kSize, kSize, kMapSize), kMapSize);
  std::string set;
  for (const auto& [k, v] : rec.params) set += " " + k + "=" + v;
  std::printf("tune acne on grazing:%s: acne %.3f%%, contact gap %.2f texels (tune: acne %.3f%%, umbra leak %.3f%%)\n",
              set.c_str(), 100.0 * acne, gap, rec.metrics.acnePct, rec.metrics.umbraLeakPct);
  EXPECT_LE(acne, kMaxAcneFraction);
  EXPECT_LE(gap, kMaxContactGapTexels);
}
