// The renderer's G-buffer: background pixels hold the documented background values in every
// attachment on every frame (they are drawn, not cleared), and the triangle ids are recorded
// only when a frame asks for them, without changing anything else.
#include "GlFixture.h"
#include "gl/Debug.h"
#include "gl/Draw.h"

#include <penumbra/Scene.h>

#include <gtest/gtest.h>

namespace penumbra::test {
namespace {

constexpr int kW = 160, kH = 90, kMap = 256;

RenderOptions frame(bool triangleIds) {
  return {.width = kW, .height = kH, .triangleIds = triangleIds};
}

size_t coveredPixels(const GBufferData& g) {
  size_t n = 0;
  for (size_t i = 0; i < g.position.size(); ++i) n += g.covered(i) ? 1 : 0;
  return n;
}

void expectSameSurfaces(const GBufferData& a, const GBufferData& b) {
  ASSERT_EQ(a.position.size(), b.position.size());
  size_t differ = 0;
  for (size_t i = 0; i < a.position.size(); ++i)
    differ += a.position[i] != b.position[i] || a.normal[i] != b.normal[i] || a.geoNormal[i] != b.geoNormal[i] ||
                      a.albedo[i] != b.albedo[i]
                  ? 1
                  : 0;
  EXPECT_EQ(differ, 0u) << "pixels whose position, normals or albedo differ";
}

}  // namespace

// A frame that sees sky where the frame before saw ground reads exactly what a first frame
// reads: zero in every attachment (position.w = 0 marks background), triangle id 0.
TEST(GBuffer, BackgroundIsWrittenEveryFrame) {
  const Scene scene = makeBuiltinScene("boxes");
  Scene down = scene;
  down.camera.position = {0.0f, 3.0f, 0.5f};  // steeply down at the ground: no sky in view
  down.camera.target = {0.0f, 0.0f, 0.0f};

  const auto reused = makeTestRenderer(scene, "uniform", "hard", {}, kMap);
  reused->setCameraAndLights(down.camera, down.lights);
  reused->render(frame(true));
  const GBufferData before = reused->readGBuffer();
  reused->setCameraAndLights(scene.camera, scene.lights);
  reused->render(frame(true));
  const GBufferData after = reused->readGBuffer();

  const auto fresh = makeTestRenderer(scene, "uniform", "hard", {}, kMap);
  fresh->render(frame(true));
  const GBufferData first = fresh->readGBuffer();

  // The test can fail: the scene's own view has background (as a first frame sees it) that the
  // earlier view covered.
  ASSERT_EQ(after.position.size(), first.position.size());
  size_t staleCandidates = 0, background = 0, nonZero = 0;
  for (size_t i = 0; i < after.position.size(); ++i) {
    if (first.covered(i)) continue;
    ++background;
    staleCandidates += before.covered(i) ? 1 : 0;
    nonZero += after.position[i] != glm::vec4(0.0f) || after.normal[i] != glm::vec4(0.0f) ||
                       after.geoNormal[i] != glm::vec4(0.0f) || after.albedo[i] != glm::vec4(0.0f) ||
                       after.triangle[i] != glm::uvec2(0u)
                   ? 1
                   : 0;
  }
  ASSERT_GT(background, 100u);
  ASSERT_GT(staleCandidates, 100u) << "the earlier view must cover pixels that are background now";
  EXPECT_EQ(nonZero, 0u) << "background pixels with a value left from the earlier frame";
  expectSameSurfaces(after, first);
  EXPECT_EQ(after.triangle, first.triangle);
}

// Without triangle ids the G-buffer holds the same surfaces and readGBuffer() leaves `triangle`
// empty; with them every covered pixel names a triangle and background names none.
TEST(GBuffer, TriangleIdsOnlyWhenAsked) {
  const Scene scene = makeBuiltinScene("boxes");
  const auto r = makeTestRenderer(scene, "uniform", "hard", {}, kMap);
  r->render(frame(false));
  const GBufferData without = r->readGBuffer();
  const std::vector<float> vWithout = r->readVisibility();
  r->render(frame(true));
  const GBufferData with = r->readGBuffer();
  EXPECT_TRUE(without.triangle.empty());
  ASSERT_EQ(with.triangle.size(), with.position.size());
  expectSameSurfaces(without, with);
  EXPECT_EQ(vWithout, r->readVisibility());
  size_t wrong = 0;
  for (size_t i = 0; i < with.triangle.size(); ++i) wrong += (with.triangle[i].x > 0) != with.covered(i) ? 1 : 0;
  EXPECT_GT(coveredPixels(with), with.position.size() / 2);
  EXPECT_EQ(wrong, 0u) << "pixels whose triangle id disagrees with their coverage";
}

// A software rasteriser gets large draws in pieces with a flush between them (what bounds its
// binning memory, docs/scenes.md#memory); the pieces draw the same triangles in the same order, so
// the G-buffer, the shadow map and V are the same bits as one draw a mesh.
TEST(GBuffer, DrawsInPiecesGiveTheSamePictureAsOneDrawAMesh) {
  const Scene scene = makeBuiltinScene("boxes");
  auto renderWith = [&](size_t triangles) {
    gl::setTrianglesPerSubmission(triangles);
    const auto r = makeTestRenderer(scene, "uniform", "pcf", {}, kMap);
    r->render(frame(true));
    std::pair<GBufferData, std::vector<float>> out{r->readGBuffer(), r->readVisibility()};
    gl::setTrianglesPerSubmission(std::nullopt);
    return out;
  };
  const auto whole = renderWith(0);
  const auto pieces = renderWith(1);  // a flush after every triangle: the most pieces there can be
  ASSERT_GT(coveredPixels(whole.first), size_t(kW * kH / 2));
  expectSameSurfaces(pieces.first, whole.first);
  EXPECT_EQ(pieces.first.triangle, whole.first.triangle);
  EXPECT_EQ(pieces.second, whole.second) << "V differs: the shadow map's pieces drew something else";
  EXPECT_EQ(gl::trianglesPerSubmission(),
            gl::isSoftwareRenderer(gl::glString(GL_RENDERER)) ? gl::kSoftwareTrianglesPerSubmission : 0u);
}

}  // namespace penumbra::test
