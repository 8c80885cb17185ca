// sdf: the shader's distance agrees with the CPU bake; on `pen` (spot light) the visibility is
// compared with the Embree reference for a sweep of k and for k from the light size (against
// pcss); it works with the sun (boxes), uploads its field once per scene, and a scene without
// casters is fully lit.
#include "GlFixture.h"
#include "GlslProbe.h"

#include "frame/FrameContext.h"
#include "bake/SdfBake.h"
#include "techniques/sdf/SdfFilter.h"
#include "shared/Bindings.h"
#include "shared/Frame.h"
#include "shared/Shadow.h"

#include <penumbra/ImageIO.h>
#include <penumbra/Metrics.h>
#include <penumbra/Reference.h>

#include <fmt/format.h>

#include <algorithm>
#include <cstdio>
#include <random>

using namespace penumbra;
using namespace penumbra::test;

namespace {

constexpr int kWidth = 256, kHeight = 144;
constexpr int kMapSize = 1024;           // for pcss; the sdf filter has no map
constexpr int kReferenceSamples = 256;

ReferenceResult traceReference(const Scene& scene, const GBufferData& g) {
  ReferenceTracer tracer(scene);
  ReferenceOptions o;
  o.samples = kReferenceSamples;
  o.progress = false;
  return tracer.trace(g, scene.light(), o);
}

VisibilityMetrics measure(const RenderResult& r, const ReferenceResult& ref) {
  return compareVisibility(r.visibility, ref.visibility, ref.litMask);
}

TEST(SdfFilter, ShaderDistanceMatchesTheBake) {
  glContext();
  const Scene scene = loadScene("pen");
  sdf::BakeOptions o;
  o.progress = false;
  o.useCache = false;
  const sdf::SdfVolume volume = sdf::bake(scene, o);
  ASSERT_TRUE(volume.hasGrid());
  ASSERT_EQ(volume.sheets.size(), 6u);  // the floor

  SdfFilter filter;
  filter.setField(volume);
  const gpu::SdfUniforms u = filter.uniforms(Technique("uniform", "sdf").filterValues());
  gl::Buffer block("sdf probe block", sizeof(u), &u);
  block.bindBase(GL_UNIFORM_BUFFER, PN_UBO_FILTER);
  const gpu::FrameUniforms frame{};
  const gpu::ShadowUniforms shadow{};
  gl::Buffer frameBlock("probe frame", sizeof(frame), &frame), shadowBlock("probe shadow", sizeof(shadow), &shadow);
  frameBlock.bindBase(GL_UNIFORM_BUFFER, PN_UBO_FRAME);
  shadowBlock.bindBase(GL_UNIFORM_BUFFER, PN_UBO_SHADOW);
  filter.fieldTexture().bindUnit(PN_TEX_FILTER0);

  // Points inside the grid, in its padding, outside it and around the floor's edges.
  constexpr int kPoints = 4096;
  const Aabb all = volume.casterBounds();
  std::mt19937 rng(11);
  std::vector<glm::vec4> points(kPoints);
  for (int i = 0; i < kPoints; ++i) {
    const Aabb box = i % 2 ? Aabb{volume.lo - 0.1f, volume.hi() + 0.1f} : Aabb{all.lo - 0.5f, all.hi + 0.5f};
    std::uniform_real_distribution<float> x(box.lo.x, box.hi.x), y(box.lo.y, box.hi.y), z(box.lo.z, box.hi.z);
    points[static_cast<size_t>(i)] = glm::vec4(x(rng), y(rng), z(rng), 0.0f);
  }
  gl::Buffer buffer("sdf probe points", points.size() * sizeof(glm::vec4), points.data());
  buffer.bindBase(GL_SHADER_STORAGE_BUFFER, PN_SSBO_TEST);
  const gl::Program probe = compileProbe("sdf distance", R"(
#include "techniques/sdf/sdf.glsl"
layout(local_size_x = 64) in;
layout(std430, binding = PN_SSBO_TEST) buffer Probe { vec4 points[]; };  // xyz in, w out
void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i < uint(points.length())) points[i].w = sdfDistance(points[i].xyz);
})");
  FrameContext::dispatch2D(probe, kPoints, 1, 64);
  buffer.download(points.data(), points.size() * sizeof(glm::vec4));

  // GPU trilinear weights carry ~8 fractional bits: |∇d| ≤ 1, so a few thousandths of a voxel.
  const float toleranceM = 0.01f * volume.voxelM;
  float worst = 0.0f;
  for (const glm::vec4& p : points) worst = std::max(worst, std::abs(p.w - volume.distance(glm::vec3(p))));
  std::printf("shader vs CPU distance: max |Δ| %.2e m over %d points (voxel %.4f m)\n", worst, kPoints, volume.voxelM);
  EXPECT_LE(worst, toleranceM);
}


