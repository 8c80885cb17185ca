// The virtual projection (paged shadow maps, docs/virtual.md): a still camera and light draw no
// page after the first frame; a moving dynamic caster redraws only pages under where it was and
// is, and leaves no stale shadow; city's camera walk draws few of its resident pages a frame; a
// full pool is reported and coarser levels serve; filters that cannot read pages are refused.
#include "GlFixture.h"

#include <penumbra/Animation.h>
#include <penumbra/Error.h>
#include <penumbra/Metrics.h>
#include <penumbra/Reference.h>

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

using namespace penumbra;
using namespace penumbra::test;

namespace {

constexpr int kW = 160, kH = 96;
const RenderOptions kRender{.width = kW, .height = kH};
const MapUpdates kEvery{}, kWhenInvalid{MapUpdates::Policy::WhenInvalid};

std::unique_ptr<Renderer> virtualRenderer(const Scene& scene, const std::string& filter, const MapUpdates& updates, const Params& params = {}) {
  auto r = makeTestRenderer(scene, "virtual", filter, params);
  r->shadows().setMapUpdates(updates);
  return r;
}

const LightShadowReport::Pages& pages(Renderer& r) { return r.shadows().lightReports().front().pages; }

// Whether page (level, x, y) of a grid of pagesPerSide² pages meets the light's view of `world`
// (its box's rectangle in the level's map, unbounded along the light).
bool pageUnder(const LightFrusta& f, const glm::ivec3& page, const Aabb& world, int pagesPerSide) {
  const Aabb clip = world.transformed(f.views[static_cast<size_t>(page.x)].clipFromWorld);
  const auto at = [&](float c) { return (c * 0.5f + 0.5f) * static_cast<float>(pagesPerSide); };
  return at(clip.lo.x) <= static_cast<float>(page.y + 1) && at(clip.hi.x) >= static_cast<float>(page.y) &&
         at(clip.lo.y) <= static_cast<float>(page.z + 1) && at(clip.hi.y) >= static_cast<float>(page.z);
}

// The index of the object named `name` (objects.size() when there is none).
size_t objectNamed(const Scene& s, const std::string& name) {
  return static_cast<size_t>(std::find_if(s.objects.begin(), s.objects.end(), [&](const Object& o) { return o.name == name; }) -
                             s.objects.begin());
}

Aabb objectBounds(const Scene& s, size_t i) { return s.meshes[s.objects[i].mesh].bounds().transformed(s.objects[i].worldFromObject); }

}  // namespace

TEST(Virtual, StillCameraAndLightDrawNoPageAfterTheFirstFrame) {
  Scene boxes = makeBuiltinScene("boxes");
  boxes.animation = {};
  for (const MapUpdates& updates : {kEvery, kWhenInvalid}) {
    auto r = virtualRenderer(boxes, "hard", updates);
    r->render(kRender);
    const LightShadowReport::Pages first = pages(*r);
    std::printf("%s: first frame %d pages needed, %d drawn, %d resident (pool %d, %.1f MiB)\n", mapUpdatesName(updates).c_str(),
                first.needed, first.drawn, first.resident, first.poolPages, static_cast<double>(first.poolBytes) / 1048576.0);
    EXPECT_GT(first.needed, 0);
    EXPECT_EQ(first.drawn, first.needed);
    EXPECT_EQ(first.missing, 0);
    const std::vector<float> v = r->readVisibility();
    for (int f = 1; f < 3; ++f) {
      r->render(kRender);
      EXPECT_EQ(pages(*r).drawn, 0) << "frame " << f;
      EXPECT_EQ(pages(*r).needed, first.needed) << "frame " << f;
      EXPECT_EQ(pages(*r).resident, first.resident) << "frame " << f;
      EXPECT_EQ(r->readVisibility(), v) << "frame " << f;
    }
  }
}

