// GLSL unit tests of the moment maths on llvmpipe: the Chebyshev bound (common/chebyshev.glsl),
// the 16-bit quantisation transform and the Hamburger 4MSM reconstruction (common/moments.glsl)
// against double-precision CPU answers. Each test runs one compute dispatch over its cases.
#include "GlFixture.h"
#include "GlslProbe.h"

#include "shared/Bindings.h"

#include <array>
#include <cmath>
#include <random>

using namespace penumbra;
using namespace penumbra::test;

namespace {

// A discrete depth distribution: points z_i with weights w_i (summing to 1).
struct Distribution {
  std::vector<double> z, w;
  std::array<double, 5> moments() const {  // (1, E z, E z², E z³, E z⁴)
    std::array<double, 5> m{};
    for (size_t i = 0; i < z.size(); ++i)
      for (int k = 0; k <= 4; ++k) m[static_cast<size_t>(k)] += w[i] * std::pow(z[i], k);
    return m;
  }
  double fractionInFront(double t) const {
    double f = 0.0;
    for (size_t i = 0; i < z.size(); ++i)
      if (z[i] < t) f += w[i];
    return f;
  }
};

// The largest mass any distribution with moments m can put at t (Christoffel function):
// 1 / (v B⁻¹ v) with v = (1, t, t²) and B the 3x3 Hankel matrix of m. Double precision.
double maxMassAt(const std::array<double, 5>& m, double t) {
  double B[3][3], v[3] = {1.0, t, t * t};
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) B[r][c] = m[static_cast<size_t>(r + c)];
  // Solve B x = v by Gaussian elimination (B is symmetric positive definite here).
  double x[3] = {v[0], v[1], v[2]};
  for (int i = 0; i < 3; ++i)
    for (int r = i + 1; r < 3; ++r) {
      const double f = B[r][i] / B[i][i];
      for (int c = i; c < 3; ++c) B[r][c] -= f * B[i][c];
      x[r] -= f * x[i];
    }
  for (int i = 2; i >= 0; --i) {
    for (int c = i + 1; c < 3; ++c) x[i] -= B[i][c] * x[c];
    x[i] /= B[i][i];
  }
  return 1.0 / (v[0] * x[0] + v[1] * x[1] + v[2] * x[2]);
}

}  // namespace

// p_max = σ² / (σ² + (t − μ)²) for t > μ, 1 otherwise; and it is sharp: for the two-point
// distribution {a, t} with mean μ and variance σ², P(z >= t) equals p_max exactly.
TEST(Moments, ChebyshevBoundForKnownMeanVarianceDepth) {
  struct Case { float mu, var, t; };
  const std::vector<Case> cases = {{0.3f, 0.01f, 0.5f}, {0.5f, 1e-4f, 0.51f}, {0.2f, 0.04f, 0.2f},
                                   {0.6f, 0.02f, 0.4f}, {0.1f, 1e-6f, 0.9f}, {0.45f, 0.0025f, 0.5f}};
  std::vector<glm::vec4> in;
  for (const Case& c : cases) in.emplace_back(c.mu, c.var, c.t, 0.0f);
  // Sharpness: mass q at t and 1 − q at a < t.
  constexpr double kA = 0.2, kT = 0.7, kQ = 0.35;
  const double mu = kQ * kT + (1 - kQ) * kA, var = kQ * (1 - kQ) * (kT - kA) * (kT - kA);
  in.emplace_back(mu, var, kT, 0.0f);
  const std::vector<glm::vec4> out = runProbeCases("chebyshev", std::string(kProbeCaseHeader) + R"(
#include "common/chebyshev.glsl"
void main() {
  vec4 c = i_cases[gl_GlobalInvocationID.x];
  float p = chebyshevUpperBound(c.x, c.y, c.z);
  o_results[gl_GlobalInvocationID.x] = vec4(p, reduceLightBleeding(p, 0.25), meanVariance(vec2(c.x, c.x * c.x + c.y), 1e-3));
}
)", in);
  for (size_t i = 0; i < cases.size(); ++i) {
    const Case& c = cases[i];
    const double d = static_cast<double>(c.t) - c.mu;
    const double expected = d <= 0.0 ? 1.0 : c.var / (c.var + d * d);
    EXPECT_NEAR(out[i].x, expected, 1e-6) << "mu " << c.mu << " var " << c.var << " t " << c.t;
    EXPECT_NEAR(out[i].y, std::clamp((expected - 0.25) / 0.75, 0.0, 1.0), 1e-6);
    EXPECT_NEAR(out[i].w, std::max<double>(c.var, 1e-3), 1e-6) << "variance floor";
  }
  EXPECT_NEAR(out.back().x, kQ, 1e-5) << "Cantelli is attained by the two-point distribution";
}

