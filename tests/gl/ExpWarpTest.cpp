// GLSL unit tests of the exponential warps (shadows/filters/exp_warp.shared.h, common/exp_warp.glsl)
// on llvmpipe: esm's and evsm's visibility on known one- and two-depth distributions against
// double-precision CPU answers and against the true lit fraction; no NaN or Inf at the exponent
// limits of 32- and 16-bit storage, in the maths and in rendered maps; and why evsm-soft reads
// its regions from a mip chain and not from a summed-area table (the table's precision).
#include "GlFixture.h"
#include "GlslProbe.h"

#include "frame/SatBuilder.h"
#include "techniques/filters/ExpWarpMaps.h"
#include "techniques/filters/exp_warp.shared.h"
#include "shared/Bindings.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <random>

using namespace penumbra;
using namespace penumbra::test;

namespace {

// A discrete depth distribution: depths z_i with weights w_i (summing to 1).
struct Distribution {
  std::vector<double> z, w;
  double litFraction(double t) const {  // the truth: the share at or beyond the receiver
    double f = 0.0;
    for (size_t i = 0; i < z.size(); ++i) f += z[i] >= t ? w[i] : 0.0;
    return f;
  }
  // E[(p, p², n, n²)] of exp_warp.shared.h's warps, in double.
  std::array<double, 4> warpMoments(double cPositive, double cNegative) const {
    std::array<double, 4> m{};
    for (size_t i = 0; i < z.size(); ++i) {
      const double p = std::exp(cPositive * (2.0 * z[i] - 1.0)), n = -std::exp(-cNegative * (2.0 * z[i] - 1.0));
      m[0] += w[i] * p, m[1] += w[i] * p * p, m[2] += w[i] * n, m[3] += w[i] * n * n;
    }
    return m;
  }
  // E[z], E[z²]: what vsm stores.
  std::array<double, 2> depthMoments() const {
    std::array<double, 2> m{};
    for (size_t i = 0; i < z.size(); ++i) m[0] += w[i] * z[i], m[1] += w[i] * z[i] * z[i];
    return m;
  }
};

// Chebyshev's bound on one warp in double, as common/exp_warp.glsl takes it (relative to w_t,
// the floor relative to the mean warp²).
double relativeChebyshev(double mean1, double mean2, double wt, double floorRelative) {
  const double mean = mean1 / wt, second = mean2 / (wt * wt);
  const double variance = std::max(second - mean * mean, mean * mean * floorRelative);
  const double m = wt > 0.0 ? mean : 2.0 - mean;
  if (1.0 <= m) return 1.0;
  return variance / (variance + (1.0 - m) * (1.0 - m));
}

double evsmCpu(const std::array<double, 4>& m, double cPositive, double cNegative, double t, double floorRelative,
               bool both) {
  const double pt = std::exp(cPositive * (2.0 * t - 1.0)), nt = -std::exp(-cNegative * (2.0 * t - 1.0));
  double v = relativeChebyshev(m[0], m[1], pt, floorRelative);
  if (both) v = std::min(v, relativeChebyshev(m[2], m[3], nt, floorRelative));
  return v;
}

// One- and two-depth distributions with receivers kept kMinGap from every depth (a receiver on a
// depth is its own occluder, a matter of bias, not of the bound).
struct Case {
  Distribution d;
  double t;
};
std::vector<Case> randomCases(int count, uint32_t seed) {
  constexpr double kMinGap = 0.01;  // linear depth
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<Case> out;
  for (int i = 0; i < count; ++i) {
    Case c;
    const int points = i % 3 == 0 ? 1 : 2;
    for (int k = 0; k < points; ++k) c.d.z.push_back(0.05 + 0.9 * unit(rng));
    c.d.w = points == 1 ? std::vector<double>{1.0} : std::vector<double>{0.1 + 0.8 * unit(rng)};
    if (points == 2) c.d.w.push_back(1.0 - c.d.w[0]);
    bool near;
    do {
      c.t = 0.02 + 0.96 * unit(rng);
      near = false;
      for (double z : c.d.z) near = near || std::abs(z - c.t) < kMinGap;
    } while (near);
    out.push_back(c);
  }
  return out;
}

}  // namespace