// boxes' rolling ball (dynamic) under a still sun and a still camera: each frame after the first
// draws at least one page and no more than the pages under the ball's bounds then and now, and
// the frame's V is a fresh render's bit for bit (no stale shadow, no page missed).
TEST(Virtual, MovingDynamicCasterRedrawsOnlyThePagesItTouches) {
  Scene boxes = makeBuiltinScene("boxes");
  boxes.animation.suns.clear();
  const size_t ball = objectNamed(boxes, "sphere A");
  ASSERT_LT(ball, boxes.objects.size()) << "boxes' rolling ball";
  for (const MapUpdates& updates : {kEvery, kWhenInvalid}) {
    auto r = virtualRenderer(boxes, "pcf", updates);
    Aabb before;
    for (const float t : {0.0f, 0.5f, 1.0f, 1.5f}) {
      Scene posed = boxes;
      poseScene(posed, t);
      r->setPose(posed);
      r->render(kRender);
      const Aabb now = objectBounds(posed, ball);
      const LightShadowReport::Pages p = pages(*r);
      if (t > 0.0f) {
        Aabb both = before;
        both.extend(now);
        int under = 0;
        for (const glm::ivec3& page : ShadowsAccess::pages(r->shadows(), 0)->drawnPages())
          under += pageUnder(r->frusta(), page, both, 16384 / 128) ? 1 : 0;
        std::printf("%s, t = %g s: %d pages drawn of %d resident, %d of them under the ball's bounds then and now\n",
                    mapUpdatesName(updates).c_str(), t, p.drawn, p.resident, under);
        EXPECT_GT(p.drawn, 0) << "t = " << t;
        EXPECT_EQ(under, p.drawn) << "t = " << t << ": a page the ball did not touch was drawn";
      }
      auto fresh = virtualRenderer(posed, "pcf", updates);
      fresh->render(kRender);
      EXPECT_EQ(r->readVisibility(), fresh->readVisibility()) << mapUpdatesName(updates) << ", t = " << t;
      before = now;
    }
  }
}

// A dynamic caster that moves where no page this frame needs lies draws nothing (3 km off: beyond
// even the coarsest level's pages that hold what the camera sees, 256 m wide).
TEST(Virtual, DynamicCasterMovingOutOfSightDrawsNoPage) {
  Scene boxes = makeBuiltinScene("boxes");
  boxes.animation = {};
  const size_t ball = objectNamed(boxes, "sphere A");
  ASSERT_LT(ball, boxes.objects.size());
  boxes.objects[ball].dynamic = true;
  boxes.objects[ball].worldFromObject = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.5f, 3000.0f));  // far behind the camera
  for (const MapUpdates& updates : {kEvery, kWhenInvalid}) {
    auto r = virtualRenderer(boxes, "hard", updates);
    r->render(kRender);
    Scene moved = boxes;
    moved.objects[ball].worldFromObject = glm::translate(glm::mat4(1.0f), glm::vec3(3.0f, 0.5f, 3000.0f));
    r->setPose(moved);
    r->render(kRender);
    EXPECT_EQ(pages(*r).drawn, 0) << mapUpdatesName(updates);
  }
}

// city's camera walk (the scene's own animation: the camera walks down the avenue at 1.4 m/s,
// a van drives by) at 30 frames a second: after the first frame, each frame draws at most 10 % of
// the pages it keeps.
TEST(Virtual, CityWalkDrawsAFewOfItsResidentPagesAFrame) {
  constexpr double kMaxDrawnShare = 0.10;
  const Scene city = makeBuiltinScene("city");
  auto r = virtualRenderer(city, "hard", kWhenInvalid);
  double worst = 0.0;
  for (int f = 0; f < 5; ++f) {
    Scene posed = city;
    poseScene(posed, static_cast<float>(f) / 30.0f);
    r->setPose(posed);
    r->render(kRender);
    const LightShadowReport::Pages p = pages(*r);
    std::printf("frame %d: %d needed, %d drawn, %d resident, %d missing\n", f, p.needed, p.drawn, p.resident, p.missing);
    EXPECT_EQ(p.missing, 0);
    if (f > 0) worst = std::max(worst, static_cast<double>(p.drawn) / static_cast<double>(p.resident));
  }
  EXPECT_LE(worst, kMaxDrawnShare);
}