// The optimised 16-bit basis maps the moments of every depth in [0, 1] into [0, 1]⁴, and decoding
// inverts it.
TEST(Moments, QuantisationTransformRoundTrips) {
  std::vector<glm::vec4> in;
  constexpr int kDepths = 101;
  for (int i = 0; i < kDepths; ++i) in.emplace_back(static_cast<float>(i) / (kDepths - 1), 0.0f, 0.0f, 0.0f);
  const std::vector<glm::vec4> out = runProbeCases("quantisation", std::string(kProbeCaseHeader) + R"(
#include "common/moments.glsl"
shared vec4 unusedShared;
void main() {
  float z = i_cases[gl_GlobalInvocationID.x].x;
  vec4 q = quantizeMoments16(depthMoments(z));
  vec4 back = dequantizeMoments16(q);
  vec4 err = abs(back - depthMoments(z));
  o_results[gl_GlobalInvocationID.x] = vec4(min(min(q.x, q.y), min(q.z, q.w)), max(max(q.x, q.y), max(q.z, q.w)),
                                            max(max(err.x, err.y), max(err.z, err.w)), 0.0);
}
)", in);
  constexpr float kRangeSlack = 1e-5f;    // float rounding of the transform
  constexpr float kRoundTripError = 2e-5f;  // float32 products of terms up to ~80
  for (size_t i = 0; i < in.size(); ++i) {
    EXPECT_GE(out[i].x, -kRangeSlack) << "z " << in[i].x;
    EXPECT_LE(out[i].y, 1.0f + kRangeSlack) << "z " << in[i].x;
    EXPECT_LE(out[i].z, kRoundTripError) << "z " << in[i].x;
  }
}

// Hamburger 4MSM on the biased moments of known two- and three-depth distributions: the result
// L is the sharp lower bound on the fraction of depth in front of t, so for the true (here: the
// bias-mixed) distribution with fraction F, F − ρ(t) <= L <= F, where ρ(t) is the largest mass a
// matching distribution can place at t. Also for moments stored in 16 bits.
TEST(Moments, HamburgerBoundOnTwoAndThreeDepthDistributions) {
  constexpr double kAlpha = 3e-5;       // the α msm.bias's default (10 texels²) gives on boxes
  constexpr double kAlpha16 = 6e-4;     // 16-bit storage: rounding errors of ~1e-5 need a larger bias
  constexpr double kFloatSlack = 2e-3;  // float32 solve of the 3x3 Hankel system
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<Distribution> dists;
  std::vector<double> ts;
  std::vector<int> quantised;
  for (int i = 0; i < 300; ++i) {
    Distribution d;
    const int points = i % 2 == 0 ? 2 : 3;
    for (int k = 0; k < points; ++k) d.z.push_back(0.05 + 0.9 * unit(rng));
    double total = 0.0;
    for (int k = 0; k < points; ++k) { d.w.push_back(0.1 + unit(rng)); total += d.w.back(); }
    for (double& w : d.w) w /= total;
    // Receivers away from the support points (a receiver on a point is its own occluder).
    double t;
    bool nearPoint;
    do {
      t = 0.02 + 0.96 * unit(rng);
      nearPoint = false;
      for (double z : d.z) nearPoint = nearPoint || std::abs(z - t) < 0.02;
    } while (nearPoint);
    dists.push_back(d);
    ts.push_back(t);
    quantised.push_back(i % 3 == 0 ? 1 : 0);
  }
  std::vector<glm::vec4> in;
  for (size_t i = 0; i < dists.size(); ++i) {
    const auto m = dists[i].moments();
    in.emplace_back(m[1], m[2], m[3], m[4]);
    in.emplace_back(ts[i], quantised[i] ? kAlpha16 : kAlpha, quantised[i], 0.0);
  }
  std::vector<glm::vec4> pairs = runProbeCases("hamburger", std::string(kProbeCaseHeader) + R"(
#include "common/moments.glsl"
void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i % 2u == 1u) return;
  vec4 b = i_cases[i];
  vec4 c = i_cases[i + 1u];
  if (c.z > 0.5) {  // through 16-bit UNORM storage: encode, round, decode
    vec4 q = round(clamp(quantizeMoments16(b), 0.0, 1.0) * 65535.0) / 65535.0;
    b = dequantizeMoments16(q);
  }
  b = biasMoments(b, c.y);
  MomentSupport s = momentSupport(b, c.x);
  vec2 blocker = momentBlockerDepth(b, c.x);
  o_results[i] = vec4(hamburgerShadowIntensity(b, c.x), s.w.x, blocker);
}
)", in);
  int outside = 0;
  double worstBelow = 0.0;
  for (size_t i = 0; i < dists.size(); ++i) {
    const glm::vec4 r = pairs[2 * i];
    const double alpha = quantised[i] ? kAlpha16 : kAlpha;
    // The biased moments are those of the mixture (1 − α)·dist + α·(½δ₀ + ½δ₁).
    Distribution mix = dists[i];
    for (double& w : mix.w) w *= 1.0 - alpha;
    mix.z.push_back(0.0), mix.w.push_back(0.5 * alpha);
    mix.z.push_back(1.0), mix.w.push_back(0.5 * alpha);
    const double f = mix.fractionInFront(ts[i]);
    const double rho = maxMassAt(mix.moments(), ts[i]);
    const double slack = kFloatSlack + (quantised[i] ? 5e-3 : 0.0);  // 16-bit rounding of the moments
    const bool ok = r.x <= f + slack && r.x >= f - rho - slack;
    if (!ok && ++outside <= 5)
      ADD_FAILURE() << dists[i].z.size() << " depths, t " << ts[i] << (quantised[i] ? " (16-bit)" : "") << ": L " << r.x
                    << " not in [" << f - rho << ", " << f << "]";
    worstBelow = std::max(worstBelow, f - r.x);
    EXPECT_NEAR(r.y, rho, 0.01 + 0.1 * rho) << "the canonical weight at t is the Christoffel function";
  }
  std::printf("Hamburger 4MSM: %zu distributions, largest F - L %.4f\n", dists.size(), worstBelow);
  EXPECT_EQ(outside, 0);
}

