#include <penumbra/Error.h>
#include "techniques/Registry.h"
#include <penumbra/SceneIO.h>

#include <gtest/gtest.h>

using namespace penumbra;

namespace {

void expectUsageError(const std::function<void()>& f, const std::string& mustMention) {
  try {
    f();
    ADD_FAILURE() << "no error thrown";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Usage) << e.what();
    EXPECT_NE(std::string(e.what()).find(mustMention), std::string::npos) << e.what();
  }
}

}  // namespace

TEST(Params, SetAcceptsKnownKeysAndChoices) {
  Scene scene = makeBuiltinScene("boxes");
  Technique t("uniform", "hard");
  applySettings({{"hard.bias", "none"}, {"hard.slopeBias", "2.5"}, {"light.size", "0.05"}}, scene, t);
  EXPECT_EQ(t.getInt("hard.bias"), 0);
  EXPECT_FLOAT_EQ(t.get("hard.slopeBias"), 2.5f);
  EXPECT_FLOAT_EQ(scene.light().size, 0.05f);
}

TEST(Params, SetRejectsUnknownKeys) {
  Scene scene = makeBuiltinScene("boxes");
  Technique t("uniform", "hard");
  expectUsageError([&] { applySettings({{"hard.nope", "1"}}, scene, t); }, "hard.nope");
  expectUsageError([&] { applySettings({{"pcss.lightSize", "1"}}, scene, t); }, "pcss.lightSize");
  expectUsageError([&] { applySettings({{"pcss.blockerSamples", "8"}}, scene, t); }, "it is pcss's");
}

TEST(Params, SetRejectsOutOfRangeAndMalformedValues) {
  Scene scene = makeBuiltinScene("boxes");
  Technique t("uniform", "hard");
  expectUsageError([&] { applySettings({{"hard.slopeBias", "1000"}}, scene, t); }, "hard.slopeBias");
  expectUsageError([&] { applySettings({{"hard.slopeBias", "-1"}}, scene, t); }, "out of range");
  expectUsageError([&] { applySettings({{"hard.slopeBias", "abc"}}, scene, t); }, "not a number");
  expectUsageError([&] { applySettings({{"hard.bias", "sloped"}}, scene, t); }, "expected one of");
  expectUsageError([&] { applySettings({{"light.size", "-0.1"}}, scene, t); }, "light.size");
  expectUsageError([] { splitAssignment("novalue"); }, "key=value");
}

TEST(Params, UnknownTechniquesAreUsageErrors) {
  expectUsageError([] { makeFilter("blurry"); }, "blurry");
  expectUsageError([] { makeProjection("fisheye"); }, "fisheye");
  expectUsageError([] { Technique("uniform", "blurry"); }, "blurry");
  expectUsageError([] { Technique().setProjection("fisheye"); }, "fisheye");
  expectUsageError([] { makeBuiltinScene("nowhere"); }, "nowhere");
}

TEST(Params, EveryDeclaredDefaultIsInRange) {
  for (const std::string& id : filterIds())
    for (const ParamDesc& d : filterParams(id)) EXPECT_NO_THROW(checkParamValue(d, d.def)) << d.key;
  for (const std::string& id : projectionIds())
    for (const ParamDesc& d : projectionParams(id)) EXPECT_NO_THROW(checkParamValue(d, d.def)) << d.key;
}

// One place routes a key: the projection's, the filter's, an add-on's, another technique's, none.
TEST(Technique, RoutesEveryKeyToItsOwner) {
  const Technique t("csm", "pcss");
  EXPECT_EQ(t.owner("csm.cascades"), ParamOwner::Projection);
  EXPECT_EQ(t.owner("pcss.blockerSamples"), ParamOwner::Filter);
  EXPECT_EQ(t.owner("contact.shadows"), ParamOwner::AddOn);
  EXPECT_EQ(t.owner("temporal.alpha"), ParamOwner::AddOn);
  EXPECT_EQ(t.owner("pcf.radiusTexels"), ParamOwner::OtherTechnique);
  EXPECT_EQ(t.owner("tsm.focusDistanceM"), ParamOwner::OtherTechnique);
  EXPECT_EQ(t.owner("pcss.nothing"), ParamOwner::None);
  EXPECT_EQ(t.owner("light.size"), ParamOwner::None) << "a scene setting, not a technique's";
  EXPECT_TRUE(t.has("csm.cascades"));
  EXPECT_FALSE(t.has("pcf.radiusTexels"));
}