// esm: V = min(E[p] / p(t), 1) = min(Σ w_i exp(2c (z_i − t)), 1) exactly, and never below the true
// lit fraction (each term is >= 1 where z_i >= t); an occluder close in front of the receiver lets
// most of the light through (the contact artifact: e^(-2cδ)).
TEST(ExpWarps, EsmOnOneAndTwoDepths) {
  std::vector<Case> cases = randomCases(300, 5);
  const std::vector<double> exponents = {10.0, 40.0, PN_EXP_WARP_MAX_LOG_FLOAT32};
  std::vector<glm::vec4> in;
  for (size_t i = 0; i < cases.size(); ++i) {
    const double c = exponents[i % exponents.size()];
    in.emplace_back(static_cast<float>(cases[i].d.warpMoments(c, 0.0)[0]), c, cases[i].t, 0.0f);
  }
  const std::vector<glm::vec4> out = runProbeCases("esm", std::string(kProbeCaseHeader) + R"(
#include "common/exp_warp.glsl"
void main() {
  vec4 c = i_cases[gl_GlobalInvocationID.x];
  o_results[gl_GlobalInvocationID.x] = vec4(esmVisibility(c.x, c.y, c.z), 0.0, 0.0, 0.0);
}
)", in);
  constexpr double kRelativeTolerance = 1e-5;  // float32 division and exp
  int belowTruth = 0;
  for (size_t i = 0; i < cases.size(); ++i) {
    const double c = exponents[i % exponents.size()];
    double expected = 0.0;
    for (size_t k = 0; k < cases[i].d.z.size(); ++k) expected += cases[i].d.w[k] * std::exp(2.0 * c * (cases[i].d.z[k] - cases[i].t));
    expected = std::min(expected, 1.0);
    EXPECT_NEAR(out[i].x, expected, kRelativeTolerance * expected + 1e-30) << "case " << i << " c " << c;
    belowTruth += out[i].x < cases[i].d.litFraction(cases[i].t) - kRelativeTolerance ? 1 : 0;
  }
  EXPECT_EQ(belowTruth, 0) << "esm darker than the lit fraction";
  // The contact: one occluder 0.005 of the depth range in front of the receiver, c = 40.
  const std::vector<glm::vec4> contact = runProbeCases("esm contact", std::string(kProbeCaseHeader) + R"(
#include "common/exp_warp.glsl"
void main() { o_results[0] = vec4(esmVisibility(positiveWarp(0.5, 40.0), 40.0, 0.505)); }
)", {glm::vec4(0.0f)});
  EXPECT_NEAR(contact[0].x, std::exp(-0.4), 1e-5) << "a shadowed receiver 0.5 % behind its occluder reads 67 % lit";
}