TEST(SdfFilter, PenAgainstReferenceKSweepAndLightSize) {
  const Scene scene = loadScene("pen");
  const RenderResult pcss = renderScene(scene, "uniform", "pcss", {}, kWidth, kHeight, kMapSize);
  const ReferenceResult ref = traceReference(scene, pcss.gbuffer);
  const VisibilityMetrics mPcss = measure(pcss, ref);

  struct Row {
    std::string label;
    VisibilityMetrics m;
    double ms;
  };
  std::vector<Row> rows;
  auto run = [&](const std::string& label, const Params& params) {
    const RenderResult r = renderScene(scene, "uniform", "sdf", params, kWidth, kHeight, kMapSize);
    rows.push_back({label, measure(r, ref), r.timings.get("visibility")});
    return rows.back().m;
  };
  const VisibilityMetrics lightCentered = run("k from light, centered", {});
  const VisibilityMetrics lightOuter = run("k from light, outer", {{"sdf.penumbra", "outer"}});
  run("k from light, centered, improved", {{"sdf.estimator", "improved"}});
  constexpr float kSweep[] = {2, 4, 8, 16, 32, 64, 128, 256};
  double bestCentered = 1e9, firstCentered = 0, lastCentered = 0;
  for (std::string_view penumbra : {"outer", "centered"}) {
    for (float k : kSweep) {
      const VisibilityMetrics m = run(fmt::format("k = {}, {}", k, penumbra),
                                      {{"sdf.kMode", "manual"}, {"sdf.k", fmt::format("{}", k)}, {"sdf.penumbra", std::string(penumbra)}});
      if (penumbra == "centered") {
        bestCentered = std::min(bestCentered, m.rmse);
        if (k == kSweep[0]) firstCentered = m.rmse;
        lastCentered = m.rmse;
      }
    }
  }
  std::printf("pen, %dx%d, reference %d samples/pixel; pcss: rmse %.4f, penumbra rmse %.4f, visibility %.1f ms\n", kWidth,
              kHeight, ref.samplesPerPixel, mPcss.rmse, mPcss.penumbraRmse, pcss.timings.get("visibility"));
  std::printf("%-36s %8s %10s %7s %10s %8s\n", "sdf", "rmse", "penumbra", "leak%", "overdark%", "ms");
  for (const Row& r : rows)
    std::printf("%-36s %8.4f %10.4f %7.2f %10.2f %8.1f\n", r.label.c_str(), r.m.rmse, r.m.penumbraRmse, r.m.leakPct,
                r.m.overDarkPct, r.ms);

  // The issue's bar: k from the light's size within 1.5x of pcss.
  EXPECT_LE(lightCentered.rmse, 1.5 * mPcss.rmse);
  // The physical k is as good as the best hand-tuned one (within 25 %), and k matters: both
  // ends of the sweep are clearly worse.
  EXPECT_LE(lightCentered.rmse, 1.25 * bestCentered);
  EXPECT_GT(firstCentered, 2.0 * bestCentered);
  EXPECT_GT(lastCentered, 1.5 * bestCentered);
  // Centering the penumbra on the hard shadow's edge is what makes the physical k work.
  EXPECT_LT(lightCentered.rmse, 0.5 * lightOuter.rmse);
}

