// The tight blocker search (pcss/vssm/msm-soft .tightSearch): the min-depth pyramid and its box
// lookup against a CPU minimum, and what the search changes where the near plane's footprint is
// far too large: `city` under its low sun, where vssm and msm-soft lost whole shadows.
#include "GlFixture.h"
#include "GlslProbe.h"
#include "frame/MinDepthPyramid.h"
#include "shared/Bindings.h"

#include <penumbra/Metrics.h>
#include <penumbra/Reference.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdio>
#include <random>

using namespace penumbra;
using namespace penumbra::test;

namespace {

constexpr int kW = 333, kH = 301;  // odd sides: every level has a left-over row and column

// One query per box: (uv centre, radius uv); the result is minDepthOverBox's.
constexpr const char* kQueryMain = R"(
#include "common/penumbra.glsl"
#include "shared/Bindings.h"
layout(local_size_x = 64) in;
layout(binding = PN_TEX_FILTER0) uniform sampler2DArray s_pyramid;
layout(std430, binding = PN_SSBO_AUX) readonly buffer Boxes { vec4 b_boxes[]; };
layout(std430, binding = PN_SSBO_TEST) writeonly buffer Results { float o_min[]; };
layout(location = 10) uniform int u_count;  // clear of the library's own locations (PN_LOC_*)
layout(location = 11) uniform float u_mapSize;
void main() {
  int i = int(gl_GlobalInvocationID.x);
  if (i >= u_count) return;
  o_min[i] = minDepthOverBox(s_pyramid, 0, b_boxes[i].xy, b_boxes[i].zw, u_mapSize);
}
)";

}  // namespace

// Every box's answer is the exact minimum over the pyramid cells the lookup reads (so the build
// is right), and never above the minimum over the box's own texels (so the search stays
// conservative: no blocker is nearer than what it returns).
TEST(TightSearch, PyramidMinimumIsExactForItsCellsAndConservativeForTheBox) {
  glContext();
  std::mt19937 rng(17);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  std::vector<float> z(static_cast<size_t>(kW) * kH);
  for (float& v : z) v = unit(rng);
  gl::Texture map("tight search depths", {GL_TEXTURE_2D_ARRAY, GL_R32F, kW, kH, 1, 1});
  map.setSampling(GL_NEAREST, GL_NEAREST);
  glTextureSubImage3D(map.id(), 0, 0, 0, 0, kW, kH, 1, GL_RED, GL_FLOAT, z.data());
  ShaderLibrary shaders;
  MinDepthPyramid pyramid;
  pyramid.build(shaders, map);

  // Boxes of every scale, in uv of a kW-texel-wide map (the lookup's mapSize), some past the edge.
  constexpr int kBoxes = 3000;
  const float mapSize = static_cast<float>(kW);
  std::vector<glm::vec4> boxes;
  std::uniform_real_distribution<float> logRadius(-1.0f, std::log2(static_cast<float>(kW)));
  for (int i = 0; i < kBoxes; ++i)
    boxes.emplace_back(unit(rng) * 1.1f - 0.05f, unit(rng) * 1.1f - 0.05f, std::exp2(logRadius(rng)) / mapSize,
                       std::exp2(logRadius(rng)) / mapSize);
  const gl::Program query = compileProbe("min-depth query", kQueryMain);
  gl::Buffer in("tight search boxes", boxes.size() * sizeof(glm::vec4), boxes.data());
  gl::Buffer out("tight search results", boxes.size() * sizeof(float));
  in.bindBase(GL_SHADER_STORAGE_BUFFER, PN_SSBO_AUX);
  out.bindBase(GL_SHADER_STORAGE_BUFFER, PN_SSBO_TEST);
  pyramid.pyramid().bindUnit(PN_TEX_FILTER0);
  glProgramUniform1i(query.id(), 10, kBoxes);
  glProgramUniform1f(query.id(), 11, mapSize);
  query.use();
  glDispatchCompute((kBoxes + 63) / 64, 1, 1);
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  std::vector<float> got(boxes.size());
  out.download(got.data(), got.size() * sizeof(float));

  // The CPU twin of minDepthOverBox's cell choice; a level-k cell covers 2^(k+1) texels, and the
  // last cell of a level also the left-over ones (GL's mip sizes round down).
  auto minOver = [&](int x0, int y0, int x1, int y1) {
    float m = 1.0f;
    for (int y = std::max(y0, 0); y <= std::min(y1, kH - 1); ++y)
      for (int x = std::max(x0, 0); x <= std::min(x1, kW - 1); ++x) m = std::min(m, z[static_cast<size_t>(y) * kW + x]);
    return m;
  };
  const int w0 = (kW + 1) / 2, h0 = (kH + 1) / 2;
  const int levels = std::bit_width(static_cast<unsigned>(std::max(w0, h0)));
  int exact = 0, conservative = 0, reported = 0;
  for (size_t i = 0; i < boxes.size(); ++i) {
    const glm::vec4 b = boxes[i];
    const glm::vec2 lo = (glm::vec2(b) - glm::vec2(b.z, b.w)) * mapSize, hi = (glm::vec2(b) + glm::vec2(b.z, b.w)) * mapSize;
    const float width = std::max(std::max(hi.x - lo.x, hi.y - lo.y), 1.0f);
    const int level = std::clamp(static_cast<int>(std::ceil(std::log2(width))) - 1, 0, levels - 1);
    const glm::ivec2 size(std::max(w0 >> level, 1), std::max(h0 >> level, 1));
    const int cell = 1 << (level + 1);
    const glm::ivec2 a = glm::clamp(glm::ivec2(glm::floor(lo / static_cast<float>(cell))), glm::ivec2(0), size - 1);
    const glm::ivec2 c = glm::clamp(glm::ivec2(glm::floor(hi / static_cast<float>(cell))), a, glm::min(a + 1, size - 1));
    const int x1 = c.x == size.x - 1 ? kW - 1 : (c.x + 1) * cell - 1;
    const int y1 = c.y == size.y - 1 ? kH - 1 : (c.y + 1) * cell - 1;
    const float cells = minOver(a.x * cell, a.y * cell, x1, y1);
    const float box = minOver(static_cast<int>(std::floor(lo.x)), static_cast<int>(std::floor(lo.y)),
                              static_cast<int>(std::floor(hi.x)), static_cast<int>(std::floor(hi.y)));
    exact += got[i] == cells;
    conservative += got[i] <= box;
    if ((got[i] != cells || got[i] > box) && ++reported <= 5)
      ADD_FAILURE() << "box " << i << " level " << level << ": " << got[i] << ", cells " << cells << ", box " << box;
  }
  std::printf("min-depth pyramid %dx%d, %d levels: %d of %d boxes exact for their cells, %d conservative\n", kW, kH,
              levels, exact, kBoxes, conservative);
  EXPECT_EQ(exact, kBoxes);
  EXPECT_EQ(conservative, kBoxes);
}