// evsm on one- and two-depth distributions, 32-bit moments: the same numbers as a double-precision
// evaluation of the same formulas; never below the true lit fraction (Chebyshev's bound on a warp
// is an upper bound, and the min of two upper bounds is one); sharp on the two-point distribution
// {occluder, receiver}; and where two occluders stand in front of the receiver, the textbook
// light bleeding of vsm, far below vsm.
TEST(ExpWarps, EvsmBoundsOnOneAndTwoDepthDistributions) {
  struct Exponents { double positive, negative; };
  const std::vector<Exponents> exponents = {{40.0, 5.0}, {43.0, 43.0}, {5.5, 5.5}, {10.0, 20.0}};
  constexpr double kStorageFloor = PN_EXP_WARP_MIN_RELATIVE_VARIANCE_FLOAT32;
  const std::vector<Case> cases = randomCases(400, 17);
  std::vector<glm::vec4> in;
  for (size_t i = 0; i < cases.size(); ++i) {
    const Exponents e = exponents[i % exponents.size()];
    const auto m = cases[i].d.warpMoments(e.positive, e.negative);
    in.emplace_back(m[0], m[1], m[2], m[3]);
    in.emplace_back(e.positive, e.negative, cases[i].t, kStorageFloor);
  }
  const std::string probe = std::string(kProbeCaseHeader) + R"(
#include "common/exp_warp.glsl"
void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i % 2u == 1u) return;
  vec4 m = i_cases[i], c = i_cases[i + 1u];
  o_results[i] = vec4(evsmVisibility(m, c.xy, c.z, 0.0, c.w, false), evsmVisibility(m, c.xy, c.z, 0.0, c.w, true),
                      0.0, 0.0);
}
)";
  const std::vector<glm::vec4> out = runProbeCases("evsm", probe, in);
  // float32 moments and arithmetic (measured: 4e-7 at most).
  constexpr double kTolerance = 1e-5;
  int belowTruth = 0;
  double worst = 0.0;
  for (size_t i = 0; i < cases.size(); ++i) {
    const Exponents e = exponents[i % exponents.size()];
    std::array<double, 4> m;
    for (int k = 0; k < 4; ++k) m[static_cast<size_t>(k)] = in[2 * i][k];  // the float32 moments the GPU read
    const double f = cases[i].d.litFraction(cases[i].t);
    const glm::vec4 r = out[2 * i];
    for (int both = 0; both < 2; ++both) {
      const double expected = evsmCpu(m, e.positive, e.negative, cases[i].t, kStorageFloor, both != 0);
      const double v = both ? r.y : r.x;
      worst = std::max(worst, std::abs(v - expected));
      EXPECT_NEAR(v, expected, kTolerance) << "case " << i << (both ? " 4" : " 2") << " components";
      belowTruth += v < f - kTolerance ? 1 : 0;
    }
    EXPECT_LE(r.y, r.x + 1e-6) << "4 components never above 2";
  }
  std::printf("evsm: %zu distributions, largest |GPU - CPU| %.2g\n", cases.size(), worst);
  EXPECT_EQ(belowTruth, 0) << "a bound below the true lit fraction";

  // Sharpness and bleeding, c+ = 40, c− = 5: (a) occluder at 0.4 (weight 0.3) and the receiver's
  // own depth 0.6: V = 0.7; (b) two occluders, 0.3 and 0.55 (half each), receiver at 0.6.
  const Distribution sharp{{0.4, 0.6}, {0.3, 0.7}}, bleed{{0.3, 0.55}, {0.5, 0.5}};
  constexpr double kT = 0.6;
  std::vector<glm::vec4> special;
  for (const Distribution& d : {sharp, bleed}) {
    const auto m = d.warpMoments(40.0, 5.0);
    special.emplace_back(m[0], m[1], m[2], m[3]);
    special.emplace_back(40.0f, 5.0f, kT, kStorageFloor);
  }
  const std::vector<glm::vec4> s = runProbeCases("evsm special", probe, special);
  EXPECT_NEAR(s[0].y, 0.7, 1e-3) << "Cantelli is attained by {occluder, receiver}, through the warp too";
  const auto vm = bleed.depthMoments();
  const double vsmBound = [&] {
    const double var = vm[1] - vm[0] * vm[0], d = kT - vm[0];
    return var / (var + d * d);
  }();
  std::printf("two occluders in front: vsm %.3f, evsm 2 components %.2g, 4 components %.2g (truth 0)\n", vsmBound,
              s[2].x, s[2].y);
  EXPECT_GT(vsmBound, 0.3) << "the configuration bleeds with vsm";
  EXPECT_LT(s[2].y, 0.01 * vsmBound) << "the warp takes the bleeding out";
}