// A pool too small for the frame's pages: the run says how many it could not take, coarser
// levels serve them, and V stays close to the full pool's.
TEST(Virtual, FullPoolIsReportedAndCoarserLevelsServe) {
  Scene boxes = makeBuiltinScene("boxes");
  boxes.animation = {};
  auto full = virtualRenderer(boxes, "hard", kEvery);
  full->render(kRender);
  const int needed = pages(*full).needed;
  const int pool = std::max(16, needed / 2);
  auto small = virtualRenderer(boxes, "hard", kEvery, {{"virtual.poolPages", std::to_string(pool)}});
  small->render(kRender);
  const LightShadowReport::Pages p = pages(*small);
  std::printf("%d pages needed, pool of %d: %d missing\n", needed, pool, p.missing);
  EXPECT_EQ(p.missing, needed - pool);
  EXPECT_EQ(p.resident, pool);
  const GBufferData g = full->readGBuffer();
  size_t differ = 0, covered = 0;
  const std::vector<float> a = full->readVisibility(), b = small->readVisibility();
  for (size_t i = 0; i < a.size(); ++i) {
    if (!g.covered(i)) continue;
    ++covered;
    differ += std::abs(a[i] - b[i]) > 0.5f ? 1 : 0;
  }
  std::printf("%zu of %zu pixels differ by > 0.5\n", differ, covered);
  EXPECT_LT(static_cast<double>(differ), 0.05 * static_cast<double>(covered));
}

// A spot light is one perspective view in mips, a point light six (its cube's faces): the first
// frame draws every needed page, the second none with V bit-identical, and away from edges V
// equals the uniform map's (hard: the same test at another resolution).
void expectPagedViewsReadTheUniformMapsShadows(const Scene& scene, int width, int height, size_t minShadowed) {
  const RenderOptions render{.width = width, .height = height};
  auto v = virtualRenderer(scene, "hard", kEvery);
  v->render(render);
  const LightShadowReport::Pages first = pages(*v);
  std::printf("%s, first frame: %d pages needed, %d drawn, %d views\n", scene.name.c_str(), first.needed, first.drawn,
              static_cast<int>(v->frusta().views.size()));
  EXPECT_GT(first.needed, 0);
  EXPECT_EQ(first.drawn, first.needed);
  EXPECT_EQ(first.missing, 0);
  const std::vector<float> a = v->readVisibility();
  v->render(render);
  EXPECT_EQ(pages(*v).drawn, 0);
  EXPECT_EQ(pages(*v).needed, first.needed);
  EXPECT_EQ(v->readVisibility(), a);

  auto u = makeTestRenderer(scene, "uniform", "hard");
  u->render(render);
  const std::vector<float> b = u->readVisibility();
  const GBufferData g = u->readGBuffer();
  // Away from edges: covered pixels whose 3×3 neighbourhood in the uniform map's V is all lit or
  // all shadowed alike.
  constexpr int kR = 1;
  size_t interior = 0, differ = 0, shadowed = 0;
  for (int y = kR; y < height - kR; ++y)
    for (int x = kR; x < width - kR; ++x) {
      const size_t i = static_cast<size_t>(y) * static_cast<size_t>(width) + static_cast<size_t>(x);
      bool flat = true;
      for (int dy = -kR; dy <= kR && flat; ++dy)
        for (int dx = -kR; dx <= kR && flat; ++dx) {
          const size_t j = static_cast<size_t>(y + dy) * static_cast<size_t>(width) + static_cast<size_t>(x + dx);
          flat = g.covered(j) && std::abs(b[j] - b[i]) < 1e-3f;
        }
      if (!flat) continue;
      ++interior;
      shadowed += b[i] < 0.5f ? 1 : 0;
      differ += std::abs(a[i] - b[i]) > 0.5f ? 1 : 0;
    }
  std::printf("%zu of %zu pixels away from edges differ by > 0.5 (%zu of them in shadow)\n", differ, interior, shadowed);
  EXPECT_GE(shadowed, minShadowed);
  EXPECT_LE(differ, 0u);
}