// Every texel of every level and layer is the minimum of the map texels under it (a CPU pyramid
// built the same way), with the minimum taken by the filter where the context can
// (GL_ARB_texture_filter_minmax: one filtered read of 2x2 texels) and by four texel fetches:
// the two builds are the same pyramid, on odd sides (left-over rows and columns) and even ones.
TEST(TightSearch, PyramidLevelsAreTheMinimaUnderThemWithAndWithoutTheMinFilter) {
  glContext();
  std::printf("GL_ARB_texture_filter_minmax: %s\n", MinDepthPyramid::hasMinFilter() ? "yes" : "no (fetches only)");
  std::mt19937 rng(23);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  ShaderLibrary shaders;
  for (const glm::ivec2 size : {glm::ivec2(kW, kH), glm::ivec2(256, 128), glm::ivec2(6, 10)}) {
    constexpr int kLayers = 2;
    std::vector<float> z(static_cast<size_t>(size.x) * size.y * kLayers);
    for (float& v : z) v = unit(rng);
    gl::Texture map("pyramid levels depths", {GL_TEXTURE_2D_ARRAY, GL_R32F, size.x, size.y, kLayers, 1});
    map.setSampling(GL_NEAREST, GL_NEAREST);
    glTextureSubImage3D(map.id(), 0, 0, 0, 0, size.x, size.y, kLayers, GL_RED, GL_FLOAT, z.data());
    // The CPU pyramid: level k's texel is the minimum over the texels of level k - 1 (the map for
    // k = 0) under it, the last row and column also over the left-over ones.
    std::vector<std::vector<float>> cpu;
    glm::ivec2 below = size;
    const std::vector<float>* source = &z;
    for (glm::ivec2 out = (size + 1) / 2;; out = glm::max(out / 2, 1)) {
      std::vector<float> level(static_cast<size_t>(out.x) * out.y * kLayers, 1.0f);
      for (int l = 0; l < kLayers; ++l)
        for (int y = 0; y < out.y; ++y)
          for (int x = 0; x < out.x; ++x) {
            const int x1 = std::min(x == out.x - 1 ? below.x - 1 : 2 * x + 1, below.x - 1);
            const int y1 = std::min(y == out.y - 1 ? below.y - 1 : 2 * y + 1, below.y - 1);
            float& m = level[(static_cast<size_t>(l) * out.y + y) * out.x + x];
            for (int sy = 2 * y; sy <= y1; ++sy)
              for (int sx = 2 * x; sx <= x1; ++sx)
                m = std::min(m, (*source)[(static_cast<size_t>(l) * below.y + sy) * below.x + sx]);
          }
      cpu.push_back(std::move(level));
      source = &cpu.back();
      below = out;
      if (out == glm::ivec2(1)) break;
    }
    for (bool minFilter : {true, false}) {
      MinDepthPyramid pyramid;
      pyramid.build(shaders, map, minFilter);
      ASSERT_EQ(pyramid.pyramid().levels(), static_cast<int>(cpu.size()));
      int wrong = 0;
      for (size_t k = 0; k < cpu.size(); ++k) {
        std::vector<float> got(cpu[k].size());
        glGetTextureImage(pyramid.pyramid().id(), static_cast<GLint>(k), GL_RED, GL_FLOAT,
                          static_cast<GLsizei>(got.size() * sizeof(float)), got.data());
        for (size_t i = 0; i < got.size(); ++i)
          if (got[i] != cpu[k][i] && ++wrong <= 5)
            ADD_FAILURE() << size.x << "x" << size.y << (minFilter ? " min filter" : " fetches") << ", level " << k
                          << ", texel " << i << ": " << got[i] << ", expected " << cpu[k][i];
      }
      EXPECT_EQ(wrong, 0) << size.x << "x" << size.y << (minFilter ? " with the min filter" : " with fetches");
    }
  }
}

