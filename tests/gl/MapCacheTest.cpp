// Cached shadow maps (Shadows::setMapCaching): with a still light and static casters the cached
// maps give bit-identical visibility to maps drawn anew; a static caster that moves invalidates
// the maps it was in (no stale shadow in the frame it moved); dynamic casters are drawn over the
// cache every frame.
#include "GlFixture.h"

#include <penumbra/Animation.h>

#include <string>

using namespace penumbra;
using namespace penumbra::test;

namespace {

constexpr int kW = 96, kH = 64, kMap = 512;
const RenderOptions kRender{kW, kH, kMap};

std::unique_ptr<Renderer> renderer(const Scene& scene, const std::string& projection, const std::string& filter, bool cached) {
  auto r = makeTestRenderer(scene, projection, filter);
  r->shadows().setMapCaching(cached);
  return r;
}

Scene stillBoxes() {
  Scene s = makeBuiltinScene("boxes");
  s.animation = {};
  return s;
}

}  // namespace

TEST(MapCache, StaticSceneGivesBitIdenticalVisibility) {
  const Scene boxes = stillBoxes();
  for (const auto& [projection, filter] : {std::pair{"uniform", "hard"}, {"csm", "pcf"}, {"uniform", "vsm"}, {"csm", "msm"}}) {
    auto plain = renderer(boxes, projection, filter, false);
    plain->render(kRender);
    auto cached = renderer(boxes, projection, filter, true);
    cached->render(kRender);  // draws the maps and stores them
    const size_t views = cached->frusta().views.size();
    EXPECT_EQ(cached->shadows().mapCacheStats().rendered, views) << projection << " " << filter;
    cached->render(kRender);  // restores them
    EXPECT_EQ(cached->shadows().mapCacheStats().restored, views) << projection << " " << filter;
    EXPECT_EQ(cached->readVisibility(), plain->readVisibility()) << projection << " " << filter;
  }
}

TEST(MapCache, MovingAStaticCasterInvalidatesItsMaps) {
  const Scene boxes = stillBoxes();
  auto cached = renderer(boxes, "uniform", "hard", true);
  cached->render(kRender);
  cached->render(kRender);
  ASSERT_EQ(cached->shadows().mapCacheStats().restored, 1u);
  Scene moved = boxes;
  moved.objects[4].worldFromObject[3] += glm::vec4(1.5f, 0.0f, 0.5f, 0.0f);  // sphere A, a static caster
  cached->setPose(moved);
  cached->render(kRender);
  EXPECT_EQ(cached->shadows().mapCacheStats().rendered, 2u) << "the frame it moved draws the map again";
  auto fresh = renderer(moved, "uniform", "hard", false);
  fresh->render(kRender);
  EXPECT_EQ(cached->readVisibility(), fresh->readVisibility()) << "no stale shadow";
}

// boxes' rolling ball without the sun's sweep: the ball is a dynamic caster, drawn over the
// cached static casters; every frame equals a frame drawn anew. (The views of uniform and csm
// are fitted to the casters' bounds, the rolling ball's among them, so here they move a little
// every frame and the maps are drawn again: cached maps pay where the views stay.)
TEST(MapCache, DynamicCastersAreDrawnOverTheCache) {
  Scene boxes = makeBuiltinScene("boxes");
  boxes.animation.suns.clear();
  auto cached = renderer(boxes, "csm", "hard", true);
  for (const float t : {0.0f, 1.0f, 2.0f, 3.0f}) {
    Scene posed = boxes;
    poseScene(posed, t);
    cached->setPose(posed);
    cached->render(kRender);
    auto fresh = renderer(posed, "csm", "hard", false);
    fresh->render(kRender);
    EXPECT_EQ(cached->readVisibility(), fresh->readVisibility()) << "t = " << t;
  }
  // The same frame again: restored, the ball drawn over.
  cached->render(kRender);
  auto again = renderer(cached->scene(), "csm", "hard", false);
  again->render(kRender);
  EXPECT_EQ(cached->readVisibility(), again->readVisibility());
  const size_t views = cached->frusta().views.size();
  EXPECT_EQ(cached->shadows().mapCacheStats().restored, views);
}
