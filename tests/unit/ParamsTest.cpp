#include <penumbra/Error.h>
#include <penumbra/Registry.h>
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
  auto p = makeProjection("uniform");
  auto f = makeFilter("hard");
  applyParams({{"hard.bias", "none"}, {"hard.slopeBias", "2.5"}, {"light.size", "0.05"}}, scene, *p, *f);
  EXPECT_EQ(f->paramInt("hard.bias"), 0);
  EXPECT_FLOAT_EQ(f->param("hard.slopeBias"), 2.5f);
  EXPECT_FLOAT_EQ(scene.light().size, 0.05f);
}

TEST(Params, SetRejectsUnknownKeys) {
  Scene scene = makeBuiltinScene("boxes");
  auto p = makeProjection("uniform");
  auto f = makeFilter("hard");
  expectUsageError([&] { applyParams({{"hard.nope", "1"}}, scene, *p, *f); }, "hard.nope");
  expectUsageError([&] { applyParams({{"pcss.lightSize", "1"}}, scene, *p, *f); }, "pcss.lightSize");
}

TEST(Params, SetRejectsOutOfRangeAndMalformedValues) {
  Scene scene = makeBuiltinScene("boxes");
  auto p = makeProjection("uniform");
  auto f = makeFilter("hard");
  expectUsageError([&] { applyParams({{"hard.slopeBias", "1000"}}, scene, *p, *f); }, "hard.slopeBias");
  expectUsageError([&] { applyParams({{"hard.slopeBias", "-1"}}, scene, *p, *f); }, "out of range");
  expectUsageError([&] { applyParams({{"hard.slopeBias", "abc"}}, scene, *p, *f); }, "not a number");
  expectUsageError([&] { applyParams({{"hard.bias", "sloped"}}, scene, *p, *f); }, "expected one of");
  expectUsageError([&] { applyParams({{"light.size", "-0.1"}}, scene, *p, *f); }, "light.size");
  expectUsageError([] { splitAssignment("novalue"); }, "key=value");
}

TEST(Params, UnknownTechniquesAreUsageErrors) {
  expectUsageError([] { makeFilter("blurry"); }, "blurry");
  expectUsageError([] { makeProjection("fisheye"); }, "fisheye");
  expectUsageError([] { makeBuiltinScene("nowhere"); }, "nowhere");
}

TEST(Params, EveryDeclaredDefaultIsInRange) {
  for (const std::string& id : filterIds())
    for (const ParamDesc& d : makeFilter(id)->paramDescs()) EXPECT_NO_THROW(checkParamValue(d, d.def)) << d.key;
  for (const std::string& id : projectionIds())
    for (const ParamDesc& d : makeProjection(id)->paramDescs()) EXPECT_NO_THROW(checkParamValue(d, d.def)) << d.key;
}

// Every numeric parameter names its unit (the viewer's sliders and penumbra list show it); a
// choice has none.
TEST(Params, EveryNumericParameterHasAUnit) {
  std::vector<std::span<const ParamDesc>> tables = {sceneParamDescs()};
  std::vector<std::unique_ptr<Parameterized>> owners;
  for (const std::string& id : projectionIds()) owners.push_back(makeProjection(id));
  for (const std::string& id : filterIds()) owners.push_back(makeFilter(id));
  for (const auto& o : owners) tables.push_back(o->paramDescs());
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
