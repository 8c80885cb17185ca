// The map update schedule without GL: a budget of N maps a frame updates the least recently
// updated maps across lights (round-robin), a kept map's view in the frusta is the one it was
// drawn with (the cascade split stays the frame's), and new or resized maps are drawn outside
// the budget.
#include "core/MapUpdateSchedule.h"

#include <gtest/gtest.h>

using namespace penumbra;
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
      const std::vector<uint8_t> kept = s.apply(l, f, 512);
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
  EXPECT_EQ(s.apply(0, f, 512), std::vector<uint8_t>(4, 0)) << "the first frame draws every map";
  s.beginFrame(budget, {true});
  f = frustaOfFrame(1, 4);
  EXPECT_EQ(s.apply(0, f, 512), (std::vector<uint8_t>{0, 1, 1, 1}));
  s.beginFrame(budget, {true});
  f = frustaOfFrame(2, 4);
  EXPECT_EQ(s.apply(0, f, 1024), std::vector<uint8_t>(4, 0)) << "a new map size: every map drawn";
  s.beginFrame(budget, {true});
  f = frustaOfFrame(3, 2);
  EXPECT_EQ(s.apply(0, f, 1024), std::vector<uint8_t>(2, 0)) << "a new view count: every map drawn";
  for (const MapUpdates::Policy p : {MapUpdates::Policy::EveryFrame, MapUpdates::Policy::WhenInvalid}) {
    s.beginFrame({p}, {true});
    f = frustaOfFrame(4, 2);
    EXPECT_EQ(s.apply(0, f, 1024), std::vector<uint8_t>(2, 0));
  }
}

// A light with a budget of its own is its own pool: light 0 (own budget 1, 2 maps), light 1
// (every frame, 1 map) and lights 2 and 3 (the shared budget of 1, 2 maps each). After the first
// frame, light 0 updates 1 of its 2 maps, light 1 its map, and lights 2 and 3 one map between them.
TEST(MapUpdateSchedule, LightsWithTheirOwnBudgetAreTheirOwnPool) {
  using Policy = MapUpdateSchedule::LightPolicy;
  MapUpdateSchedule s;
  const MapUpdates shared{MapUpdates::Policy::Budget, 1};
  const std::vector<Policy> lights = {{true, {MapUpdates::Policy::Budget, 1}, true},
                                      {true, {}, true},
                                      {true, shared, false},
                                      {true, shared, false}};
  const std::vector<int> views = {2, 1, 2, 2};
  for (int frame = 0; frame < 5; ++frame) {
    s.beginFrame(lights);
    std::vector<int> updated(lights.size(), 0);
    for (size_t l = 0; l < lights.size(); ++l) {
      LightFrusta f = frustaOfFrame(frame, views[l]);
      for (const uint8_t kept : s.apply(l, f, 256)) updated[l] += kept ? 0 : 1;
    }
    if (frame == 0) {
      EXPECT_EQ(updated, views);
      continue;
    }
    EXPECT_EQ(updated[0], 1) << "frame " << frame;
    EXPECT_EQ(updated[1], 1) << "frame " << frame;
    EXPECT_EQ(updated[2] + updated[3], 1) << "frame " << frame;
  }
  EXPECT_EQ(s.staleness(0), 1);
  EXPECT_EQ(s.staleness(1), 0);
  EXPECT_EQ(s.staleness(2), 3) << "4 maps, 1 a frame";
}
