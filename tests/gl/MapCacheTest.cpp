// Cached shadow maps (Shadows::setMapUpdates): with a still light and static casters the cached
// maps give bit-identical visibility to maps drawn anew; a static caster that moves invalidates
// the maps it was in (no stale shadow in the frame it moved); dynamic casters are drawn over the
// cache every frame, and the views, fitted to the static casters, stay; the round-robin budget
// updates exactly N maps a frame and the visibility pass reads a kept map with the view it was
// drawn with.
#include "GlFixture.h"

#include <penumbra/Animation.h>
#include <penumbra/Error.h>
#include <penumbra/Metrics.h>
#include <penumbra/Reference.h>

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <cstdio>
#include <string>

using namespace penumbra;
using namespace penumbra::test;

namespace {

constexpr int kW = 96, kH = 64, kMap = 512;
const RenderOptions kRender{.width = kW, .height = kH};
// Where pixels are counted: enough of them that one pixel is not a percent.
const RenderOptions kRenderLarger{.width = 2 * kW, .height = 2 * kH};

const MapUpdates kEvery{}, kWhenInvalid{MapUpdates::Policy::WhenInvalid};

std::unique_ptr<Renderer> renderer(const Scene& scene, const std::string& projection, const std::string& filter,
                                   const MapUpdates& updates) {
  auto r = makeTestRenderer(scene, projection, filter, {}, kMap);
  r->shadows().setMapUpdates(updates);
  return r;
}

Scene stillBoxes() {
  Scene s = makeBuiltinScene("boxes");
  s.animation = {};
  return s;
}

// Share of pixels whose V differs by more than half (a shadow edge in another place).
double differingPct(const std::vector<float>& a, const std::vector<float>& b) {
  size_t n = 0;
  for (size_t i = 0; i < a.size(); ++i) n += std::abs(a[i] - b[i]) > 0.5f ? 1 : 0;
  return 100.0 * static_cast<double>(n) / static_cast<double>(a.size());
}

}  // namespace

