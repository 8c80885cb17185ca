// pcf: the GLSL averaging of comparisons on a known 3×3 neighbourhood (software taps and the
// hardware 2×2 comparison sampler), and rendered edges that soften with the radius on spot and
// sun lights without darkening unoccluded floor (the per-tap receiver bias).
#include "GlFixture.h"
#include "TestGeometry.h"

#include "gl/Objects.h"
#include "shader/ShaderLibrary.h"
#include "techniques/filters/PcfFilter.h"
#include "shared/Bindings.h"

#include <cmath>
#include <cstdio>

using namespace penumbra;
using namespace penumbra::test;

namespace {

// Compiles `main` (which may #include library files) as a compute program; 0 on failure.
GLuint compileCompute(const std::string& main, const std::string& defines) {
  ShaderLibrary lib;
  const ExpandedSource src = expandIncludes({"pcf_test.glsl"}, [&](std::string_view key) -> std::optional<std::string> {
    if (key == "pcf_test.glsl") return main;
    return lib.source(key);
  });
  const std::string text = "#version 450 core\n" + defines + src.text;
  const GLuint shader = glCreateShader(GL_COMPUTE_SHADER);
  const char* ptr = text.c_str();
  glShaderSource(shader, 1, &ptr, nullptr);
  glCompileShader(shader);
  GLint ok = 0;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char log[4096];
    glGetShaderInfoLog(shader, sizeof log, nullptr, log);
    ADD_FAILURE() << remapShaderLog(log, src.files);
    glDeleteShader(shader);
    return 0;
  }
  const GLuint program = glCreateProgram();
  glAttachShader(program, shader);
  glLinkProgram(program);
  glDeleteShader(shader);
  glGetProgramiv(program, GL_LINK_STATUS, &ok);
  EXPECT_TRUE(ok);
  return program;
}

// The library's box PCF around the centre of a 3×3 map, radius one texel, receiver depth 0.5.
constexpr const char* kProbeMain = R"(
#include "common/depth_compare.glsl"
layout(local_size_x = 1) in;
layout(binding = PN_TEX_FILTER0) uniform PN_COMPARISON_MAP s_test;
layout(std430, binding = PN_SSBO_TEST) buffer Out { float o_v[]; };
void main() {
  ComparisonReceiver r;
  r.uv = vec2(0.5);
  r.layer = 0;
  r.depth = 0.5;
  r.bias = 0.0;
  r.depthPerUv = vec2(0.0);
  r.projectivePerUv = vec2(0.0);
  r.biasPerTexel = 0.0;
  r.creasePerTexel = 0.0;
  o_v[0] = percentageCloserBox(s_test, r, vec2(1.0 / 3.0), 1);
}
)";

// Stored depths whose comparisons with 0.5 read, top row first, 1 0 1 / 1 0 1 / 1 1 0.
std::vector<float> neighbourhoodDepths() {
  constexpr float kLit = 1.0f, kBlocked = 0.25f;
  const int comparisons[3][3] = {{1, 0, 1}, {1, 0, 1}, {1, 1, 0}};  // [row from top][column]
  std::vector<float> d(9);
  for (int row = 0; row < 3; ++row)
    for (int x = 0; x < 3; ++x) d[static_cast<size_t>((2 - row) * 3 + x)] = comparisons[row][x] ? kLit : kBlocked;  // GL row 0 = bottom
  return d;
}

float runProbe(bool hardware) {
  glContext();
  const GLuint program = compileCompute(kProbeMain, hardware ? "#define PN_HARDWARE_COMPARE 1\n" : "");
  if (!program) return -1.0f;
  const GLenum format = hardware ? GL_DEPTH_COMPONENT32F : GL_R32F;
  gl::Texture map("pcf test map", {GL_TEXTURE_2D_ARRAY, format, 3, 3, 1, 1});
  map.setSampling(GL_NEAREST, GL_NEAREST);
  const std::vector<float> depths = neighbourhoodDepths();
  glTextureSubImage3D(map.id(), 0, 0, 0, 0, 3, 3, 1, hardware ? GL_DEPTH_COMPONENT : GL_RED, GL_FLOAT, depths.data());
  map.bindUnit(PN_TEX_FILTER0);
  ComparisonSampler compare;
  if (hardware) compare.bind(PN_TEX_FILTER0);
  const float init = -1.0f;
  gl::Buffer out("pcf test out", sizeof(float), &init);
  out.bindBase(GL_SHADER_STORAGE_BUFFER, PN_SSBO_TEST);
  glUseProgram(program);
  glDispatchCompute(1, 1, 1);
  glMemoryBarrier(GL_ALL_BARRIER_BITS);
  float v = -1.0f;
  out.download(&v, sizeof v);
  if (hardware) ComparisonSampler::unbind(PN_TEX_FILTER0);
  glDeleteProgram(program);
  return v;
}

constexpr float kSixNinths = 6.0f / 9.0f;  // 0.667: six of the nine comparisons pass
constexpr float kProbeTolerance = 0.001f;

}  // namespace

TEST(PcfGlsl, AveragesTheComparisonsOfA3x3Neighbourhood) {
  // Averaging the depths instead would give (6·1 + 3·0.25)/9 = 0.75 > 0.5: one test, V = 1.
  EXPECT_NEAR(runProbe(false), kSixNinths, kProbeTolerance);
}

TEST(PcfGlsl, HardwareComparisonSamplerAtTexelCentresGivesTheSameAverage) {
  // Taps at texel centres: each bilinear 2×2 comparison is its own texel's comparison.
  EXPECT_NEAR(runProbe(true), kSixNinths, kProbeTolerance);
}

