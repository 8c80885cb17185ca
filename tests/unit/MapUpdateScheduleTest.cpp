// The map update schedule without GL: a budget of N maps a frame updates the least recently
// updated maps across lights (round-robin), a kept map's view in the frusta is the one it was
// drawn with (the cascade split stays the frame's), and new or resized maps are drawn outside
// the budget.
#include "core/MapUpdateSchedule.h"

#include <gtest/gtest.h>

using namespace penumbra;
using penumbra::core::LightKey;
using penumbra::core::MapUpdateSchedule;

namespace {

/// `views` views whose matrices say the frame they were made in; splits 10, 20, ...
LightFrusta frustaOfFrame(int frame, int views) {
  LightFrusta f;
  for (int v = 0; v < views; ++v) {
    ShadowView view;
    view.clipFromWorld[3][0] = static_cast<float>(frame);
    view.splitFarM = 10.0f * static_cast<float>(v + 1) + static_cast<float>(frame);
    f.views.push_back(view);
  }
  return f;
}

}  // namespace

TEST(MapUpdateSchedule, BudgetGoesRoundRobinAcrossLightsAndKeepsTheDrawnViews) {
  MapUpdateSchedule s;
  const MapUpdates budget{MapUpdates::Policy::Budget, 2};
  const std::vector<bool> shadowed = {true, true};
  // Light 0: 3 views, light 1: 1 view: 4 maps, 2 a frame.
  std::vector<std::vector<int>> drawnIn = {{0, 0, 0}, {0}};
  for (int frame = 0; frame < 5; ++frame) {
    s.beginFrame(budget, shadowed);
    int updated = 0;
    for (size_t l = 0; l < 2; ++l) {
      LightFrusta f = frustaOfFrame(frame, l == 0 ? 3 : 1);
      const std::vector<uint8_t> kept = s.apply(LightKey{0, l}, f, 512);
      for (size_t v = 0; v < f.views.size(); ++v) {
        if (!kept[v]) {
          drawnIn[l][v] = frame;
          ++updated;
        }
        EXPECT_EQ(f.views[v].clipFromWorld[3][0], static_cast<float>(drawnIn[l][v])) << "frame " << frame << " light " << l << " view " << v;
        EXPECT_EQ(f.views[v].splitFarM, 10.0f * static_cast<float>(v + 1) + static_cast<float>(frame)) << "the split is this frame's";
      }
    }
    EXPECT_EQ(updated, frame == 0 ? 4 : 2) << "frame " << frame;
  }
  // Frames 1..4 update (0,1), (2; light 1), (0,1), (2; light 1): each map waits one frame.
  EXPECT_EQ(drawnIn, (std::vector<std::vector<int>>{{3, 3, 4}, {4}}));
  EXPECT_EQ(s.kept(), 8u);
  EXPECT_EQ(s.maxStaleness(), 1);
  EXPECT_DOUBLE_EQ(s.meanStaleness(), 8.0 / 20.0);
}

TEST(MapUpdateSchedule, NewMapsAreDrawnOutsideTheBudgetAndOtherPoliciesKeepNothing) {
  MapUpdateSchedule s;
  const MapUpdates budget{MapUpdates::Policy::Budget, 1};
  s.beginFrame(budget, {true});
  LightFrusta f = frustaOfFrame(0, 4);
  EXPECT_EQ(s.apply(LightKey{0, 0}, f, 512), std::vector<uint8_t>(4, 0)) << "the first frame draws every map";
  s.beginFrame(budget, {true});
  f = frustaOfFrame(1, 4);
  EXPECT_EQ(s.apply(LightKey{0, 0}, f, 512), (std::vector<uint8_t>{0, 1, 1, 1}));
  s.beginFrame(budget, {true});
  f = frustaOfFrame(2, 4);
  EXPECT_EQ(s.apply(LightKey{0, 0}, f, 1024), std::vector<uint8_t>(4, 0)) << "a new map size: every map drawn";
  s.beginFrame(budget, {true});
  f = frustaOfFrame(3, 2);
  EXPECT_EQ(s.apply(LightKey{0, 0}, f, 1024), std::vector<uint8_t>(2, 0)) << "a new view count: every map drawn";
  for (const MapUpdates::Policy p : {MapUpdates::Policy::EveryFrame, MapUpdates::Policy::WhenInvalid}) {
    s.beginFrame({p}, {true});
    f = frustaOfFrame(4, 2);
    EXPECT_EQ(s.apply(LightKey{0, 0}, f, 1024), std::vector<uint8_t>(2, 0));
  }
}

