// Real scene files on the GPU and in the reference: the project's alpha_quad.gltf (a quad whose
// texture has holes, under a KHR_lights_punctual sun straight above) must cast a shadow with the
// texture's holes in it, in the renderer and in the Embree reference, and the camera must see
// through the holes. A scene file that places an OBJ and a glTF side by side renders, and agrees
// with the reference.
#include "CompressedModels.h"
#include "GlFixture.h"
#include "sceneio/loaders/GltfLoader.h"

#include <penumbra/Reference.h>

#include <glm/geometric.hpp>

#include <cmath>
#include <cstdio>
#include <string>

using namespace penumbra;
using namespace penumbra::test;

namespace {

constexpr int kSize = 192;
constexpr int kMapSize = 2048;
const std::string kData = PENUMBRA_TEST_DATA;
// tests/data/make_test_models.py: the mask (row 0 = the image's top = the quad's -z edge), the
// quad spanning x, z in [-1, 1] at y = 1, each texel 0.5 m square.
const char* const kMask[4] = {"X.XX", "..X.", "X...", "XX.X"};
constexpr float kQuadHalfM = 1.0f, kQuadHeightM = 1.0f, kTexelM = 0.5f;
// Probes stay this far from texel borders: the sun's 0.005 rad radius blurs 1 m below the quad by
// 5 mm, the 2048² map's texels are ~3 mm, so 5 cm leaves every probe clearly in or out.
constexpr float kBorderMarginM = 0.05f;
constexpr float kOnPlaneM = 1e-3f;
constexpr float kShadowedV = 0.1f, kLitV = 0.9f;
constexpr float kGltfGroundM = 0.01f;  // scenes/obj_and_gltf.json lifts the glTF by 1 cm

ReferenceOptions quietReference() {
  ReferenceOptions o;
  o.samples = 16;
  o.progress = false;
  o.useCache = false;
  return o;
}

/// The mask texel over world point (x, z), or 0 when the point is not under the quad or too near
/// a texel border to call: 'X' (opaque: shadowed) or '.' (a hole: lit).
char maskAt(float x, float z) {
  const float u = (x + kQuadHalfM) / kTexelM, v = (z + kQuadHalfM) / kTexelM;
  if (u <= 0.0f || v <= 0.0f || u >= 4.0f || v >= 4.0f) return 0;
  const float margin = kBorderMarginM / kTexelM;
  if (u - std::floor(u) < margin || std::ceil(u) - u < margin || v - std::floor(v) < margin || std::ceil(v) - v < margin) return 0;
  return kMask[static_cast<int>(v)][static_cast<int>(u)];
}


/// The masked quad's shadow on the ground must have the mask's holes (in the renderer and the
/// reference), and the camera must see the quad only where it is opaque.
void expectShadowWithTheMasksHoles(const std::string& file) {
  SCOPED_TRACE(file);
  const Scene scene = loadScene(kData + "/models/" + file);
  ASSERT_EQ(scene.lights.size(), 1u);
  const RenderResult r = renderScene(scene, "uniform", "hard", {{"hard.bias", "slope"}}, kSize, kSize, kMapSize);
  ReferenceTracer tracer(scene);
  const ReferenceResult ref = tracer.trace(r.gbuffer, scene.light(), quietReference());

  int shadowed = 0, lit = 0, rendererWrong = 0, referenceWrong = 0, quadPixels = 0, quadOnHoles = 0;
  for (size_t i = 0; i < r.visibility.size(); ++i) {
    if (!r.gbuffer.covered(i)) continue;
    const glm::vec3 p(r.gbuffer.position[i]);
    const char texel = maskAt(p.x, p.z);
    if (std::abs(p.y - kQuadHeightM) < kOnPlaneM && texel) {  // the camera sees the quad only where it is opaque
      ++quadPixels;
      quadOnHoles += texel == '.';
    }
    if (std::abs(p.y) > kOnPlaneM || !texel) continue;  // ground probes under the quad
    const bool expectShadow = texel == 'X';
    (expectShadow ? shadowed : lit) += 1;
    rendererWrong += expectShadow ? r.visibility[i] > kShadowedV : r.visibility[i] < kLitV;
    referenceWrong += expectShadow ? ref.visibility[i] > kShadowedV : ref.visibility[i] < kLitV;
  }
  std::printf("alpha quad: %d shadowed and %d lit probes; wrong: renderer %d, reference %d; quad pixels %d (%d on holes)\n",
              shadowed, lit, rendererWrong, referenceWrong, quadPixels, quadOnHoles);
  ::testing::Test::RecordProperty("probes", shadowed + lit);
  EXPECT_GT(shadowed, 200);
  EXPECT_GT(lit, 200);
  EXPECT_EQ(rendererWrong, 0);
  EXPECT_EQ(referenceWrong, 0);
  EXPECT_GT(quadPixels, 200);
  EXPECT_EQ(quadOnHoles, 0);
}

// tests/data/make_test_models.py: textured_quads.gltf's ground is a JPEG of 4 x 4 blocks under
// KHR_texture_transform (scale 2, a quarter turn: u' = 2v, v' = -2u), 6 m square from uv (0, 0)
// at (-3, 0, -3).
const char* const kChecker[4] = {"ABAA", "BBAB", "ABBB", "AABA"};
constexpr float kGroundHalfM = 3.0f;
constexpr float kCheckerBorderMargin = 0.04f;  // of a block: probes keep off block borders
const glm::vec3 kCheckerSrgb[2] = {{230, 200, 40}, {30, 60, 190}};  // 'A', 'B'

glm::vec3 linearFromSrgb8(glm::vec3 c) {
  auto lin = [](float x) { x /= 255.0f; return x <= 0.04045f ? x / 12.92f : std::pow((x + 0.055f) / 1.055f, 2.4f); };
  return {lin(c.x), lin(c.y), lin(c.z)};
}

/// The checker block over ground point (x, z): 'A', 'B', or 0 near a block border.
char checkerAt(float x, float z) {
  const float u = (x + kGroundHalfM) / (2 * kGroundHalfM), v = (z + kGroundHalfM) / (2 * kGroundHalfM);
  const float tu = 4.0f * (2.0f * v), tv = 4.0f * (-2.0f * u);  // in blocks; the texture repeats
  const float fu = tu - std::floor(tu), fv = tv - std::floor(tv);
  if (fu < kCheckerBorderMargin || fu > 1 - kCheckerBorderMargin || fv < kCheckerBorderMargin || fv > 1 - kCheckerBorderMargin) return 0;
  const int bu = static_cast<int>(std::floor(tu)) & 3, bv = static_cast<int>(std::floor(tv)) & 3;
  return kChecker[bv][bu];
}

}  // namespace