// At the largest exponents each storage allows (the parameters' maximum, clamped for float16),
// the moments of the nearest and farthest depths, stored in that format, give finite moments and
// a visibility in [0, 1] for receivers at both ends and in between, and so do esm's at c = 86.
// Raising a limit in exp_warp.shared.h breaks this (float16: e^12 = 162755 is infinite in a half).
TEST(ExpWarps, NoNanOrInfAtTheExponentLimitsInTheMaths) {
  std::vector<glm::vec4> in;
  for (ExpWarpStorage storage : {ExpWarpStorage::Float32, ExpWarpStorage::Float16}) {
    const float c = maxWarpExponent(storage, 2);
    for (float zMix : {0.0f, 0.5f, 1.0f})      // weight of depth 0 (the rest at depth 1)
      for (float t : {0.0f, 0.25f, 1.0f})      // receiver
        for (float slope : {0.0f, 1.0f, 100.0f})  // the shadow pass's slope term, depth units per texel
          in.emplace_back(c, zMix + 2.0f * t, slope, storage == ExpWarpStorage::Float16 ? 1.0f : 0.0f);
  }
  ASSERT_EQ(maxWarpExponent(ExpWarpStorage::Float32, 1), PN_EXP_WARP_MAX_LOG_FLOAT32);
  const std::vector<glm::vec4> out = runProbeCases("limits", std::string(kProbeCaseHeader) + R"(
#include "common/exp_warp.glsl"
float stored(float v, bool isHalf) { return isHalf ? unpackHalf2x16(packHalf2x16(vec2(v, 0.0))).x : v; }
// The texel moments as passes/exp_warp.frag.glsl writes them, through the storage.
vec4 texelMoments(float z, float c, float slopeVariance, float largest, bool isHalf) {
  vec4 m = expWarpMoments(z, c, c);
  m.y = min(m.y * (1.0 + 4.0 * c * c * slopeVariance), largest);
  m.w = min(m.w * (1.0 + 4.0 * c * c * slopeVariance), largest);
  return vec4(stored(m.x, isHalf), stored(m.y, isHalf), stored(m.z, isHalf), stored(m.w, isHalf));
}
void main() {
  vec4 k = i_cases[gl_GlobalInvocationID.x];
  float c = k.x, w0 = fract(k.y), t = floor(k.y) * 0.5;
  bool isHalf = k.w > 0.5;
  float largest = exp(isHalf ? PN_EXP_WARP_MAX_LOG_FLOAT16 : PN_EXP_WARP_MAX_LOG_FLOAT32);
  float slopeVariance = 0.25 * 2.0 * k.z * k.z;
  vec4 a = texelMoments(0.0, c, slopeVariance, largest, isHalf), b = texelMoments(1.0, c, slopeVariance, largest, isHalf);
  vec4 m = w0 * a + (1.0 - w0) * b;
  float floorRelative = isHalf ? PN_EXP_WARP_MIN_RELATIVE_VARIANCE_FLOAT16 : PN_EXP_WARP_MIN_RELATIVE_VARIANCE_FLOAT32;
  float v = evsmVisibility(m, vec2(c), t, 1e-4, floorRelative, true);
  float esmC = PN_EXP_WARP_MAX_LOG_FLOAT32;
  float esm = esmVisibility(w0 * positiveWarp(0.0, esmC) + (1.0 - w0) * positiveWarp(1.0, esmC), esmC, t);
  bool finite = !any(isinf(a)) && !any(isnan(a)) && !any(isinf(b)) && !any(isnan(b));
  o_results[gl_GlobalInvocationID.x] = vec4(finite ? 1.0 : 0.0, v, esm, 0.0);
}
)", in);
  for (size_t i = 0; i < in.size(); ++i) {
    const std::string what = fmt::format("c {} case {} slope {} {}", in[i].x, in[i].y, in[i].z, in[i].w > 0.5f ? "float16" : "float32");
    EXPECT_EQ(out[i].x, 1.0f) << "moments not finite: " << what;
    EXPECT_TRUE(std::isfinite(out[i].y) && out[i].y >= 0.0f && out[i].y <= 1.0f) << "evsm V " << out[i].y << ": " << what;
    EXPECT_TRUE(std::isfinite(out[i].z) && out[i].z >= 0.0f && out[i].z <= 1.0f) << "esm V " << out[i].z << ": " << what;
  }
}

namespace {

// Every value of every mip level of a float texture, finite?
bool allFinite(const gl::Texture& t) {
  for (int level = 0; level < t.levels(); ++level) {
    const size_t texels = static_cast<size_t>(std::max(t.width() >> level, 1)) *
                          static_cast<size_t>(std::max(t.height() >> level, 1)) * static_cast<size_t>(t.layers());
    std::vector<float> v(texels * 4);
    t.read(GL_RGBA, GL_FLOAT, v.data(), v.size() * sizeof(float), level);
    for (float x : v)
      if (!std::isfinite(x)) return false;
  }
  return true;
}

}  // namespace