// A light with a budget of its own is its own pool: light 0 (own budget 1, 2 maps), light 1
// (every frame, 1 map) and lights 2 and 3 (the shared budget of 1, 2 maps each). After the first
// frame, light 0 updates 1 of its 2 maps, light 1 its map, and lights 2 and 3 one map between them.
TEST(MapUpdateSchedule, LightsWithTheirOwnBudgetAreTheirOwnPool) {
  using Policy = MapUpdateSchedule::LightPolicy;
  MapUpdateSchedule s;
  const MapUpdates shared{MapUpdates::Policy::Budget, 1};
  const std::vector<Policy> lights = {{LightKey{0, 0}, true, {MapUpdates::Policy::Budget, 1}, true},
                                      {LightKey{0, 1}, true, {}, true},
                                      {LightKey{0, 2}, true, shared, false},
                                      {LightKey{0, 3}, true, shared, false}};
  const std::vector<int> views = {2, 1, 2, 2};
  for (int frame = 0; frame < 5; ++frame) {
    s.beginFrame(lights);
    std::vector<int> updated(lights.size(), 0);
    for (size_t l = 0; l < lights.size(); ++l) {
      LightFrusta f = frustaOfFrame(frame, views[l]);
      for (const uint8_t kept : s.apply(LightKey{0, l}, f, 256)) updated[l] += kept ? 0 : 1;
    }
    if (frame == 0) {
      EXPECT_EQ(updated, views);
      continue;
    }
    EXPECT_EQ(updated[0], 1) << "frame " << frame;
    EXPECT_EQ(updated[1], 1) << "frame " << frame;
    EXPECT_EQ(updated[2] + updated[3], 1) << "frame " << frame;
  }
  EXPECT_EQ(s.staleness(LightKey{0, 0}), 1);
  EXPECT_EQ(s.staleness(LightKey{0, 1}), 0);
  EXPECT_EQ(s.staleness(LightKey{0, 2}), 3) << "4 maps, 1 a frame";
}

// Lights are known by their key, not their place: two lights swapped between frames keep the
// views their maps were drawn with, their staleness and their turn in the budget; a light that
// leaves takes its maps with it.
TEST(MapUpdateSchedule, SwappedLightsKeepTheirOwnMaps) {
  using Policy = MapUpdateSchedule::LightPolicy;
  MapUpdateSchedule s;
  const MapUpdates budget{MapUpdates::Policy::Budget, 1};
  const LightKey a{7, 0}, b{9, 0};
  // A view made for light `key` in frame `frame`: its matrix says both.
  const auto viewOf = [](const LightKey& key, int frame) {
    LightFrusta f = frustaOfFrame(frame, 1);
    f.views[0].clipFromWorld[3][1] = static_cast<float>(key.id);
    return f;
  };
  const std::vector<Policy> ab = {{a, true, budget, false}, {b, true, budget, false}};
  const std::vector<Policy> ba = {{b, true, budget, false}, {a, true, budget, false}};
  s.beginFrame(ab);
  for (const LightKey& k : {a, b}) {
    LightFrusta f = viewOf(k, 0);
    EXPECT_EQ(s.apply(k, f, 256), std::vector<uint8_t>{0}) << "the first frame draws every map";
  }
  // Frame 1, the lights swapped: the budget updates one map (a's, first in the frame before); b's
  // stays as frame 0 drew it, with b's view, not a's.
  s.beginFrame(ba);
  LightFrusta fb = viewOf(b, 1), fa = viewOf(a, 1);
  const std::vector<uint8_t> keptB = s.apply(b, fb, 256), keptA = s.apply(a, fa, 256);
  EXPECT_EQ(keptB[0] + keptA[0], 1) << "one map of two updated";
  const LightFrusta& kept = keptB[0] ? fb : fa;
  const LightKey& keptKey = keptB[0] ? b : a;
  EXPECT_EQ(kept.views[0].clipFromWorld[3][1], static_cast<float>(keptKey.id)) << "the kept map's view is its own light's";
  EXPECT_EQ(kept.views[0].clipFromWorld[3][0], 0.0f) << "… as frame 0 drew it";
  EXPECT_EQ(s.staleness(keptKey), 1);
  // Light a leaves: its maps go with it; back, it draws them anew outside the budget.
  s.beginFrame(std::vector<Policy>{{b, true, budget, false}});
  LightFrusta f = viewOf(b, 2);
  s.apply(b, f, 256);
  EXPECT_EQ(s.staleness(a), 0) << "a's maps are forgotten";
  s.beginFrame(ab);
  f = viewOf(a, 3);
  EXPECT_EQ(s.apply(a, f, 256), std::vector<uint8_t>{0});
}