namespace {

constexpr int kWidth = 256, kHeight = 160, kMapSize = 1024;
constexpr float kPenumbraLow = 0.02f, kPenumbraHigh = 0.98f;

size_t fractionalPixels(const RenderResult& r) {
  size_t n = 0;
  for (size_t i = 0; i < r.visibility.size(); ++i)
    n += r.gbuffer.covered(i) && r.visibility[i] > kPenumbraLow && r.visibility[i] < kPenumbraHigh;
  return n;
}

// Fraction of floor pixels with no caster within jitterM of their light ray that read V < 0.9.
double darkenedUnoccludedFraction(const Scene& scene, const RenderResult& r, float jitterM) {
  CasterTriangles tris(scene);
  size_t floor = 0, dark = 0;
  constexpr size_t kStride = 3;  // every third pixel keeps the CPU side fast
  constexpr float kDarkV = 0.9f;
  for (size_t i = 0; i < r.visibility.size(); i += kStride) {
    if (!onFloor(r.gbuffer.position[i])) continue;
    if (tris.robustOcclusion(scene, glm::vec3(r.gbuffer.position[i]), {0, 1, 0}, jitterM) != 0.0f) continue;
    ++floor;
    dark += r.visibility[i] < kDarkV;
  }
  EXPECT_GT(floor, 1000u);
  return static_cast<double>(dark) / static_cast<double>(std::max<size_t>(floor, 1));
}

// World radius (m) on the floor of a kernel of `texels` texels: the map's texel there, stretched
// by the floor's slant to the light, with a margin of half again for the edge's own aliasing.
float floorKernelRadiusM(const Scene& scene, const RenderResult& r, float texels) {
  const ShadowView& v = r.frusta.views.at(0);
  const Light& l = scene.light();
  const glm::vec3 toLight = l.type == LightType::Spot ? glm::normalize(l.position) : -l.direction;
  const float distanceM = l.type == LightType::Spot ? glm::length(l.position) : 1.0f;  // floor near the origin
  const float texelM = std::max(v.extent.x, v.extent.y) * (v.perspective ? distanceM : 1.0f) / static_cast<float>(kMapSize);
  constexpr float kMargin = 1.5f;
  return kMargin * texels * texelM / std::max(toLight.y, 0.1f);
}

void checkSoftening(const std::string& sceneName) {
  const Scene scene = makeBuiltinScene(sceneName);
  const RenderResult narrow = renderScene(scene, "uniform", "pcf", {{"pcf.radiusTexels", "1"}}, kWidth, kHeight, kMapSize);
  const RenderResult wide = renderScene(scene, "uniform", "pcf", {{"pcf.radiusTexels", "6"}, {"pcf.samples", "32"}}, kWidth, kHeight, kMapSize);
  const RenderResult box = renderScene(scene, "uniform", "pcf", {{"pcf.kernel", "box"}, {"pcf.radiusTexels", "6"}}, kWidth, kHeight, kMapSize);
  const size_t nNarrow = fractionalPixels(narrow), nWide = fractionalPixels(wide), nBox = fractionalPixels(box);
  const float jitterM = floorKernelRadiusM(scene, wide, 6.0f);
  const double darkWide = darkenedUnoccludedFraction(scene, wide, jitterM);
  const double darkBox = darkenedUnoccludedFraction(scene, box, jitterM);
  std::printf("pcf on %s (unoccluded: no caster within %.3f m): penumbra pixels r=1 %zu, r=6 poisson %zu, r=6 box %zu; darkened unoccluded floor %.3f%% / %.3f%%\n",
              sceneName.c_str(), jitterM, nNarrow, nWide, nBox, 100.0 * darkWide, 100.0 * darkBox);
  EXPECT_GT(nNarrow, 20u);
  EXPECT_GT(static_cast<double>(nWide), 2.0 * static_cast<double>(nNarrow));
  EXPECT_GT(static_cast<double>(nBox), 2.0 * static_cast<double>(nNarrow));
  EXPECT_LE(darkWide, 0.005);
  EXPECT_LE(darkBox, 0.005);
}

}  // namespace

TEST(PcfRender, WiderKernelSoftensSpotShadowWithoutAcne) { checkSoftening("pen"); }

TEST(PcfRender, WiderKernelSoftensSunShadowWithoutAcne) { checkSoftening("boxes"); }

TEST(PcfRender, HardwareCompareAgreesWithSoftwareTaps) {
  const Scene scene = makeBuiltinScene("pen");
  const std::vector<std::pair<std::string, std::string>> base = {{"pcf.radiusTexels", "3"}, {"pcf.kernel", "box"}};
  auto hwParams = base;
  hwParams.emplace_back("pcf.hardwareCompare", "on");
  const RenderResult sw = renderScene(scene, "uniform", "pcf", base, kWidth, kHeight, kMapSize);
  const RenderResult hw = renderScene(scene, "uniform", "pcf", hwParams, kWidth, kHeight, kMapSize);
  double sumAbs = 0.0;
  size_t n = 0;
  for (size_t i = 0; i < sw.visibility.size(); ++i) {
    if (!sw.gbuffer.covered(i)) continue;
    sumAbs += std::abs(sw.visibility[i] - hw.visibility[i]);
    ++n;
  }
  const double meanAbs = sumAbs / static_cast<double>(std::max<size_t>(n, 1));
  std::printf("pcf hardware vs software taps: mean |dV| %.5f, penumbra pixels %zu vs %zu\n", meanAbs,
              fractionalPixels(hw), fractionalPixels(sw));
  EXPECT_LT(meanAbs, 0.01);  // both are the same box filter; bilinear taps only smooth it
  EXPECT_GT(fractionalPixels(hw), 20u);
}