// `city`: a low sun (0.005 rad) over tall buildings puts every cascade's near plane far toward
// the sun, so the near-plane search region of a receiver on the ground is metres wide and a low
// bench covers under 1 % of it: vssm's Chebyshev unoccluded fraction is then > 0.99 and the
// bench's shadow disappears (so does msm-soft's). Searched from the nearest surface instead, the
// region shrinks to what the bench needs and the shadow comes back. Counted: pixels in the
// reference's umbra that a filter leaves almost fully lit (V > 0.9), and RMSE.
TEST(TightSearch, BringsBackShadowsTheNearPlaneSearchLosesInCity) {
  const Scene scene = makeBuiltinScene("city");
  constexpr int kWidth = 256, kHeight = 144, kMapSize = 2048;  // the CLI's default map size
  const RenderResult first = renderScene(scene, "csm", "hard", {}, kWidth, kHeight, kMapSize);
  ReferenceTracer tracer(scene);
  ReferenceOptions o;
  o.samples = 64;
  o.progress = false;
  o.useCache = false;
  const ReferenceResult ref = tracer.trace(first.gbuffer, scene.light(), o);
  constexpr float kUmbraV = 0.02f;   // the reference's umbra, as umbra_leak_pct defines it
  constexpr float kLostV = 0.9f;     // a filter's V above this there: the shadow is as good as gone
  constexpr size_t kMinLostOff = 20;  // the near-plane search must lose this many, or the view proves nothing
  // With the tight search, at most this share of the umbra may be left lit. The cascades are 746 m
  // deep: a variance floor or moment bias stated in linear depth (σ of metres) washed the bench's
  // shadow out even when the search found it (vssm 44, msm-soft 22 of 2416 pixels); stated in
  // texels², 2 and 2.
  constexpr double kMaxLostShareOn = 0.005;
  auto inUmbra = [&](size_t i) { return ref.litMask[i] && ref.visibility[i] <= kUmbraV; };
  auto lostUmbra = [&](const RenderResult& r) {
    size_t lost = 0;
    for (size_t i = 0; i < r.visibility.size(); ++i) lost += inUmbra(i) && r.visibility[i] > kLostV;
    return lost;
  };
  size_t umbra = 0;
  for (size_t i = 0; i < ref.visibility.size(); ++i) umbra += inUmbra(i);
  std::printf("city 256x144, csm, reference 64 samples: %zu umbra pixels\n", umbra);
  for (const char* filter : {"pcss", "vssm", "msm-soft"}) {
    const std::string key = std::string(filter) + ".tightSearch";
    const RenderResult off = renderScene(scene, "csm", filter, {{key, "off"}}, kWidth, kHeight, kMapSize);
    const RenderResult on = renderScene(scene, "csm", filter, {{key, "on"}}, kWidth, kHeight, kMapSize);
    const VisibilityMetrics mOff = compareVisibility(off.visibility, ref.visibility, ref.litMask);
    const VisibilityMetrics mOn = compareVisibility(on.visibility, ref.visibility, ref.litMask);
    const size_t lostOff = lostUmbra(off), lostOn = lostUmbra(on);
    std::printf("  %-9s umbra pixels at V > %.1f: near-plane search %zu, tight %zu; RMSE %.4f -> %.4f\n", filter, kLostV,
                lostOff, lostOn, mOff.rmse, mOn.rmse);
    EXPECT_LE(mOn.rmse, mOff.rmse) << filter;
    EXPECT_LE(lostOn, lostOff) << filter;
    if (std::string(filter) != "pcss") {
      EXPECT_GT(lostOff, kMinLostOff) << filter << ": the near-plane search no longer loses shadows here; pick another view";
      EXPECT_LE(2 * lostOn, lostOff) << filter;
    }
    EXPECT_LE(static_cast<double>(lostOn), kMaxLostShareOn * static_cast<double>(umbra)) << filter;
  }
}