TEST(MapCache, StaticSceneGivesBitIdenticalVisibility) {
  const Scene boxes = stillBoxes();
  for (const auto& [projection, filter] : {std::pair{"uniform", "hard"}, {"csm", "pcf"}, {"uniform", "vsm"}, {"csm", "msm"}}) {
    auto plain = renderer(boxes, projection, filter, kEvery);
    plain->render(kRender);
    auto cached = renderer(boxes, projection, filter, kWhenInvalid);
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
  auto cached = renderer(boxes, "uniform", "hard", kWhenInvalid);
  cached->render(kRender);
  cached->render(kRender);
  ASSERT_EQ(cached->shadows().mapCacheStats().restored, 1u);
  Scene moved = boxes;
  moved.objects[4].worldFromObject[3] += glm::vec4(1.5f, 0.0f, 0.5f, 0.0f);  // sphere A, a static caster
  cached->setPose(moved);
  cached->render(kRender);
  EXPECT_EQ(cached->shadows().mapCacheStats().rendered, 2u) << "the frame it moved draws the map again";
  auto fresh = renderer(moved, "uniform", "hard", kEvery);
  fresh->render(kRender);
  EXPECT_EQ(cached->readVisibility(), fresh->readVisibility()) << "no stale shadow";
}

// boxes' rolling ball (a dynamic caster) under a still sun and a still camera: with cached maps
// the cascades are fitted to the static casters, so they stay where they are while the ball
// rolls, and every map's static layer is restored in every frame after the first; the ball is
// drawn over it, exactly as a fresh cached render of that frame draws it. Against a render
// without the cache (whose cascades follow the ball's bounds too) only the texel grid moves:
// its RMSE against the reference stays within kRmseBound and fewer than kDifferingPct of the
// pixels change side of a shadow edge.
TEST(MapCache, MovingDynamicCasterKeepsTheStaticMapsUnderAStillLight) {
  constexpr double kRmseBound = 0.01, kDifferingPctBound = 1.0;
  Scene boxes = makeBuiltinScene("boxes");
  boxes.animation.suns.clear();
  auto cached = renderer(boxes, "csm", "hard", kWhenInvalid);
  ReferenceOptions ro;
  ro.useCache = false;
  ro.progress = false;
  ro.samples = 16;
  const std::vector<float> times = {0.0f, 1.0f, 2.0f, 3.0f};
  glm::mat4 firstView(0.0f);
  for (const float t : times) {
    Scene posed = boxes;
    poseScene(posed, t);
    cached->setPose(posed);
    cached->render(kRenderLarger);
    if (t == 0.0f) firstView = cached->frusta().views[0].clipFromWorld;
    EXPECT_EQ(cached->frusta().views[0].clipFromWorld, firstView) << "t = " << t << ": the ball moved the fitted views";
    auto fresh = renderer(posed, "csm", "hard", kWhenInvalid);
    fresh->render(kRenderLarger);
    EXPECT_EQ(cached->readVisibility(), fresh->readVisibility()) << "t = " << t;
    auto plain = renderer(posed, "csm", "hard", kEvery);
    plain->render(kRenderLarger);
    const GBufferData g = plain->readGBuffer();
    const ReferenceResult ref = ReferenceTracer(posed).trace(g, posed.light(), ro);
    const double rmseCached = compareVisibility(cached->readVisibility(), ref.visibility, ref.litMask).rmse;
    const double rmsePlain = compareVisibility(plain->readVisibility(), ref.visibility, ref.litMask).rmse;
    const double differing = differingPct(cached->readVisibility(), plain->readVisibility());
    std::printf("t = %g s: RMSE cached %.4f, uncached %.4f; %.3f%% of pixels differ by > 0.5\n", t, rmseCached, rmsePlain, differing);
    EXPECT_NEAR(rmseCached, rmsePlain, kRmseBound) << "t = " << t;
    EXPECT_LT(differing, kDifferingPctBound) << "t = " << t;
  }
  const size_t views = cached->frusta().views.size();
  EXPECT_EQ(cached->shadows().mapCacheStats().rendered, views) << "drawn in the first frame only";
  EXPECT_EQ(cached->shadows().mapCacheStats().restored, views * (times.size() - 1));
}

// csm's 4 cascades under boxes' sweeping sun (every map invalid in every frame): a budget of N
// updates exactly N maps a frame after the first, keeps the others, and the staleness the
// round-robin reaches is 4/N − 1 frames.
TEST(MapCache, BudgetUpdatesExactlyNMapsPerFrameRoundRobin) {
  const Scene boxes = makeBuiltinScene("boxes");
  for (const int budget : {1, 2}) {
    auto r = renderer(boxes, "csm", "hard", {MapUpdates::Policy::Budget, budget});
    Shadows::MapCacheStats last{};
    for (int f = 0; f < 6; ++f) {
      Scene posed = boxes;
      poseScene(posed, 0.5f * static_cast<float>(f));
      r->setPose(posed);
      r->render(kRender);
      const Shadows::MapCacheStats now = r->shadows().mapCacheStats();
      const size_t updated = now.restored + now.rendered - last.restored - last.rendered, kept = now.kept - last.kept;
      const size_t views = r->frusta().views.size();
      ASSERT_EQ(views, 4u);
      EXPECT_EQ(updated, f == 0 ? views : static_cast<size_t>(budget)) << "budget " << budget << ", frame " << f;
      EXPECT_EQ(kept, f == 0 ? 0u : views - static_cast<size_t>(budget)) << "budget " << budget << ", frame " << f;
      last = now;
    }
    EXPECT_EQ(last.maxStaleness, 4 / budget - 1) << "budget " << budget;
    EXPECT_GT(last.meanStaleness, 0.0);
  }
}

// Two suns with one map each and a budget of 1: in the second frame (both suns turned 10°) sun 0's
// map is updated and sun 1's kept, so sun 1's shadows are where the first frame's sun put them:
// its view is the first frame's, and its V matches a fresh render with the first frame's
// direction on the pixels where the two directions disagree (reading the kept map with this
// frame's matrix puts them elsewhere). The third frame updates sun 1 and keeps sun 0.
TEST(MapCache, KeptMapIsReadWithTheViewItWasDrawnWith) {
  constexpr float kHorizontalNormalY = 0.99f;
  Scene scene = makeBuiltinScene("boxes");
  scene.animation = {};
  Light second = scene.lights[0];
  second.direction = glm::vec3(glm::rotate(glm::mat4(1.0f), glm::radians(70.0f), glm::vec3(0, 1, 0)) * glm::vec4(second.direction, 0.0f));
  scene.lights.push_back(second);
  const auto turned = [&](float deg) {
    Scene s = scene;
    for (Light& l : s.lights)
      l.direction = glm::vec3(glm::rotate(glm::mat4(1.0f), glm::radians(deg), glm::vec3(0, 1, 0)) * glm::vec4(l.direction, 0.0f));
    return s;
  };
  const std::vector<Scene> poses = {turned(0.0f), turned(10.0f), turned(20.0f)};
  std::vector<std::unique_ptr<Renderer>> fresh;
  for (const Scene& s : poses) {
    fresh.push_back(renderer(s, "uniform", "hard", kWhenInvalid));
    fresh.back()->render(kRenderLarger);
  }
  auto budget = renderer(scene, "uniform", "hard", {MapUpdates::Policy::Budget, 1});
  for (size_t f = 0; f < poses.size(); ++f) {
    budget->setPose(poses[f]);
    budget->render(kRenderLarger);
    if (f == 0) continue;
    const size_t updated = f % 2 == 1 ? 0 : 1, kept = 1 - updated;  // the least recently updated, light 0 first on ties
    EXPECT_EQ(budget->readVisibility(updated), fresh[f]->readVisibility(updated)) << "frame " << f << ": the updated sun";
    EXPECT_EQ(budget->frusta(kept).views[0].clipFromWorld, fresh[f - 1]->frusta(kept).views[0].clipFromWorld) << "frame " << f;
    // Where the shadows of this frame's and the last frame's directions differ, the kept map
    // shows the last frame's: on horizontal surfaces, whose angle to the suns (turned about the
    // vertical) is the same in both frames, so that only the map and its view decide.
    const std::vector<float> now = fresh[f]->readVisibility(kept), before = fresh[f - 1]->readVisibility(kept);
    const std::vector<float> v = budget->readVisibility(kept);
    const GBufferData g = budget->readGBuffer();
    size_t moved = 0, asBefore = 0;
    for (size_t i = 0; i < v.size(); ++i) {
      if (!g.covered(i) || g.geoNormal[i].y < kHorizontalNormalY || std::abs(now[i] - before[i]) < 0.5f) continue;
      ++moved;
      asBefore += std::abs(v[i] - before[i]) < 0.5f ? 1 : 0;
    }
    std::printf("frame %zu, kept sun %zu: %zu pixels where the directions disagree, %zu as the last frame's\n", f, kept, moved, asBefore);
    ASSERT_GT(moved, 50u) << "the test needs the shadows to move";
    EXPECT_GE(static_cast<double>(asBefore), 0.98 * static_cast<double>(moved)) << "frame " << f;
  }
  EXPECT_EQ(budget->shadows().mapCacheStats().kept, 2u);
  EXPECT_EQ(budget->shadows().mapCacheStats().maxStaleness, 1);
}

// Policies per light: three suns with csm's 4 cascades under boxes' sweeping sun, Shadows' budget
// of 2 maps a frame. Sun 0 has a budget of its own of 1 map, sun 1 is drawn every frame, sun 2
// follows the shared budget: after the first frame each light keeps 3, 0 and 2 of its maps, and
// the oldest reaches 3, 0 and 1 frames; sun 1's maps are neither cached nor counted.
TEST(MapCache, EachLightFollowsItsOwnPolicy) {
  Scene boxes = makeBuiltinScene("boxes");
  boxes.lights.resize(3, boxes.lights[0]);
  boxes.lights[0].shadow.updates = MapUpdates{MapUpdates::Policy::Budget, 1};
  boxes.lights[1].shadow.updates = MapUpdates{};
  auto r = renderer(boxes, "csm", "hard", {MapUpdates::Policy::Budget, 2});
  const std::vector<int> keptPerFrame = {3, 0, 2}, oldest = {3, 0, 1};
  for (int f = 0; f < 6; ++f) {
    Scene posed = boxes;
    poseScene(posed, 0.5f * static_cast<float>(f));
    r->setPose(posed);
    r->render(kRender);
    const std::vector<LightShadowReport>& reports = r->shadows().lightReports();
    ASSERT_EQ(reports.size(), 3u);
    for (size_t l = 0; l < 3; ++l) {
      ASSERT_EQ(reports[l].views, 4) << "light " << l;
      EXPECT_EQ(reports[l].keptMaps, f == 0 ? 0 : keptPerFrame[l]) << "light " << l << ", frame " << f;
      if (f >= 4) {
        EXPECT_EQ(reports[l].staleness, oldest[l]) << "light " << l << ", frame " << f;
      }
    }
    EXPECT_EQ(reports[0].updates, (MapUpdates{MapUpdates::Policy::Budget, 1}));
    EXPECT_EQ(reports[1].updates, MapUpdates{});
    EXPECT_EQ(reports[2].updates, (MapUpdates{MapUpdates::Policy::Budget, 2}));
  }
  // Sun 0 updates 1 map a frame after the first, sun 2 two: the cache counts (4 + 4) + 5 · 3.
  const Shadows::MapCacheStats c = r->shadows().mapCacheStats();
  EXPECT_EQ(c.restored + c.rendered, 8u + 5u * 3u);
  EXPECT_EQ(c.kept, 5u * 5u);
  // A light's own budget below 1 is refused, naming the light.
  boxes.lights[2].shadow.updates = MapUpdates{MapUpdates::Policy::Budget, 0};
  r->setPose(boxes);
  try {
    r->render(kRender);
    ADD_FAILURE() << "a budget of 0 maps was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("light 2: LightShadowSettings::updates: MapUpdates::budgetMaps = 0"), std::string::npos) << e.what();
  }
}