// The same through the real pipeline: fence from behind its wall (depths from the wall's foot to
// the far floor) with every exponent at its parameter's maximum, in both storages: the maps and
// every mip level finite, V finite and in [0, 1].
TEST(ExpWarps, NoNanOrInfAtTheExponentLimitsInRenderedMaps) {
  Scene scene = makeBuiltinScene("fence");
  scene.camera = parseCameraArgument("4,3,-6:0,0,-3.5:50", scene.camera);
  const std::string maxEvsm = fmt::format("{}", PN_EXP_WARP_MAX_LOG_FLOAT32 / 2.0f);
  const std::vector<std::pair<std::string, Params>> configs = {
      {"esm", {{"esm.exponent", fmt::format("{}", PN_EXP_WARP_MAX_LOG_FLOAT32)}}},
      {"evsm", {{"evsm.storage", "float32"}, {"evsm.positiveExponent", maxEvsm}, {"evsm.negativeExponent", maxEvsm}}},
      {"evsm", {{"evsm.storage", "float16"}, {"evsm.positiveExponent", maxEvsm}, {"evsm.negativeExponent", maxEvsm}}},
      {"evsm", {{"evsm.storage", "float16"}, {"evsm.components", "2"}, {"evsm.positiveExponent", maxEvsm}}},
      {"evsm-soft", {{"evsm-soft.storage", "float16"}, {"evsm-soft.positiveExponent", maxEvsm}, {"evsm-soft.negativeExponent", maxEvsm}}},
      {"evsm-soft", {{"evsm-soft.storage", "float32"}, {"evsm-soft.positiveExponent", maxEvsm}, {"evsm-soft.negativeExponent", maxEvsm}}},
  };
  constexpr int kW = 128, kH = 72, kMap = 512;
  for (const auto& [filter, params] : configs) {
    const std::unique_ptr<Renderer> r = makeTestRenderer(scene, "uniform", filter, params, kMap);
    RenderOptions o;
    o.width = kW;
    o.height = kH;
    r->render(o);
    std::string what = filter;
    for (const auto& [k, v] : params) what += " " + k + "=" + v;
    const std::vector<DebugImage> images = r->debugImages();
    const auto moments = std::find_if(images.begin(), images.end(), [&](const DebugImage& d) {
      return d.name.find("moments") != std::string::npos || d.name.find("warp") != std::string::npos;
    });
    ASSERT_NE(moments, images.end()) << what;
    EXPECT_TRUE(allFinite(*moments->texture)) << what << ": a stored moment is Inf or NaN";
    const std::vector<float> v = r->readVisibility();
    ASSERT_EQ(v.size(), static_cast<size_t>(kW * kH));
    const size_t bad = static_cast<size_t>(std::count_if(v.begin(), v.end(), [](float x) { return !(x >= 0.0f && x <= 1.0f); }));
    EXPECT_EQ(bad, 0u) << what << ": V not finite or outside [0, 1]";
  }
}

