// Every projection × every registered filter, on a sun scene and a spot-light scene: each pair
// either renders without GL errors and agrees with the same filter on the uniform projection
// (same shadows, different sampling), or is refused up front with the filter's reason.
#include "GlFixture.h"

#include <penumbra/Error.h>

#include <cmath>

using namespace penumbra;
using namespace penumbra::test;

namespace {

constexpr int kW = 128, kH = 96, kMap = 512;
// Pixels whose V differs from uniform's by more than half: shadows in the wrong place, not a
// different sampling of the right ones (edges move by a texel or so between projections).
constexpr float kFarOffV = 0.5f;
constexpr double kMaxFarOffFraction = 0.04;

struct Outcome {
  bool refused = false;
  std::string why;
  RenderResult result;
};

Outcome run(const Scene& scene, const std::string& projection, const std::string& filter) {
  Outcome o;
  // The projection may refuse the light (only uniform and virtual shadow a point light), or the filter the pair.
  std::string reason = projectionIncompatibility(projection, scene.light());
  if (reason.empty()) reason = filterIncompatibility(filter, projection, scene.light());
  if (!reason.empty()) {
    o.refused = true;
    o.why = reason;
    // The renderer must refuse it too, naming the pair and the reason.
    glContext();
    Renderer r;
    r.setScene(scene);
    try {
      r.setTechnique(Technique(projection, filter));
      ADD_FAILURE() << filter << " × " << projection << ": incompatible but accepted";
    } catch (const Error& e) {
      EXPECT_EQ(e.kind(), ErrorKind::Usage);
      EXPECT_NE(std::string(e.what()).find(reason), std::string::npos) << e.what();
    }
    return o;
  }
  o.result = renderScene(scene, projection, filter, {}, kW, kH, kMap);  // throws on a GL error
  return o;
}

void checkAllPairs(const Scene& scene) {
  for (const std::string& filter : filterIds()) {
    const Outcome base = run(scene, "uniform", filter);
    for (const std::string& projection : projectionIds()) {
      SCOPED_TRACE(scene.name + ": --projection " + projection + " --filter " + filter);
      Outcome o;
      ASSERT_NO_THROW(o = run(scene, projection, filter));
      if (o.refused) {
        EXPECT_FALSE(o.why.empty());
        continue;
      }
      const std::vector<float>& v = o.result.visibility;
      size_t covered = 0, farOff = 0, shadowed = 0;
      for (size_t i = 0; i < v.size(); ++i) {
        ASSERT_TRUE(std::isfinite(v[i]) && v[i] >= 0.0f && v[i] <= 1.0f) << "V = " << v[i] << " at pixel " << i;
        if (!o.result.gbuffer.covered(i)) continue;
        ++covered;
        shadowed += v[i] < 0.5f ? 1 : 0;
        if (!base.refused && std::abs(v[i] - base.result.visibility[i]) > kFarOffV) ++farOff;
      }
      ASSERT_GT(covered, 0u);
      EXPECT_GT(shadowed, covered / 400) << "no shadows at all";
      EXPECT_LT(static_cast<double>(farOff) / static_cast<double>(covered), kMaxFarOffFraction)
          << farOff << " of " << covered << " pixels disagree with uniform × " << filter;
    }
  }
}

}  // namespace

TEST(ProjectionMatrix, EveryPairOnASunScene) { checkAllPairs(makeBuiltinScene("boxes")); }

TEST(ProjectionMatrix, EveryPairOnASpotLightScene) { checkAllPairs(makeBuiltinScene("pen")); }

// room's lamp alone: a point light, which only uniform and virtual shadow (the others refuse it
// with their reason).
TEST(ProjectionMatrix, EveryPairOnAPointLightScene) {
  Scene room = makeBuiltinScene("room");
  room.lights.resize(1);
  checkAllPairs(room);
}
