// The lit pass: a frame lit only by suns is built without the spot and point code (PN_ONLY_SUNS)
// and shades exactly as the general program does.
#include "GlFixture.h"

#include <penumbra/Scene.h>

#include <gtest/gtest.h>

namespace penumbra::test {

// boxes (one sun) against boxes with a dark point light added: the point light adds exactly 0 to
// every pixel, but its presence builds the program with the positional code.
TEST(LitPass, OnlySunsShadesAsTheGeneralProgram) {
  const Scene scene = makeBuiltinScene("boxes");
  ASSERT_FALSE(isPositional(scene.light()));
  Scene withPoint = scene;
  Light dark;
  dark.type = LightType::Point;
  dark.position = {0.0f, 3.0f, 0.0f};
  dark.intensity = 0.0f;
  dark.castsShadow = false;
  withPoint.lights.push_back(dark);
  const RenderOptions o{.width = 160, .height = 90, .triangleIds = false};

  const auto suns = makeTestRenderer(scene, "uniform", "hard", {}, 256);
  suns->render(o);
  const auto general = makeTestRenderer(withPoint, "uniform", "hard", {}, 256);
  general->render(o);
  ASSERT_EQ(general->lightCount(), 2u);
  const ColorImage a = suns->readColor(), b = general->readColor();
  ASSERT_EQ(a.rgba.size(), b.rgba.size());
  size_t differ = 0, lit = 0;
  for (size_t i = 0; i < a.rgba.size(); i += 4) {
    differ += a.rgba[i] != b.rgba[i] || a.rgba[i + 1] != b.rgba[i + 1] || a.rgba[i + 2] != b.rgba[i + 2] ? 1 : 0;
    lit += a.rgba[i] > 128 ? 1 : 0;
  }
  EXPECT_GT(lit, a.rgba.size() / 16) << "the sun lights the frame";
  EXPECT_EQ(differ, 0u) << "pixels the two lit programs shade differently";
}

}  // namespace penumbra::test
