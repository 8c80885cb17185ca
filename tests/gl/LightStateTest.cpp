// Each light's state (its maps, its map-update schedule, its filter instance) belongs to the
// light, found by its Light::id: lights swapped between frames under a map-update budget keep
// their own maps; a filter of the caller's runs for every light; lights that come and go leave
// GL objects and memory flat.
#include "GlFixture.h"

#include "core/ShadowsAccess.h"
#include "frame/FrameContext.h"
#include "gl/Objects.h"
#include "techniques/filters/HardFilter.h"

#include <penumbra/Shadows.h>
#include <penumbra/ShadowsDebug.h>

#include <algorithm>
#include <atomic>

using namespace penumbra;
using namespace penumbra::test;

namespace {

constexpr int kW = 128, kH = 72, kMap = 256;

/// room's two lamps (a point light and a spot), named 1 and 2.
Scene namedRoom() {
  Scene room = makeBuiltinScene("room");
  EXPECT_EQ(room.lights.size(), 2u);
  for (size_t i = 0; i < room.lights.size(); ++i) room.lights[i].id = i + 1;
  return room;
}

/// room with two spots instead: its own and a second one beside it, named 1 and 2. Both have
/// one map of one size, so a map kept for the wrong light would be read as its own.
Scene twoSpotRoom() {
  Scene room = namedRoom();
  const Light spot = room.lights[1];
  EXPECT_EQ(spot.type, LightType::Spot);
  Light second = spot;
  second.position += glm::vec3(-1.2f, 0.3f, 0.8f);
  second.id = 2;
  room.lights = {spot, second};
  room.lights[0].id = 1;
  return room;
}

size_t differing(const std::vector<float>& a, const std::vector<float>& b) {
  size_t n = 0;
  for (size_t i = 0; i < a.size(); ++i) n += a[i] != b[i] ? 1 : 0;
  return n;
}

}  // namespace

// Under a budget of one map a frame, the frames after the first update one of the two spots'
// maps and keep the other; with the lights swapped, each spot still reads its own map: its V is
// the first frame's, bit for bit (the scene stands still). Keyed by place, the spot now first
// would read the other's kept map.
TEST(LightState, SwappedLightsKeepTheirOwnMapsUnderABudget) {
  const Scene room = twoSpotRoom();
  auto r = makeTestRenderer(room, "uniform", "hard", {}, kMap);
  r->shadows().setMapUpdates({MapUpdates::Policy::Budget, 1});
  const RenderOptions o{.width = kW, .height = kH};
  r->render(o);
  const std::vector<float> first[2] = {r->readVisibility(0), r->readVisibility(1)};
  const LightFrusta firstViews[2] = {r->frusta(0), r->frusta(1)};
  std::vector<Light> swapped = {room.lights[1], room.lights[0]};
  for (int frame = 0; frame < 3; ++frame) {
    r->setCameraAndLights(room.camera, frame % 2 == 0 ? swapped : room.lights);
    r->render(o);
    const bool isSwapped = frame % 2 == 0;
    for (size_t layer = 0; layer < 2; ++layer) {
      const size_t light = isSwapped ? 1 - layer : layer;
      EXPECT_EQ(r->shadows().lightReports()[layer].id, light + 1);
      EXPECT_EQ(differing(r->readVisibility(layer), first[light]), 0u) << "frame " << frame + 1 << ", light " << light + 1;
      ASSERT_EQ(r->frusta(layer).views.size(), firstViews[light].views.size());
      for (size_t v = 0; v < firstViews[light].views.size(); ++v)
        EXPECT_EQ(r->frusta(layer).views[v].clipFromWorld, firstViews[light].views[v].clipFromWorld) << "light " << light + 1;
    }
    EXPECT_GT(r->shadows().lightReports()[0].keptMaps + r->shadows().lightReports()[1].keptMaps, 0) << "the budget kept maps";
  }
}

namespace {

// The hard filter under an id of the test's own, counting its instances: a filter an engine's
// tool adds to the registry.
std::atomic<int> gCountingFilters{0};

class CountingFilter final : public Filter {
public:
  CountingFilter() : Filter(filterParams("hard")) { ++gCountingFilters; }
  ~CountingFilter() override { --gCountingFilters; }
  std::string_view id() const override { return "test-counting-hard"; }
  std::string_view description() const override { return "the hard filter, counted"; }
  void renderShadowMaps(FrameContext& frame) override { mHard.renderShadowMaps(frame); }
  void computeVisibility(FrameContext& frame) override { mHard.computeVisibility(frame); }

private:
  HardFilter mHard;
};

}  // namespace

// A filter of the caller's, registered once, runs for every light (each its own instance, none
// remade by id into a built-in), and gives what the filter it wraps gives.
TEST(LightState, ACallersFilterRunsForEveryLight) {
  static const bool registered = [] {
    registerFilter([] { return std::make_unique<CountingFilter>(); });
    return true;
  }();
  ASSERT_TRUE(registered);
  EXPECT_THROW(registerFilter([] { return std::make_unique<CountingFilter>(); }), Error) << "an id is registered once";
  const Scene room = namedRoom();
  (void)Technique("uniform", "test-counting-hard");  // the registry's own instance (ids, parameters) exists from here
  const int before = gCountingFilters.load();
  auto counted = makeTestRenderer(room, "uniform", "test-counting-hard", {{"hard.bias", "normal"}}, kMap);
  auto plain = makeTestRenderer(room, "uniform", "hard", {{"hard.bias", "normal"}}, kMap);
  const RenderOptions o{.width = kW, .height = kH};
  counted->render(o);
  plain->render(o);
  EXPECT_EQ(gCountingFilters.load() - before, 2) << "one instance per light";
  for (size_t light = 0; light < 2; ++light) {
    EXPECT_EQ(filterOf(counted->shadows(), light).id(), "test-counting-hard");
    EXPECT_EQ(differing(counted->readVisibility(light), plain->readVisibility(light)), 0u) << "light " << light;
  }
  counted.reset();
  EXPECT_EQ(gCountingFilters.load(), before) << "the lights' instances go with the Shadows";
}

// Lights that come, go and change places, frame after frame: the first frames make what the
// lights need; after them no GL object and no byte of the technique's memory is added.
TEST(LightState, LightsComingAndGoingLeaveObjectsAndMemoryFlat) {
  const Scene room = namedRoom();
  auto r = makeTestRenderer(room, "uniform", "pcf", {}, kMap);
  const RenderOptions o{.width = kW, .height = kH};
  const std::vector<std::vector<Light>> orders = {room.lights, {room.lights[1], room.lights[0]}, {room.lights[1]}, room.lights};
  for (const auto& lights : orders) {  // each arrangement once: its storage is made
    r->setCameraAndLights(room.camera, lights);
    r->render(o);
  }
  const int objects = gl::liveObjectCount();
  const std::size_t bytes = r->shadows().techniqueMemoryBytes();
  constexpr int kFrames = 40;
  for (int f = 0; f < kFrames; ++f) {
    r->setCameraAndLights(room.camera, orders[static_cast<size_t>(f) % orders.size()]);
    r->render(o);
  }
  r->setCameraAndLights(room.camera, room.lights);
  r->render(o);
  EXPECT_EQ(gl::liveObjectCount(), objects);
  EXPECT_EQ(r->shadows().techniqueMemoryBytes(), bytes);
  std::printf("  %d frames of lights coming and going: %d GL objects, %.2f MiB of technique memory, before and after\n", kFrames,
              objects, static_cast<double>(bytes) / (1 << 20));
}
