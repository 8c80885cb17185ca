// `room` under its point lamp (light 0, a 5 cm sphere): world points the Embree reference puts in
// the lamp's umbra (the floor and the left wall beyond the table, where the table top hides the
// whole sphere) and in its full light (the table top, the floor before the lamp, the back wall)
// read the same V from every filter that must work with a point light: hard, pcf, pcss, vsm, msm.
// The probes lie well away from every shadow edge, so the tolerance is the filters' leak and
// over-darkening in a plain umbra and a plain lit area, not their penumbra shapes.
#include "GlFixture.h"
#include "ReferenceKnownAnswers.h"

#include <penumbra/Reference.h>
#include <penumbra/Shadows.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

using namespace penumbra;
using namespace penumbra::test;

namespace {

constexpr int kWidth = 96, kHeight = 54;  // the frame only sets the camera; the probes are world points
constexpr int kMapSize = 512;             // texels per cube face
constexpr int kReferenceSamples = 256;    // over the lamp's sphere
constexpr float kUmbraMaxV = 0.01f;       // the reference's umbra: the sphere hidden (sampling noise aside)
constexpr float kLitMinV = 0.99f;         // … and its full light
// V may differ from the reference by this much at the probes: 0.05 for the comparison filters
// (a small bias or a kernel's tail; measured: exact); 0.1 for the moment filters, whose Chebyshev
// and Hamburger bounds leak a little light into an umbra and darken a lit receiver near its own
// depth (measured at 512² maps: vsm leaks 0.004 onto the wall, msm reads 0.97 on the table top).
const std::map<std::string, float> kToleranceV = {{"hard", 0.05f}, {"pcf", 0.05f}, {"pcss", 0.05f}, {"vsm", 0.1f}, {"msm", 0.1f}};

struct Probe {
  const char* what;
  glm::vec3 wsPosition;
  glm::vec3 wsNormal;
  bool umbra;  ///< true: the table hides the lamp; false: the lamp is in full view
};

// The room (src/sceneio/LampScenes.cpp): the lamp at (0.7, 1.3, -0.7); the table's top, 5 cm thick
// with its upper face at 0.75 m, spans x in [-1.5, -0.1] and z in [-1.3, -0.5]; the left wall's
// face is x = -2.5, the back wall's z = -2.5.
const Probe kProbes[] = {
    {"floor beyond the table", {-2.0f, 0.0f, -0.9f}, {0, 1, 0}, true},
    {"floor beyond the table's middle", {-1.7f, 0.0f, -1.0f}, {0, 1, 0}, true},
    // The lamp hangs low: it lights the floor under the table's near half; under the far end,
    // between the legs, the top hides it.
    {"floor under the table's far end", {-1.4f, 0.0f, -0.9f}, {0, 1, 0}, true},
    {"left wall in the top's shadow", {-2.5f, 0.25f, -0.9f}, {1, 0, 0}, true},
    {"table top", {-0.8f, 0.75f, -0.9f}, {0, 1, 0}, false},
    {"floor before the lamp", {1.5f, 0.0f, 0.5f}, {0, 1, 0}, false},
    {"back wall above the table", {-0.5f, 1.2f, -2.5f}, {0, 0, 1}, false},
};

GBufferData probesGBuffer() {
  GBufferData g;
  g.width = static_cast<int>(std::size(kProbes));
  g.height = 1;
  for (const Probe& p : kProbes) {
    g.position.emplace_back(p.wsPosition, 1.0f);
    g.geoNormal.emplace_back(p.wsNormal, 0.0f);
    g.normal.emplace_back(p.wsNormal, 0.0f);
    g.albedo.emplace_back(1.0f);
  }
  return g;
}

}  // namespace

TEST(RoomScene, EveryFilterAgreesWithTheReferenceUnderThePointLamp) {
  const Scene room = makeBuiltinScene("room");
  ASSERT_EQ(room.lights.front().type, LightType::Point);
  const ReferenceResult ref = ReferenceTracer(room).trace(probesGBuffer(), room.lights.front(), quiet(kReferenceSamples));
  // The probes are what they claim to be: deep umbra or full light, by the reference.
  for (size_t i = 0; i < std::size(kProbes); ++i) {
    if (kProbes[i].umbra) EXPECT_LE(ref.visibility[i], kUmbraMaxV) << kProbes[i].what;
    else EXPECT_GE(ref.visibility[i], kLitMinV) << kProbes[i].what;
  }

  std::vector<SurfaceSample> points;
  for (const Probe& p : kProbes) points.push_back({p.wsPosition, p.wsNormal, {0, 0}});
  for (const auto& [filter, tolerance] : kToleranceV) {
    const auto renderer = makeTestRenderer(room, "uniform", filter, {}, kMapSize);
    renderer->render({.width = kWidth, .height = kHeight});
    ASSERT_EQ(renderer->lightCount(), room.lights.size()) << filter;
    const std::vector<float> v = renderer->visibilityAt(points, 0);
    ASSERT_EQ(v.size(), points.size()) << filter;
    for (size_t i = 0; i < v.size(); ++i) {
      std::printf("%-5s %-32s V %.3f  reference %.3f\n", filter.c_str(), kProbes[i].what, v[i], ref.visibility[i]);
      EXPECT_NEAR(v[i], ref.visibility[i], tolerance) << filter << ", " << kProbes[i].what;
    }
  }
}