TEST(Virtual, SpotIsOneViewInMipsAndReadsTheUniformMapsShadows) {
  Scene pen = makeBuiltinScene("pen");
  pen.animation = {};
  ASSERT_EQ(pen.light().type, LightType::Spot);
  // Twice the other tests' size: pen's shadow is a few pixels wide at 160×96, all of it edge.
  expectPagedViewsReadTheUniformMapsShadows(pen, 2 * kW, 2 * kH, 50);
}

// room's lamp alone (its point light; the spot beside it is the test above's kind).
Scene roomLamp() {
  Scene room = makeBuiltinScene("room");
  room.animation = {};
  room.lights.resize(1);
  return room;
}

TEST(Virtual, PointLightIsSixFacesInMipsAndReadsTheUniformMapsShadows) {
  const Scene room = roomLamp();
  ASSERT_EQ(room.light().type, LightType::Point);
  expectPagedViewsReadTheUniformMapsShadows(room, kW, kH, 500);
}

// A perspective view's page is a sub-frustum: `object`, declared dynamic and moved 5 cm along x,
// redraws only pages whose uv rectangle meets its box's projection then or now, and V equals a
// fresh renderer's bit for bit.
void expectPagesRedrawOnlyUnderAMovedDynamicCaster(Scene scene, const std::string& object) {
  const size_t caster = objectNamed(scene, object);
  ASSERT_LT(caster, scene.objects.size());
  scene.objects[caster].dynamic = true;
  const int pagesPerSide = 16384 / 128;
  // Whether page (view, x, y) meets the projection of `world`'s corners (all in front of the light).
  const auto under = [&](const LightFrusta& f, const glm::ivec3& page, const Aabb& world) {
    const glm::mat4& m = f.views[static_cast<size_t>(page.x)].clipFromWorld;
    glm::vec2 lo(1e30f), hi(-1e30f);
    for (const glm::vec3& c : world.corners()) {
      const glm::vec4 clip = m * glm::vec4(c, 1.0f);
      if (clip.w <= 0.0f) return true;
      const glm::vec2 at = (glm::vec2(clip) / clip.w * 0.5f + 0.5f) * static_cast<float>(pagesPerSide);
      lo = glm::min(lo, at);
      hi = glm::max(hi, at);
    }
    return lo.x <= static_cast<float>(page.y + 1) && hi.x >= static_cast<float>(page.y) && lo.y <= static_cast<float>(page.z + 1) &&
           hi.y >= static_cast<float>(page.z);
  };
  for (const MapUpdates& updates : {kEvery, kWhenInvalid}) {
    auto r = virtualRenderer(scene, "hard", updates);
    r->render(kRender);
    const int resident = pages(*r).resident;
    Scene moved = scene;
    moved.objects[caster].worldFromObject =
        glm::translate(glm::mat4(1.0f), glm::vec3(0.05f, 0.0f, 0.0f)) * scene.objects[caster].worldFromObject;
    r->setPose(moved);
    r->render(kRender);
    Aabb both = objectBounds(scene, caster);
    both.extend(objectBounds(moved, caster));
    int inside = 0;
    const std::vector<glm::ivec3>& drawn = ShadowsAccess::pages(r->shadows(), 0)->drawnPages();
    for (const glm::ivec3& page : drawn) inside += under(r->frusta(), page, both) ? 1 : 0;
    std::printf("%s, %s: %d pages drawn of %d resident, %d of them under the %s's box then and now\n", scene.name.c_str(),
                mapUpdatesName(updates).c_str(), pages(*r).drawn, resident, inside, object.c_str());
    EXPECT_GT(pages(*r).drawn, 0);
    EXPECT_LT(pages(*r).drawn, resident);
    EXPECT_EQ(inside, pages(*r).drawn);
    auto fresh = virtualRenderer(moved, "hard", updates);
    fresh->render(kRender);
    EXPECT_EQ(r->readVisibility(), fresh->readVisibility()) << mapUpdatesName(updates);
  }
}

