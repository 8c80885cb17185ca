// The "blocker-depth" and "penumbra-width-m" debug images of pcss and vssm (shared/
// PenumbraDebug.h) on `pen`: in the umbra the blocker is closer to the light than the receiver;
// floor whose blocker search cannot reach the pencil carries the "none" sentinel; the penumbra is narrower near
// the pencil's contact with the floor than far from it; the images follow the screen size
// without creating GL objects per frame.
#include "GlFixture.h"

#include "gl/Objects.h"
#include "shared/PenumbraDebug.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <string>

using namespace penumbra;
using namespace penumbra::test;

namespace {

constexpr int kWidth = 400, kHeight = 225;
constexpr int kMapSize = 1024;
constexpr float kFloorEpsM = 1e-3f;    // G-buffer positions on the floor have y ≈ 0
constexpr float kUmbraV = 0.05f;       // V below this: the whole light is hidden
constexpr float kNearContactM = 0.15f;  // "near the contact": floor within this of the tip
constexpr float kFarFromTipM = 0.6f;    // "far": the shadow of the pencil's upper half
constexpr float kAreaM = 1.5f;          // floor considered: within this of the tip (well inside the spot)

struct Frame {
  std::vector<float> visibility, blockerDepth, widthM;
  GBufferData g;
  LightFrusta frusta;
};

std::vector<float> readR32F(const gl::Texture& t) {
  std::vector<float> v(static_cast<size_t>(t.width()) * static_cast<size_t>(t.height()));
  t.read(GL_RED, GL_FLOAT, v.data(), v.size() * sizeof(float));
  return v;
}

const gl::Texture* findImage(const Renderer& r, const std::string& name) {
  for (const DebugImage& d : r.debugImages())
    if (d.name == name) return d.texture;
  return nullptr;
}

Frame renderPen(const std::string& filter) {
  const std::unique_ptr<Renderer> owned = makeTestRenderer(makeBuiltinScene("pen"), "uniform", filter, {}, kMapSize);
  Renderer& renderer = *owned;
  RenderOptions o;
  o.width = kWidth;
  o.height = kHeight;
  renderer.render(o);
  Frame f;
  const gl::Texture* depth = findImage(renderer, "blocker-depth");
  const gl::Texture* width = findImage(renderer, "penumbra-width-m");
  EXPECT_NE(depth, nullptr);
  EXPECT_NE(width, nullptr);
  if (!depth || !width) return f;
  EXPECT_EQ(depth->width(), kWidth);
  EXPECT_EQ(depth->height(), kHeight);
  f.visibility = renderer.readVisibility();
  f.blockerDepth = readR32F(*depth);
  f.widthM = readR32F(*width);
  f.g = renderer.readGBuffer();
  f.frusta = renderer.frusta();
  return f;
}

float median(std::vector<float> v) {
  if (v.empty()) return std::nanf("");
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2), v.end());
  return v[v.size() / 2];
}

// Map uv of world point p in a perspective view.
glm::vec2 mapUv(const ShadowView& v, const glm::vec3& p) {
  const glm::vec4 c = v.clipFromWorld * glm::vec4(p, 1.0f);
  return glm::vec2(c) / c.w * 0.5f + 0.5f;
}

float distanceToSegment(glm::vec2 p, glm::vec2 a, glm::vec2 b) {
  const glm::vec2 ab = b - a;
  const float t = std::clamp(glm::dot(p - a, ab) / glm::dot(ab, ab), 0.0f, 1.0f);
  return glm::length(p - (a + t * ab));
}

// True if no texel of the pencil can lie in the blocker search region of floor point p: the
// pencil's axis, projected into the map, is farther from p's uv than the search box's corner
// (common/penumbra.glsl's blockerSearchRadiusUv, clamped to maxRadiusTexels) plus the pencil's
// radius and a margin. Such a receiver must carry the sentinel.
bool outOfSearchReach(const Scene& scene, const ShadowView& v, const glm::vec3& p, float maxRadiusTexels) {
  constexpr float kPencilRadiusM = 0.04f, kPencilLengthM = 1.62f, kLeanRad = 0.45f;  // BuiltinScenes.cpp makePen
  constexpr float kMarginUv = 0.01f;
  const glm::vec3 top = glm::vec3(-std::cos(kLeanRad), std::sin(kLeanRad), 0.0f) * kPencilLengthM;
  const float depth = glm::dot(v.depthPlane, glm::vec4(p, 1.0f));
  const float receiverM = v.nearM + depth * (v.farM - v.nearM);
  const float searchM = scene.light().size * (receiverM - v.nearM) / receiverM;  // footprint on the near plane
  const float searchUv = std::min(searchM / (v.extent.x * v.nearM), maxRadiusTexels / static_cast<float>(kMapSize));
  const float pencilUv = kPencilRadiusM / (v.extent.x * v.nearM);  // its widest: at the near plane
  return distanceToSegment(mapUv(v, p), mapUv(v, glm::vec3(0.0f)), mapUv(v, top)) >
         std::sqrt(2.0f) * searchUv + pencilUv + kMarginUv;
}