// A copyable value: copies compare equal until one changes; the text names what differs from the
// defaults; a new projection starts at its defaults and keeps the rest.
TEST(Technique, IsAValue) {
  Technique a("csm", "pcss", {{"pcss.blockerSamples", "8"}, {"contact.shadows", "on"}});
  a.setMapSize(1024);
  Technique b = a;
  EXPECT_TRUE(a == b);
  b.set("pcss.blockerSamples", 9.0f);
  EXPECT_FALSE(a == b);
  EXPECT_EQ(a.text(), "csm × pcss, 1024² maps, pcss.blockerSamples=8, contact.shadows=on");
  EXPECT_EQ(a.changedParams(), (std::vector<std::pair<std::string, std::string>>{{"pcss.blockerSamples", "8"}, {"contact.shadows", "on"}}));
  const Technique back(a.projection(), a.filter(), a.changedParams());
  EXPECT_TRUE(back == Technique(a).setMapSize(kDefaultMapSize)) << "changedParams() reads back";
  b = a;
  b.set("csm.cascades", 2.0f).setProjection("uniform");
  EXPECT_FALSE(b.has("csm.cascades"));
  EXPECT_EQ(b.get("pcss.blockerSamples"), 8.0f);
  EXPECT_EQ(b.mapSize(), 1024);
  b.setProjection("csm");
  EXPECT_EQ(b.get("csm.cascades"), Technique("csm", "hard").get("csm.cascades")) << "back at its default";
  expectUsageError([&] { b.setMapSize(0); }, "Technique::mapSize");
}

// A light's own settings are merged into the technique as values: its projection, filter, map
// size and parameters; keys of another technique wait for it (checked all the same); a key of
// none, or a bad value, names the light and the field.
TEST(Technique, MergesALightsOwnSettings) {
  const Technique sun("csm", "pcf", {{"pcf.radiusTexels", "2"}});
  LightShadowSettings lamp;
  lamp.projection = "uniform";
  lamp.mapSize = 512;
  lamp.params = {{"csm.cascades", "2"}, {"pcf.radiusTexels", "3"}, {"uniform.marginTexels", "2"}};
  Light point;
  point.type = LightType::Point;
  EXPECT_NE(sun.problemWith(point).find("Technique::projection \"csm\" cannot shadow a point light"), std::string::npos) << sun.problemWith(point);
  const Technique merged = sun.forLight(lamp, "light 1");
  EXPECT_EQ(merged.projection(), "uniform");
  EXPECT_EQ(merged.filter(), "pcf");
  EXPECT_EQ(merged.mapSize(), 512);
  EXPECT_EQ(merged.get("pcf.radiusTexels"), 3.0f);
  EXPECT_EQ(merged.problemWith(point), "");
  EXPECT_EQ(sun.get("pcf.radiusTexels"), 2.0f) << "the technique itself is unchanged";
  lamp.params = {{"pcf.nothing", "1"}};
  expectUsageError([&] { (void)sun.forLight(lamp, "light 1"); }, "light 1: LightShadowSettings::params: no projection, filter or add-on has a parameter 'pcf.nothing'");
  lamp.params = {{"csm.cascades", "99"}};
  expectUsageError([&] { (void)Technique("uniform", "pcf").forLight(lamp, "light 1"); }, "csm.cascades=99");
  lamp.params = {};
  lamp.filter = "blurry";
  expectUsageError([&] { (void)sun.forLight(lamp, "light 1"); }, "light 1: LightShadowSettings::filter: unknown filter 'blurry'");
}

// Every numeric parameter names its unit (the viewer's sliders and penumbra list show it); a
// choice has none.
TEST(Params, EveryNumericParameterHasAUnit) {
  std::vector<std::span<const ParamDesc>> tables = {sceneParamDescs()};
  for (const std::string& id : projectionIds()) tables.push_back(projectionParams(id));
  for (const std::string& id : filterIds()) tables.push_back(filterParams(id));
  size_t numeric = 0;
  for (const auto& table : tables)
    for (const ParamDesc& d : table) {
      if (d.isChoice()) {
        EXPECT_TRUE(d.unit.empty()) << d.key;
      } else {
        EXPECT_FALSE(d.unit.empty()) << d.key << " has no unit";
        ++numeric;
      }
    }
  EXPECT_GT(numeric, 40u);
}