// Why evsm-soft reads its regions from the mip chain and not from a summed-area table like vssm:
// a table holds sums over the whole map with an absolute precision (common/sat.glsl: each value
// rounded to 2^-31 of the largest, here the far plane's warp, normalised to 1), where the bound
// needs precision relative to the receiver's own warp w_t, and to w_t² for the variance. A map
// whose left half lies at depth 1 and whose right half is flat at depth t: the mean and variance
// of the warp w = exp(2c (z − 1)) over a flat 16² box, relative to w_t (truth: 1 and 0), from a
// table of w (SatBuilder's 64-bit fixed point; it forms w² itself) and from a mip chain of
// (w, w²) in RG32F. The table's variance error grows as 2^-32 · e^(4c(1 − t)): harmless at c = 5,
// useless at evsm's exponents for receivers in the middle of the depth range; the chain's stays
// at float rounding.
TEST(ExpWarps, SummedAreaTablesLoseTheWarpsOfReceiversNearTheLight) {
  constexpr int kSide = 512, kBox = 16, kMipLevel = 4;  // a level-4 texel is a 16² box
  static_assert(1 << kMipLevel == kBox);
  constexpr int kBoxX = 24 * kBox, kBoxY = 16 * kBox;   // inside the right half
  glContext();
  ShaderLibrary shaders;
  const gl::Program query = compileProbe("sat warp query", std::string(kProbeCaseHeader) + R"(
#include "common/sat.glsl"
void main() {
  vec4 c = i_cases[0];
  dvec2 m = satTexelRectMean(ivec2(c.z), ivec2(c.xy), ivec2(c.xy) + ivec2(c.w) - 1, 0);
  double wt = double(i_cases[1].x);
  o_results[0] = vec4(float(m.x / wt - 1.0LF), float((m.y - m.x * m.x) / (wt * wt)), 0.0, 0.0);
}
)");
  struct Row { double c, t, satMean, satVariance, mipMean, mipVariance; };
  std::vector<Row> rows;
  for (double c : {5.0, 10.0, 20.0, 40.0})
    for (double t : {0.5, 0.8, 0.95}) {
      const float wFar = 1.0f, wt = static_cast<float>(std::exp(2.0 * c * (t - 1.0)));
      std::vector<float> w(static_cast<size_t>(kSide) * kSide);
      std::vector<glm::vec2> moments(w.size());
      for (int y = 0; y < kSide; ++y)
        for (int x = 0; x < kSide; ++x) {
          const size_t i = static_cast<size_t>(y) * kSide + static_cast<size_t>(x);
          w[i] = x < kSide / 2 ? wFar : wt;
          moments[i] = glm::vec2(w[i], w[i] * w[i]);
        }
      gl::Texture warp("sat warp test", {GL_TEXTURE_2D_ARRAY, GL_R32F, kSide, kSide, 1, 1});
      warp.setSampling(GL_NEAREST, GL_NEAREST);
      glTextureSubImage3D(warp.id(), 0, 0, 0, 0, kSide, kSide, 1, GL_RED, GL_FLOAT, w.data());
      SatBuilder sat;
      sat.build(shaders, warp, 2);
      sat.bindTable();
      const std::vector<glm::vec4> in = {glm::vec4(kBoxX, kBoxY, kSide, kBox), glm::vec4(wt, 0.0f, 0.0f, 0.0f)};
      gl::Buffer inBuffer("sat warp query in", in.size() * sizeof(glm::vec4), in.data());
      std::vector<glm::vec4> out(2);
      gl::Buffer outBuffer("sat warp query out", out.size() * sizeof(glm::vec4), out.data());
      inBuffer.bindBase(GL_SHADER_STORAGE_BUFFER, PN_SSBO_AUX);
      outBuffer.bindBase(GL_SHADER_STORAGE_BUFFER, PN_SSBO_TEST);
      query.use();
      glDispatchCompute(1, 1, 1);
      glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
      outBuffer.download(out.data(), out.size() * sizeof(glm::vec4));

      gl::Texture chain("mip warp test", {GL_TEXTURE_2D_ARRAY, GL_RG32F, kSide, kSide, 1, kMipLevel + 1});
      glTextureSubImage3D(chain.id(), 0, 0, 0, 0, kSide, kSide, 1, GL_RG, GL_FLOAT, moments.data());
      glGenerateTextureMipmap(chain.id());
      const int levelSide = kSide >> kMipLevel;
      std::vector<glm::vec4> level(static_cast<size_t>(levelSide) * levelSide);
      chain.read(GL_RGBA, GL_FLOAT, level.data(), level.size() * sizeof(glm::vec4), kMipLevel);
      const glm::vec4 box = level[static_cast<size_t>(kBoxY / kBox) * levelSide + static_cast<size_t>(kBoxX / kBox)];
      const double mean = box.x, second = box.y;
      rows.push_back({c, t, out[0].x, out[0].y, mean / wt - 1.0, (second - mean * mean) / (double(wt) * wt)});
    }
  std::printf("warp w = exp(2c (z - 1)) over a flat 16² box at depth t, relative to w_t (truth 0, 0):\n"
              "   c      t   SAT mean     SAT variance   mip mean     mip variance\n");
  for (const Row& r : rows)
    std::printf("  %4.0f  %5.2f  %10.3g  %14.3g  %10.3g  %14.3g\n", r.c, r.t, r.satMean, r.satVariance, r.mipMean,
                r.mipVariance);
  // The mip chain: float rounding of w and w², whatever c and t.
  constexpr double kMipTolerance = 1e-6;
  for (const Row& r : rows) {
    EXPECT_LE(std::abs(r.mipMean), kMipTolerance) << "c " << r.c << " t " << r.t;
    EXPECT_LE(std::abs(r.mipVariance), kMipTolerance) << "c " << r.c << " t " << r.t;
  }
  const auto row = [&](double c, double t) {
    return *std::find_if(rows.begin(), rows.end(), [&](const Row& r) { return r.c == c && r.t == t; });
  };
  // The table where the warp's range is small: as good as the chain (e^(4c(1 − t)) = e^1).
  EXPECT_LE(std::abs(row(5.0, 0.95).satVariance), kMipTolerance);
  // At evsm's c+ = 40 a receiver at mid depth (w_t = e^-40) is below the table's resolution:
  // its warp reads 0 or noise, the bound is meaningless.
  EXPECT_GE(std::abs(row(40.0, 0.5).satMean), 0.5);
  // c = 20 at t = 0.8: variance error ~2^-32 · e^16 = 2e-3, the size of the bound's own floor
  // ((2c · 2 texels of depth)² ≈ 1e-3 … 1e-2): already unusable.
  EXPECT_GE(std::abs(row(20.0, 0.8).satVariance), 1e-4);
}