TEST(SdfFilter, SunOnBoxesAgainstReference) {
  const Scene scene = loadScene("boxes");
  ASSERT_EQ(scene.light().type, LightType::Directional);
  const RenderResult pcss = renderScene(scene, "uniform", "pcss", {}, kWidth, kHeight, kMapSize);
  const RenderResult sdf = renderScene(scene, "uniform", "sdf", {}, kWidth, kHeight, kMapSize);
  const ReferenceResult ref = traceReference(scene, sdf.gbuffer);
  const VisibilityMetrics mSdf = measure(sdf, ref), mPcss = measure(pcss, ref);
  std::printf("boxes (sun): sdf rmse %.4f (penumbra %.4f, leak %.2f%%, over-dark %.2f%%), pcss rmse %.4f\n", mSdf.rmse,
              mSdf.penumbraRmse, mSdf.leakPct, mSdf.overDarkPct, mPcss.rmse);
  EXPECT_LE(mSdf.rmse, 1.5 * mPcss.rmse);
  // Shadows exist: a good share of the lit-facing pixels is in umbra, in both.
  size_t dark = 0, darkRef = 0;
  for (size_t i = 0; i < ref.litMask.size(); ++i) {
    if (!ref.litMask[i]) continue;
    dark += sdf.visibility[i] < 0.1f;
    darkRef += ref.visibility[i] < 0.1f;
  }
  EXPECT_GT(darkRef, 100u);
  EXPECT_NEAR(static_cast<double>(dark), static_cast<double>(darkRef), 0.1 * static_cast<double>(darkRef));
}

TEST(SdfFilter, LightSizeDrivesKOnlyInLightMode) {
  Scene scene = loadScene("pen");
  auto meanV = [&](float size, const Params& params) {
    Scene s = scene;
    s.lights.front().size = size;
    const RenderResult r = renderScene(s, "uniform", "sdf", params, kWidth, kHeight, kMapSize);
    double sum = 0.0;
    for (float v : r.visibility) sum += v;
    return sum / static_cast<double>(r.visibility.size());
  };
  const float size = scene.light().size;
  // A bigger light: a wider penumbra. Centered, it brightens the umbra as much as it darkens the
  // outside, so the mean hardly moves; outer puts all of it outside: darker.
  const Params outer{{"sdf.penumbra", "outer"}};
  EXPECT_LT(meanV(4.0f * size, outer), meanV(size, outer) - 1e-4);
  const Params manual{{"sdf.kMode", "manual"}, {"sdf.penumbra", "outer"}};
  EXPECT_EQ(meanV(4.0f * size, manual), meanV(size, manual));
}

TEST(SdfFilter, FieldIsUploadedOncePerScene) {
  glContext();
  Scene scene = loadScene("pen");
  const std::unique_ptr<Renderer> owned = makeTestRenderer(scene, "uniform", "sdf");
  Renderer& renderer = *owned;
  RenderOptions o;
  o.width = 64;
  o.height = 36;
  renderer.render(o);
  auto& filter = dynamic_cast<SdfFilter&>(filterOf(renderer.shadows()));  // light 0's, made by its first frame
  renderer.render(o);
  EXPECT_EQ(filter.fieldUploads(), 1);
  const auto set = [&renderer](const char* key, float value) {
    Technique t = renderer.technique();
    t.set(key, value);
    renderer.setTechnique(t);
  };
  set("sdf.k", 4.0f);  // a march parameter: no new field
  renderer.render(o);
  EXPECT_EQ(filter.fieldUploads(), 1);
  scene.objects.back().worldFromObject[3][1] += 0.1f;  // the pencil moved: a new field
  renderer.setScene(scene);
  renderer.render(o);
  EXPECT_EQ(filter.fieldUploads(), 2);
  set("sdf.resolution", 64.0f);
  renderer.render(o);
  EXPECT_EQ(filter.fieldUploads(), 3);
}

TEST(SdfFilter, NoCastersMeansFullyLit) {
  Scene scene = loadScene("boxes");
  for (Object& o : scene.objects) o.castsShadow = false;
  const RenderResult r = renderScene(scene, "uniform", "sdf", {}, 64, 36, kMapSize);
  size_t lit = 0, litFacing = 0;
  for (size_t i = 0; i < r.visibility.size(); ++i) {
    if (!r.gbuffer.covered(i) || r.visibility[i] == 0.0f) continue;  // background or facing away (V = 0 by the pass)
    ++litFacing;
    lit += r.visibility[i] == 1.0f;
  }
  EXPECT_GT(litFacing, 100u);
  EXPECT_EQ(lit, litFacing);
}

}  // namespace