TEST(Gltf, AlphaMaskedQuadCastsAShadowWithHoles) { expectShadowWithTheMasksHoles("alpha_quad.gltf"); }

// Most glTF files in the wild use JPEG, which was refused ("not an image stb_image can decode"),
// even as a normal map Penumbra ignores. Here the ground's colour is a JPEG under
// KHR_texture_transform, its normal map a WebP nothing decodes, and the quad's PNG mask still cuts
// the shadow's holes.
TEST(Gltf, JpegTexturedGroundWithTransformAndTheMasksHoles) {
  expectShadowWithTheMasksHoles("textured_quads.gltf");
  const Scene scene = loadScene(kData + "/models/textured_quads.gltf");
  const RenderResult r = renderScene(scene, "uniform", "hard", {{"hard.bias", "slope"}}, kSize, kSize, kMapSize);
  int probes = 0, wrong = 0;
  for (size_t i = 0; i < r.visibility.size(); ++i) {
    const glm::vec3 p(r.gbuffer.position[i]);
    if (!r.gbuffer.covered(i) || std::abs(p.y) > kOnPlaneM) continue;  // the ground only
    const char block = checkerAt(p.x, p.z);
    if (!block) continue;
    ++probes;
    const glm::vec3 albedo(r.gbuffer.albedo[i]);
    const glm::vec3 a = linearFromSrgb8(kCheckerSrgb[0]), b = linearFromSrgb8(kCheckerSrgb[1]);
    const char seen = glm::length(albedo - a) < glm::length(albedo - b) ? 'A' : 'B';
    wrong += seen != block;
  }
  std::printf("jpeg ground: %d probes, %d with the wrong block colour\n", probes, wrong);
  EXPECT_GT(probes, 2000);
  EXPECT_EQ(wrong, 0);
}

TEST(Gltf, AlphaMaskIsWhatCutsTheHoles) {
  // The same file with the mask switched off: the whole quad is opaque, so every probe is shadowed.
  Scene scene = loadScene(kData + "/models/alpha_quad.gltf");
  for (Material& m : scene.materials) m.alphaMask = false;
  const RenderResult r = renderScene(scene, "uniform", "hard", {{"hard.bias", "slope"}}, kSize, kSize, kMapSize);
  int probes = 0, lit = 0;
  for (size_t i = 0; i < r.visibility.size(); ++i) {
    const glm::vec3 p(r.gbuffer.position[i]);
    if (!r.gbuffer.covered(i) || std::abs(p.y) > kOnPlaneM || !maskAt(p.x, p.z)) continue;
    ++probes;
    lit += r.visibility[i] > kShadowedV;
  }
  EXPECT_GT(probes, 100);
  EXPECT_EQ(lit, 0);
}