void checkPen(const std::string& filter, double maxSpuriousFraction) {
  const float maxRadiusTexels = Technique("uniform", filter).get(filter + ".maxRadiusTexels");
  const Scene scene = makeBuiltinScene("pen");
  const Frame f = renderPen(filter);
  ASSERT_FALSE(f.blockerDepth.empty());
  ASSERT_EQ(f.frusta.views.size(), 1u);
  const glm::vec4 depthPlane = f.frusta.views[0].depthPlane;

  size_t umbra = 0, umbraBad = 0, open = 0, openSentinel = 0, notFinite = 0;
  std::vector<float> nearW, farW;
  double worstGap = 1.0;
  for (size_t i = 0; i < f.visibility.size(); ++i) {
    notFinite += !std::isfinite(f.blockerDepth[i]) || !std::isfinite(f.widthM[i]);
    if (!f.g.covered(i)) {
      EXPECT_EQ(f.blockerDepth[i], PN_PENUMBRA_DEBUG_NONE) << "pixel " << i << " has no geometry";
      continue;
    }
    const glm::vec3 p(f.g.position[i]);
    if (std::abs(p.y) > kFloorEpsM || glm::length(glm::vec2(p.x, p.z)) > kAreaM) continue;
    const float receiverDepth = glm::dot(depthPlane, glm::vec4(p, 1.0f));
    const float blocker = f.blockerDepth[i], width = f.widthM[i];
    const bool found = blocker >= 0.0f;
    if (found) EXPECT_GE(width, 0.0f);
    else EXPECT_EQ(width, PN_PENUMBRA_DEBUG_NONE);
    if (f.visibility[i] < kUmbraV) {
      ++umbra;
      if (!found || blocker >= receiverDepth) ++umbraBad;
      else worstGap = std::min(worstGap, static_cast<double>(receiverDepth - blocker));
      if (found) {
        const float fromTipM = glm::length(p);
        if (fromTipM < kNearContactM) nearW.push_back(width);
        if (fromTipM > kFarFromTipM) farW.push_back(width);
      }
    } else if (outOfSearchReach(scene, f.frusta.views[0], p, maxRadiusTexels)) {
      ++open;
      openSentinel += !found;
    }
  }
  const float nearMedian = median(nearW), farMedian = median(farW);
  std::printf("%s: %zu umbra floor pixels (%zu without a closer blocker, smallest depth gap %.4f); %zu floor pixels "
              "out of the search's reach (%zu with the sentinel); penumbra width median %.4f m within %.2f m of the tip "
              "(%zu px), %.4f m beyond %.2f m (%zu px)\n",
              filter.c_str(), umbra, umbraBad, worstGap, open, openSentinel, nearMedian, kNearContactM, nearW.size(),
              farMedian, kFarFromTipM, farW.size());
  EXPECT_EQ(notFinite, 0u);
  EXPECT_GT(umbra, 300u);
  EXPECT_EQ(umbraBad, 0u);
  EXPECT_GT(open, 5000u);
  EXPECT_GE(static_cast<double>(openSentinel), (1.0 - maxSpuriousFraction) * static_cast<double>(open));
  ASSERT_GT(nearW.size(), 10u);
  ASSERT_GT(farW.size(), 50u);
  EXPECT_LT(nearMedian, 0.5f * farMedian);
}

}  // namespace

TEST(PenumbraDebugView, PcssBlockerDepthAndPenumbraWidthOnPen) { checkPen("pcss", 0.0); }

// vssm may see a blocker where there is none: Chebyshev's bound over a region that mixes
// depths (the floor's slope across the search box) falls below kUnoccludedLit (vssm.glsl).
TEST(PenumbraDebugView, VssmBlockerDepthAndPenumbraWidthOnPen) { checkPen("vssm", 0.01); }

// The images follow the screen size; frames at one size create no GL object.
TEST(PenumbraDebugView, ImagesFollowResizeWithoutGlObjectGrowth) {
  for (const std::string filter : {"pcss", "vssm"}) {
    const std::unique_ptr<Renderer> owned = makeTestRenderer(makeBuiltinScene("pen"), "uniform", filter, {}, 256);
    Renderer& renderer = *owned;
    RenderOptions o;
    o.width = 96;
    o.height = 64;
    renderer.render(o);
    const int afterFirst = gl::liveObjectCount();
    for (int i = 0; i < 3; ++i) renderer.render(o);
    EXPECT_EQ(gl::liveObjectCount(), afterFirst) << filter;
    o.width = 80;
    o.height = 48;
    renderer.render(o);
    renderer.render(o);
    EXPECT_EQ(gl::liveObjectCount(), afterFirst) << filter << ": a resize replaces the images, it adds none";
    for (const char* name : {"blocker-depth", "penumbra-width-m"}) {
      const gl::Texture* t = findImage(renderer, name);
      ASSERT_NE(t, nullptr) << filter << " " << name;
      EXPECT_EQ(t->width(), 80) << filter << " " << name;
      EXPECT_EQ(t->height(), 48) << filter << " " << name;
    }
  }
}