TEST(Virtual, SpotPagesRedrawOnlyUnderAMovedDynamicCaster) {
  Scene pen = makeBuiltinScene("pen");
  pen.animation = {};
  expectPagesRedrawOnlyUnderAMovedDynamicCaster(pen, "pencil");
}

TEST(Virtual, PointLightPagesRedrawOnlyUnderAMovedDynamicCaster) { expectPagesRedrawOnlyUnderAMovedDynamicCaster(roomLamp(), "chair back"); }

TEST(Virtual, RefusesFiltersThatCannotReadPagesAndPagesEveryLight) {
  Scene boxes = makeBuiltinScene("boxes");
  for (const char* filter : {"vsm", "msm", "esm", "vssm", "sdf", "second-depth"}) {
    const std::string why = filterIncompatibility(filter, "virtual", boxes.light());
    EXPECT_NE(why.find("paged"), std::string::npos) << filter << ": " << why;
  }
  for (const char* filter : {"hard", "pcf", "pcss", "smrt"}) EXPECT_EQ(filterIncompatibility(filter, "virtual", boxes.light()), "") << filter;
  for (const char* scene : {"boxes", "pen", "room"}) EXPECT_EQ(projectionIncompatibility("virtual", makeBuiltinScene(scene).light()), "") << scene;
}

// pcss's blocker search and smrt's march are bounded by the nearest surface over the light's
// footprint, read from the pool's min-depth pyramid page by page (common/shadow.glsl:
// pagedMinDepthOverBox). On city, where the sun's near plane lies far above the street, the
// unbounded search (pcss.tightSearch off: the near plane's footprint) loses the small blockers in
// its wide region and smrt marches to the near plane in steps too long for the poles. Measured at
// 160x96 (64 samples): pcss 0.0361 bounded, 0.0944 not; smrt 0.0372 (with the bound taken as the
// near plane: pcss 0.0944, smrt 0.0458).
TEST(Virtual, SoftFiltersBoundTheirSearchWithThePagesMinDepth) {
  const Scene city = makeBuiltinScene("city");
  ReferenceOptions o;
  o.samples = 64;
  o.progress = false;
  auto rmse = [&](const std::string& filter, const Params& params) {
    const RenderResult r = renderScene(city, "virtual", filter, params, kW, kH, 2048);
    const ReferenceResult ref = ReferenceTracer(city).trace(r.gbuffer, city.light(), o);
    const double e = compareVisibility(r.visibility, ref.visibility, ref.litMask, kW).rmse;
    std::printf("virtual x %s%s: RMSE %.4f\n", filter.c_str(), params.empty() ? "" : " (search unbounded)", e);
    return e;
  };
  const double pcss = rmse("pcss", {}), unbounded = rmse("pcss", {{"pcss.tightSearch", "off"}}), smrt = rmse("smrt", {});
  EXPECT_LT(pcss, 0.5 * unbounded);
  EXPECT_LT(pcss, 0.042);
  EXPECT_LT(smrt, 0.042);
}

// Where the camera grazes the street far off, the poles' shadows span a pixel or two across: a
// level finer there (virtual.grazingLevels) resolves them, a texel as wide as the pixel breaks
// them into dashes.
TEST(Virtual, GrazingLevelsResolveThinShadowsFarOff) {
  const Scene city = makeBuiltinScene("city");
  ReferenceOptions o;
  o.samples = 64;
  o.progress = false;
  const RenderResult fine = renderScene(city, "virtual", "smrt", {}, kW, kH, 2048);
  const RenderResult flat = renderScene(city, "virtual", "smrt", {{"virtual.grazingLevels", "0"}}, kW, kH, 2048);
  const ReferenceResult ref = ReferenceTracer(city).trace(fine.gbuffer, city.light(), o);
  const double withLevels = compareVisibility(fine.visibility, ref.visibility, ref.litMask, kW).rmse;
  const double without = compareVisibility(flat.visibility, ref.visibility, ref.litMask, kW).rmse;
  std::printf("virtual x smrt: RMSE %.4f with grazing levels, %.4f without\n", withLevels, without);
  EXPECT_LT(withLevels, 0.8 * without);
}