TEST(Gltf, SceneFileWithObjAndGltfRendersAndMatchesTheReference) {
  const Scene scene = loadScene(kData + "/scenes/obj_and_gltf.json");
  const RenderResult r = renderScene(scene, "uniform", "hard", {{"hard.bias", "slope"}}, kSize, kSize, kMapSize);
  ReferenceTracer tracer(scene);
  const ReferenceResult ref = tracer.trace(r.gbuffer, scene.light(), quietReference());
  int boxPixels = 0, quadPixels = 0, floorShadowLeft = 0, floorShadowRight = 0, compared = 0, disagree = 0;
  for (size_t i = 0; i < r.visibility.size(); ++i) {
    if (!r.gbuffer.covered(i)) continue;
    const glm::vec3 p(r.gbuffer.position[i]);
    const glm::vec3 albedo(r.gbuffer.albedo[i]);
    boxPixels += albedo.x > 0.6f && albedo.y < 0.2f;                       // box.mtl: Kd 0.8 0.1 0.1
    quadPixels += albedo.x > 0.5f && albedo.y < 0.05f && p.y > 0.4f;       // the texture's red (sRGB 220, 40, 30)
    // The box's shadow on the floor (y = 0), the quad's on the glTF's own ground (y = 0.01).
    if (r.visibility[i] < kShadowedV && std::abs(p.y) < kOnPlaneM && p.x < 0.0f) ++floorShadowLeft;
    if (r.visibility[i] < kShadowedV && std::abs(p.y - kGltfGroundM) < kOnPlaneM) ++floorShadowRight;
    if (ref.litMask[i]) {
      ++compared;
      disagree += std::abs(r.visibility[i] - ref.visibility[i]) > 0.5f;
    }
  }
  const double disagreePct = 100.0 * disagree / std::max(compared, 1);
  std::printf("obj+gltf: box %d px, quad %d px, floor shadow left %d / right %d px, %.2f%% of %d lit-facing px disagree with the reference\n",
              boxPixels, quadPixels, floorShadowLeft, floorShadowRight, disagreePct, compared);
  EXPECT_GT(boxPixels, 100);
  EXPECT_GT(quadPixels, 20);
  EXPECT_GT(floorShadowLeft, 40);    // the box's shadow (mostly behind the box from this camera)
  EXPECT_GT(floorShadowRight, 40);   // the masked quad's shadow
  EXPECT_GT(compared, 10000);
  EXPECT_LT(disagreePct, 1.0);       // only shadow-edge pixels may differ
}

// Compressed geometry renders as the original: the box and ground as plain accessors, with
// KHR_draco_mesh_compression (quantised: edges may move by a pixel) and with
// EXT_meshopt_compression (lossless positions) cover the same pixels and cast the same shadow.
TEST(Gltf, CompressedModelsRenderLikeTheOriginal) {
  auto sceneOf = [](const std::vector<uint8_t>& glb) {
    loaders::Model m = loaders::loadGltfFromMemory(glb, "mem.glb", "");
    loaders::addDefaultLightAndCamera(m.scene, m.hasCamera);
    m.scene.validate();
    return m.scene;
  };
  auto render = [](const Scene& scene) { return renderScene(scene, "uniform", "hard", {{"hard.bias", "slope"}}, kSize, kSize, kMapSize); };
  const RenderResult plain = render(sceneOf(test::plainBoxGlb()));
  constexpr double kMaxDifferingPct = 0.5;  // Draco's 14-bit positions move a silhouette by under a pixel
  for (const auto& [name, glb] : {std::pair{"draco", test::dracoBoxGlb()}, std::pair{"meshopt", test::meshoptBoxGlb()}}) {
    const RenderResult r = render(sceneOf(glb));
    size_t covered = 0, differing = 0, shadowed = 0;
    for (size_t i = 0; i < r.visibility.size(); ++i) {
      covered += plain.gbuffer.covered(i);
      shadowed += plain.gbuffer.covered(i) && plain.visibility[i] < kShadowedV;
      differing += r.gbuffer.covered(i) != plain.gbuffer.covered(i) || std::abs(r.visibility[i] - plain.visibility[i]) > 0.5f;
    }
    const double pct = 100.0 * static_cast<double>(differing) / static_cast<double>(r.visibility.size());
    std::printf("%s box: %.3f%% of pixels differ from the plain file's (%zu covered, %zu in shadow)\n", name, pct, covered, shadowed);
    EXPECT_GT(covered, r.visibility.size() / 4) << name;
    EXPECT_GT(shadowed, 1000u) << name << ": the box's shadow";
    EXPECT_LT(pct, kMaxDifferingPct) << name;
  }
}