// Two depths, one in front of the receiver: the reconstruction's blockers are that depth, with
// its weight, and the bound is (nearly) exact because two depths leave no freedom.
TEST(Moments, TwoDepthBlockerSearchRecoversTheOccluder) {
  const Distribution d{{0.3, 0.8}, {0.4, 0.6}};
  const auto m = d.moments();
  const std::vector<glm::vec4> in = {{m[1], m[2], m[3], m[4]}, {0.6f, 3e-5f, 0.0f, 0.0f}};
  const std::vector<glm::vec4> out = runProbeCases("blocker", std::string(kProbeCaseHeader) + R"(
#include "common/moments.glsl"
void main() {
  if (gl_GlobalInvocationID.x != 0u) return;
  vec4 b = biasMoments(i_cases[0], i_cases[1].y);
  o_results[0] = vec4(hamburgerShadowIntensity(b, i_cases[1].x), momentBlockerDepth(b, i_cases[1].x), 0.0);
}
)", in);
  EXPECT_NEAR(out[0].x, 0.4, 0.01) << "shadow intensity = the occluder's weight";
  EXPECT_NEAR(out[0].y, 0.3, 0.01) << "blocker depth";
  EXPECT_NEAR(out[0].z, 0.4, 0.01) << "blocker fraction";
}

// A region of one depth (a wall's umbra; a flat floor under a fine map): its moments are
// (z, z², z³, z⁴) up to float rounding, and with a small bias the rounding leaves the Hankel
// matrix singular or indefinite. The bound must then still call a receiver behind the depth
// shadowed and one in front lit (the solve's roots had lit pixels scattered through fence's
// umbra behind its wall), and the blocker search must still find the depth.
TEST(Moments, OneDepthRegionSurvivesRounding) {
  std::vector<glm::vec4> in;
  for (float z : {0.1f, 0.37f, 0.5f, 0.61f, 0.83f, 0.97f})
    for (float alpha : {0.0f, 1e-8f, 1e-7f, 1e-6f})
      for (float dt : {-0.02f, 0.02f}) in.emplace_back(z, alpha, z + dt, 0.0f);
  const std::vector<glm::vec4> out = runProbeCases("one-depth", std::string(kProbeCaseHeader) + R"(
#include "common/moments.glsl"
void main() {
  uint i = gl_GlobalInvocationID.x;
  vec4 c = i_cases[i];
  vec4 b = biasMoments(depthMoments(c.x), c.y);
  o_results[i] = vec4(hamburgerShadowIntensity(b, c.z), momentBlockerDepth(b, c.z), 0.0);
}
)", in);
  int degenerate = 0;
  for (size_t i = 0; i < in.size(); ++i) {
    const glm::vec4 c = in[i], r = out[i];
    const bool behind = c.z > c.x;
    const std::string what = "z " + std::to_string(c.x) + " alpha " + std::to_string(c.y) + " t " + std::to_string(c.z);
    if (behind) {
      EXPECT_GE(r.x, 0.99f) << what << ": shadowed";
      EXPECT_NEAR(r.y, c.x, 0.01f) << what << ": blocker depth";
      EXPECT_GE(r.z, 0.99f) << what << ": blocker fraction";
    } else {
      EXPECT_LE(r.x, 0.01f) << what << ": lit";
      EXPECT_LE(r.z, 0.01f) << what << ": no blocker";
    }
    degenerate += !(std::isfinite(r.x) && std::isfinite(r.y));
  }
  EXPECT_EQ(degenerate, 0);
}
