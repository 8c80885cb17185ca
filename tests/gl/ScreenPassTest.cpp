// The full-screen passes run as the fragment shader of a drawn triangle (frame/ScreenTarget.h),
// the same GLSL as the compute shader that evaluates a list of points (Shadows::visibilityAt):
// both stages must compute the same V, for every filter.
#include "GlFixture.h"

#include "techniques/Registry.h"
#include <penumbra/SceneIO.h>

#include <fmt/format.h>

#include <cmath>

using namespace penumbra;
using namespace penumbra::test;

namespace {

// Pixels whose drawn V and points-mode V differ by more than `tolerance`, over the covered pixels
// of one frame of `scene` with `filter`; `shadowed` counts the pixels below V = 0.5 (the frame
// must show shadows for the comparison to mean anything).
struct StageAgreement {
  size_t compared = 0, differ = 0, shadowed = 0;
  float worst = 0.0f;
};

StageAgreement drawnAgainstPoints(const Scene& scene, const std::string& projection, const std::string& filter) {
  auto r = makeTestRenderer(scene, projection, filter, {}, 512);
  r->render({.width = 96, .height = 64});
  const GBufferData g = r->readGBuffer();
  const std::vector<float> image = r->readVisibility();
  std::vector<SurfaceSample> points;
  std::vector<float> drawn;
  for (int y = 0; y < g.height; ++y)
    for (int x = 0; x < g.width; ++x) {
      const size_t i = static_cast<size_t>(y) * static_cast<size_t>(g.width) + static_cast<size_t>(x);
      if (!g.covered(i)) continue;
      points.push_back({glm::vec3(g.position[i]), glm::vec3(g.geoNormal[i]), {x, y}});
      drawn.push_back(image[i]);
    }
  const std::vector<float> computed = r->visibilityAt(points);
  StageAgreement a;
  a.compared = points.size();
  for (size_t i = 0; i < computed.size() && i < drawn.size(); ++i) {
    const float d = std::abs(computed[i] - drawn[i]);
    a.worst = std::max(a.worst, d);
    a.differ += d > 1e-5f ? 1 : 0;
    a.shadowed += drawn[i] < 0.5f ? 1 : 0;
  }
  if (computed.size() != drawn.size()) a.differ = a.compared;
  return a;
}

}  // namespace

// Every filter on boxes (a sun; one map, csm's cascades with their blend band, where the filter
// runs twice a pixel, and virtual's paged levels for the filters that read pages) and on pen (a spherical spot, contact-hardening): the drawn visibility pass
// and its compute twin agree to 1e-5 at every covered pixel.
TEST(ScreenPass, DrawnVisibilityEqualsTheComputeStageForEveryFilter) {
  const Scene boxes = makeBuiltinScene("boxes");
  const Scene pen = makeBuiltinScene("pen");
  const struct {
    const Scene* scene;
    const char* name;
    const char* projection;
  } views[] = {{&boxes, "boxes", "uniform"}, {&boxes, "boxes", "csm"}, {&boxes, "boxes", "virtual"}, {&pen, "pen", "uniform"}};
  for (const std::string& filter : filterIds())
    for (const auto& v : views) {
      if (!filterIncompatibility(filter, v.projection, v.scene->light()).empty()) continue;  // virtual's refused filters
      const StageAgreement a = drawnAgainstPoints(*v.scene, v.projection, filter);
      const std::string where = fmt::format("{} · {} on {}", filter, v.projection, v.name);
      ASSERT_GT(a.compared, 1000u) << where;
      EXPECT_GT(a.shadowed, 20u) << where;  // boxes at 96×64: 49–300 shadowed pixels
      EXPECT_EQ(a.differ, 0u) << where << ": worst |ΔV| " << a.worst;
    }
}
