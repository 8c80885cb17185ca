// The prefiltered filters (vsm, vssm, msm, msm-soft, esm, evsm, evsm-soft) end to end: shadows
// where the geometry says for the sun (orthographic), the spot (perspective) and cascades; no
// self-shadowing on a grazing plane; against the Embree reference, msm's and msm-soft's light
// leaks on `fence` below vsm's and vssm's, and at most half of them behind the wall, where the
// leaks are light bleeding, as are evsm's and evsm-soft's (FenceBehindTheWallIsLightBleeding);
// esm near contacts: less over-darkening than vsm, more light behind a thin caster; vssm's RMSE
// on `pen` within 1.5x of pcss's.
// Benchmarks (disabled, run with --gtest_also_run_disabled_tests) print the visibility-pass times
// of the issue's note.
#include "GlFixture.h"
#include "GlslProbe.h"
#include "TestGeometry.h"

#include "comparison/Shimmer.h"
#include "techniques/filters/esm.shared.h"
#include "techniques/filters/evsm.shared.h"
#include "techniques/filters/evsm_soft.shared.h"
#include "techniques/filters/exp_warp.shared.h"
#include "techniques/filters/msm.shared.h"
#include "techniques/filters/msm_soft.shared.h"
#include "techniques/filters/vsm.shared.h"
#include "techniques/filters/vssm.shared.h"

#include <penumbra/Metrics.h>
#include <penumbra/Reference.h>

#include <fmt/format.h>

#include <algorithm>
#include <cstdio>
#include <random>
#include <stdexcept>

using namespace penumbra;
using namespace penumbra::test;

namespace {


struct Variant {
  std::string name, filter;
  Params params;
};

// Every storage/source choice of the prefiltered filters.
const std::vector<Variant>& variants() {
  static const std::vector<Variant> list = {
      {"vsm", "vsm", {}},
      {"vssm sat", "vssm", {{"vssm.source", "sat"}}},
      {"vssm mip", "vssm", {{"vssm.source", "mip"}}},
      {"msm float32", "msm", {{"msm.storage", "float32"}}},
      {"msm quantized16", "msm", {{"msm.storage", "quantized16"}}},
      {"msm-soft", "msm-soft", {}},
      {"esm", "esm", {}},
      {"evsm 2", "evsm", {{"evsm.components", "2"}}},
      {"evsm 4", "evsm", {{"evsm.components", "4"}}},
      {"evsm 4 float16", "evsm", {{"evsm.components", "4"}, {"evsm.storage", "float16"}}},
      {"evsm-soft", "evsm-soft", {}},
  };
  return list;
}

const Variant& variant(const std::string& name) {
  for (const Variant& v : variants())
    if (v.name == name) return v;
  throw std::logic_error("no variant " + name);
}

Params with(Params p, const Params& more) {
  p.insert(p.end(), more.begin(), more.end());
  return p;
}

constexpr int kMapSize = 1024;
// Floor pixels robustly in or out of the hard shadow: perKind of each kind.
FloorProbes hardProbes(const Scene& scene, const GBufferData& g, int perKind, float jitterM) {
  return floorProbes(scene, g, static_cast<size_t>(perKind), jitterM, 3, perKind * 200);
}

ReferenceResult traceReference(const Scene& scene, const GBufferData& g) {
  ReferenceTracer tracer(scene);
  ReferenceOptions o;
  o.samples = 256;
  o.progress = false;
  o.useCache = false;
  return tracer.trace(g, scene.light(), o);
}

// A filter and a projection on a scene: shadowed probes dark, lit probes lit.
void expectProbes(const std::string& sceneName, const std::string& projection, float lightSize, float jitterM) {
  const Scene scene = makeBuiltinScene(sceneName);
  constexpr int kW = 192, kH = 108;
  constexpr int kProbesPerKind = 150;
  const Params light = {{"light.size", fmt::format("{}", lightSize)}};
  const RenderResult hard = renderScene(scene, projection, "hard", light, kW, kH, kMapSize);
  const FloorProbes probes = hardProbes(scene, hard.gbuffer, kProbesPerKind, jitterM);
  ASSERT_GE(probes.shadowed.size(), 20u) << sceneName;
  ASSERT_GE(probes.lit.size(), 20u) << sceneName;
  constexpr float kDarkV = 0.2f, kLitV = 0.8f;  // a probe is right when V is beyond these
  constexpr double kMaxWrong = 0.02;            // share of probes allowed to miss (map texels at edges)
  for (const Variant& v : variants()) {
    const RenderResult r = renderScene(scene, projection, v.filter, with(v.params, light), kW, kH, kMapSize);
    ASSERT_GE(r.frusta.views.size(), 1u);
    int wrongShadowed = 0, wrongLit = 0;
    for (size_t i : probes.shadowed) wrongShadowed += r.visibility[i] > kDarkV ? 1 : 0;
    for (size_t i : probes.lit) wrongLit += r.visibility[i] < kLitV ? 1 : 0;
    std::printf("%-8s %-8s %zu views %-16s: %d/%zu shadowed probes lit, %d/%zu lit probes dark\n", sceneName.c_str(),
                projection.c_str(), r.frusta.views.size(), v.name.c_str(), wrongShadowed, probes.shadowed.size(), wrongLit,
                probes.lit.size());
    EXPECT_LE(wrongShadowed, kMaxWrong * static_cast<double>(probes.shadowed.size())) << v.name << " on " << sceneName;
    EXPECT_LE(wrongLit, kMaxWrong * static_cast<double>(probes.lit.size())) << v.name << " on " << sceneName;
  }
}

GLint uniformOffset(GLuint program, const char* name) {
  const GLuint index = glGetProgramResourceIndex(program, GL_UNIFORM, name);
  if (index == GL_INVALID_INDEX) return -1;
  const GLenum prop = GL_OFFSET;
  GLint offset = -1;
  glGetProgramResourceiv(program, GL_UNIFORM, index, 1, &prop, 1, nullptr, &offset);
  return offset;
}

}  // namespace

// The filters' uniform blocks: the driver's std140 offsets are the C++ ones.
TEST(VarianceFilters, UniformBlocksMatchCpp) {
  glContext();
  const gl::Program probe = compileProbe("prefiltered blocks", R"(
#include "shared/Bindings.h"
#include "techniques/filters/msm.shared.h"
#include "techniques/filters/msm_soft.shared.h"
#include "techniques/filters/vsm.shared.h"
#include "techniques/filters/vssm.shared.h"
#include "techniques/filters/esm.shared.h"
#include "techniques/filters/evsm.shared.h"
#include "techniques/filters/evsm_soft.shared.h"
#include "techniques/filters/exp_warp.shared.h"
layout(local_size_x = 1) in;
layout(std140, binding = 0) uniform A { VsmUniforms u_vsm; };
layout(std140, binding = 1) uniform B { VssmUniforms u_vssm; };
layout(std140, binding = 2) uniform C { MsmUniforms u_msm; };
layout(std140, binding = 3) uniform D { MsmSoftUniforms u_msmSoft; };
layout(std140, binding = 4) uniform E { EsmUniforms u_esm; };
layout(std140, binding = 5) uniform F { EvsmUniforms u_evsm; };
layout(std140, binding = 6) uniform G { EvsmSoftUniforms u_evsmSoft; };
layout(std140, binding = 7) uniform H { ExpWarpUniforms u_warp; };
layout(std430, binding = PN_SSBO_TEST) buffer Out { vec4 o; };
void main() {
  o = u_vsm.params + vec4(u_vsm.mode) + u_vssm.params + vec4(u_vssm.mode) + u_msm.params + vec4(u_msm.mode) + u_msmSoft.params
    + u_esm.params + vec4(u_esm.mode) + u_evsm.warp + u_evsm.params + vec4(u_evsm.mode) + u_evsmSoft.warp
    + u_evsmSoft.params + vec4(u_evsmSoft.mode) + u_warp.warp;
}
)");
  // The driver's block sizes (modes and kernels are compiled in; what is left is in the blocks).
  const auto blockBytes = [&](const char* block) {
    GLint bytes = 0;
    glGetActiveUniformBlockiv(probe.id(), glGetUniformBlockIndex(probe.id(), block), GL_UNIFORM_BLOCK_DATA_SIZE, &bytes);
    return bytes;
  };
  EXPECT_EQ(blockBytes("A"), GLint(sizeof(gpu::VsmUniforms)));
  EXPECT_EQ(blockBytes("B"), GLint(sizeof(gpu::VssmUniforms)));
  EXPECT_EQ(blockBytes("C"), GLint(sizeof(gpu::MsmUniforms)));
  EXPECT_EQ(blockBytes("D"), GLint(sizeof(gpu::MsmSoftUniforms)));
  EXPECT_EQ(uniformOffset(probe.id(), "u_msmSoft.params"), GLint(offsetof(gpu::MsmSoftUniforms, params)));
  EXPECT_EQ(uniformOffset(probe.id(), "u_esm.mode"), GLint(offsetof(gpu::EsmUniforms, mode)));
  EXPECT_EQ(uniformOffset(probe.id(), "u_evsm.params"), GLint(offsetof(gpu::EvsmUniforms, params)));
  EXPECT_EQ(uniformOffset(probe.id(), "u_evsm.mode"), GLint(offsetof(gpu::EvsmUniforms, mode)));
  EXPECT_EQ(uniformOffset(probe.id(), "u_evsmSoft.params"), GLint(offsetof(gpu::EvsmSoftUniforms, params)));
  EXPECT_EQ(uniformOffset(probe.id(), "u_evsmSoft.mode"), GLint(offsetof(gpu::EvsmSoftUniforms, mode)));
  EXPECT_EQ(uniformOffset(probe.id(), "u_warp.warp"), GLint(offsetof(gpu::ExpWarpUniforms, warp)));
}

TEST(VarianceFilters, SunOrthographicProbes) { expectProbes("boxes", "uniform", 0.005f, 0.06f); }
// The pencil's shadow is 8 cm wide; vsm and msm average over the pixel's footprint (~3 cm on the
// floor at this size), so probes keep 2.5 cm from the edges.
TEST(VarianceFilters, SpotPerspectiveProbes) { expectProbes("pen", "uniform", 0.01f, 0.025f); }
TEST(VarianceFilters, SunCascadeProbes) { expectProbes("boxes", "csm", 0.005f, 0.06f); }
TEST(VarianceFilters, SpotCascadeProbes) { expectProbes("pen", "csm", 0.01f, 0.025f); }

// A plane lit 80 degrees from its normal, nothing above most of it: no filter may darken it.
TEST(VarianceFilters, NoSelfShadowingOnAGrazingPlane) {
  const Scene scene = makeBuiltinScene("grazing");
  constexpr int kW = 192, kH = 108;
  const RenderResult hard = renderScene(scene, "uniform", "hard", {}, kW, kH, kMapSize);
  const FloorProbes probes = hardProbes(scene, hard.gbuffer, 400, 0.1f);
  ASSERT_GE(probes.lit.size(), 200u);
  constexpr float kAcneV = 0.9f;         // a lit floor pixel darker than this is self-shadowed
  constexpr double kMaxAcneShare = 0.005;
  for (const Variant& v : variants()) {
    const RenderResult r = renderScene(scene, "uniform", v.filter, v.params, kW, kH, kMapSize);
    int acne = 0;
    for (size_t i : probes.lit) acne += r.visibility[i] < kAcneV ? 1 : 0;
    std::printf("grazing %-16s: %d/%zu lit floor probes below V=%.1f\n", v.name.c_str(), acne, probes.lit.size(), kAcneV);
    EXPECT_LE(acne, kMaxAcneShare * static_cast<double>(probes.lit.size())) << v.name;
  }
}

// The contact band: floor pixels within this distance (horizontally) of a caster, where the wall
// and the slats stand on the floor.
constexpr float kContactBandM = 0.5f;

// hard, pcss and every variant on `fence` (kFenceW x kFenceH, 1024² map) against one reference, printed as
// the table of docs/msm.md; and the same metrics over the floor near contacts (floorNearCasters).
struct FenceLeaks {
  std::vector<std::pair<std::string, VisibilityMetrics>> results, nearContacts;
  ReferenceResult ref;
  VisibilityMetrics get(const std::string& name) const { return find(results, name); }
  VisibilityMetrics nearContact(const std::string& name) const { return find(nearContacts, name); }

private:
  static VisibilityMetrics find(const std::vector<std::pair<std::string, VisibilityMetrics>>& list, const std::string& name) {
    for (const auto& [n, m] : list)
      if (n == name) return m;
    ADD_FAILURE() << name;
    return VisibilityMetrics{};
  }
};

constexpr int kFenceW = 256, kFenceH = 144;

FenceLeaks measureFenceLeaks(const Scene& scene, const char* view) {
  FenceLeaks out;
  ReferenceResult& ref = out.ref;
  std::vector<uint8_t> band;
  std::vector<Variant> list = {Variant{"hard", "hard", {}}, Variant{"pcss", "pcss", {}}};
  list.insert(list.end(), variants().begin(), variants().end());
  for (const Variant& v : list) {
    const RenderResult r = renderScene(scene, "uniform", v.filter, v.params, kFenceW, kFenceH, kMapSize);
    if (ref.visibility.empty()) {
      ref = traceReference(scene, r.gbuffer);
      band = floorNearCasters(scene, r.gbuffer, ref.litMask, kContactBandM);
    }
    out.results.emplace_back(v.name, compareVisibility(r.visibility, ref.visibility, ref.litMask));
    out.nearContacts.emplace_back(v.name, compareVisibility(r.visibility, ref.visibility, band));
  }
  std::printf("fence (%s) %dx%d, map %d, reference %d samples, %zu pixels (%zu on the floor within %.1f m of a caster):\n"
              "  %-16s %8s %8s %8s %8s | near contacts: %8s %8s\n",
              view, kFenceW, kFenceH, kMapSize, ref.samplesPerPixel, out.results[0].second.pixels,
              out.nearContacts[0].second.pixels, kContactBandM, "filter", "leak %", "umbra %", "dark %", "RMSE", "leak %",
              "dark %");
  for (size_t i = 0; i < out.results.size(); ++i) {
    const VisibilityMetrics& m = out.results[i].second;
    const VisibilityMetrics& c = out.nearContacts[i].second;
    std::printf("  %-16s %8.3f %8.3f %8.3f %8.4f | %22.3f %8.3f\n", out.results[i].first.c_str(), m.leakPct,
                m.umbraLeakPct, m.overDarkPct, m.rmse, c.leakPct, c.overDarkPct);
  }
  return out;
}

// Overlapping slats at different depths: the case where two moments bleed light and four do not.
// leak % counts every pixel with V − V_ref > 0.1. On the scene's own view most of it comes from
// what every filter shares (a hard-ish edge against the reference's penumbra, the pixel-footprint
// blur): hard itself leaks ~1.4 %. The bleeding is the difference between two and four moments in
// the same pipeline: vssm vs msm-soft (one O(1) soft pipeline), vsm vs msm (one mip-filter width).
TEST(VarianceFilters, FenceLeaksAgainstReference) {
  const FenceLeaks f = measureFenceLeaks(makeBuiltinScene("fence"), "its own camera");
  ASSERT_GT(f.get("vsm").leakPct, 0.0);
  ASSERT_GT(f.get("vssm sat").leakPct, 0.0);
  // Four moments cut the bleeding: the leaks inside the reference's umbra (umbraLeakPct, the
  // light-bleeding share) drop, msm-soft's to at most this share of vssm's (measured 0.61 on
  // llvmpipe), msm's to no more than vsm's; so do the total leaks. msm-soft's leakPct is at most
  // half of vsm's (measured 0.45), the issue's target; msm's is not here (0.90): most of it is edge
  // shape under the pixel footprint that vsm and msm share (docs/msm.md). Behind the wall, where
  // the leaks are bleeding, it is (FenceBehindTheWallIsLightBleeding).
  constexpr double kSoftUmbraLeakRatio = 0.8, kSoftLeakRatioToVsm = 0.5;
  EXPECT_LE(f.get("msm-soft").umbraLeakPct, kSoftUmbraLeakRatio * f.get("vssm sat").umbraLeakPct);
  EXPECT_LE(f.get("msm-soft").leakPct, kSoftLeakRatioToVsm * f.get("vsm").leakPct);
  EXPECT_LT(f.get("msm-soft").leakPct, f.get("vssm sat").leakPct);
  for (const char* msm : {"msm float32", "msm quantized16"}) {
    EXPECT_LE(f.get(msm).umbraLeakPct, f.get("vsm").umbraLeakPct) << msm;
    EXPECT_LE(f.get(msm).leakPct, f.get("vsm").leakPct) << msm;
  }
  // msm-soft is also the closer of the two soft pipelines overall.
  EXPECT_LT(f.get("msm-soft").rmse, f.get("vssm sat").rmse);
  // esm near the slats' feet: V = E[exp(2c (z − t))] is never below a region's lit fraction
  // (common/exp_warp.glsl), so it darkens the lit floor by a caster's foot no more than vsm
  // (measured on llvmpipe: 4.89 % of those pixels over-dark, vsm 5.80 %).
  EXPECT_LE(f.nearContact("esm").overDarkPct, f.nearContact("vsm").overDarkPct);
}

// The floor behind fence's wall, seen from behind it: it lies in the wall's umbra, and in the map
// the slats stand in front of the wall, so every filter region across a slat's edge holds two
// occluder depths far in front of the receiver — the textbook case of light bleeding (the slats'
// outlines show through the wall's shadow with two moments). Here the leaks are bleeding, not
// edge shape: hard leaks 0.33 %, pcss none, vsm 2.6 % (2.4 % inside the umbra); four moments
// take out most of it (measured on llvmpipe: msm float32 ×0.14 of vsm, quantized16 ×0.26,
// msm-soft ×0.06, and ×0.03 of vssm's).
TEST(VarianceFilters, FenceBehindTheWallIsLightBleeding) {
  Scene scene = makeBuiltinScene("fence");
  scene.camera = parseCameraArgument("4,3,-6:0,0,-3.5:50", scene.camera);
  const FenceLeaks f = measureFenceLeaks(scene, "behind the wall");
  // The view measures bleeding: vsm leaks inside the umbra, several times what hard's edges leak.
  constexpr double kMinVsmUmbraLeakPct = 1.0, kMinBleedOverHard = 4.0;
  ASSERT_GE(f.get("vsm").umbraLeakPct, kMinVsmUmbraLeakPct);
  ASSERT_GE(f.get("vsm").leakPct, kMinBleedOverHard * f.get("hard").leakPct);
  ASSERT_GE(f.get("vssm sat").umbraLeakPct, kMinVsmUmbraLeakPct);
  // The issue's target: msm's and msm-soft's leaks at most half of vsm's.
  constexpr double kLeakRatioToVsm = 0.5;
  for (const char* four : {"msm float32", "msm quantized16", "msm-soft"}) {
    EXPECT_LE(f.get(four).leakPct, kLeakRatioToVsm * f.get("vsm").leakPct) << four;
    EXPECT_LE(f.get(four).umbraLeakPct, kLeakRatioToVsm * f.get("vsm").umbraLeakPct) << four;
  }
  EXPECT_LE(f.get("msm-soft").leakPct, kLeakRatioToVsm * f.get("vssm sat").leakPct);
  EXPECT_LE(f.get("msm-soft").leakPct, kLeakRatioToVsm * f.get("vssm mip").leakPct);
  // The exponential warps: evsm's umbra leak at most half of vsm's, as the issue asks (measured
  // on llvmpipe: 0.048 % with 2 and 4 components, ×0.02 of vsm; float16, whose exponents stop
  // at 5.5, 0.954 %, ×0.40, not asserted), and evsm-soft's at most half of vssm's (0.081 %).
  for (const char* warped : {"evsm 2", "evsm 4"}) {
    EXPECT_LE(f.get(warped).umbraLeakPct, kLeakRatioToVsm * f.get("vsm").umbraLeakPct) << warped;
    EXPECT_LE(f.get(warped).leakPct, kLeakRatioToVsm * f.get("vsm").leakPct) << warped;
  }
  EXPECT_LE(f.get("evsm-soft").umbraLeakPct, kLeakRatioToVsm * f.get("vssm sat").umbraLeakPct);
  EXPECT_LE(f.get("evsm-soft").leakPct, kLeakRatioToVsm * f.get("vssm sat").leakPct);
  // esm has no bleeding between occluders, but the floor just behind the wall (0.2 m thick) lies
  // close behind it in depth, and exp(2c (z − t)) lets that light through: near the wall's foot
  // it leaks more than vsm (measured: 21.3 % of those pixels, vsm 13.6 %).
  constexpr double kMinEsmContactLeakOverVsm = 1.25;
  EXPECT_GE(f.nearContact("esm").leakPct, kMinEsmContactLeakOverVsm * f.nearContact("vsm").leakPct);
  // A finer map keeps that: the wall's umbra is a region of one depth, where rounding can leave
  // the moment solve degenerate (common/moments.glsl); its roots once lit pixels all over it
  // (RMSE at 2048² 0.060 for msm, 0.029 for msm-soft; measured now 0.017 and 0.008).
  constexpr int kFineMap = 2048;
  constexpr double kMaxFineRmseRatio = 1.5;
  for (const Variant& v : {variant("msm float32"), variant("msm-soft")}) {
    const RenderResult r = renderScene(scene, "uniform", v.filter, v.params, kFenceW, kFenceH, kFineMap);
    const VisibilityMetrics m = compareVisibility(r.visibility, f.ref.visibility, f.ref.litMask);
    std::printf("  %-16s at %d²: leak %.3f %%, RMSE %.4f\n", v.name.c_str(), kFineMap, m.leakPct, m.rmse);
    EXPECT_LE(m.rmse, kMaxFineRmseRatio * f.get(v.name).rmse) << v.name;
  }
}

// The contact-hardening penumbra of `pen`: vssm's error within 1.5x of pcss's.
TEST(VarianceFilters, PenRmseNearPcss) {
  const Scene scene = makeBuiltinScene("pen");
  constexpr int kW = 256, kH = 144;
  const RenderResult pcss = renderScene(scene, "uniform", "pcss", {}, kW, kH, kMapSize);
  const ReferenceResult ref = traceReference(scene, pcss.gbuffer);
  const VisibilityMetrics mPcss = compareVisibility(pcss.visibility, ref.visibility, ref.litMask);
  std::printf("pen %dx%d, map %d: RMSE (penumbra RMSE) pcss %.4f (%.4f)\n", kW, kH, kMapSize, mPcss.rmse, mPcss.penumbraRmse);
  constexpr double kMaxRatio = 1.5;
  for (const Variant& v : {variant("vssm sat"), variant("vssm mip"), variant("msm-soft")}) {
    const RenderResult r = renderScene(scene, "uniform", v.filter, v.params, kW, kH, kMapSize);
    const VisibilityMetrics m = compareVisibility(r.visibility, ref.visibility, ref.litMask);
    std::printf("  %-16s %.4f (%.4f), x%.2f of pcss\n", v.name.c_str(), m.rmse, m.penumbraRmse, m.rmse / mPcss.rmse);
    if (v.name == "vssm sat") {
      EXPECT_LE(m.rmse, kMaxRatio * mPcss.rmse);
    }
    // The mip chain's boxes, read as 2 x 2 sub-boxes (vssm.mipSplit's default): x2.17 of pcss;
    // one trilinear read per box weighed a tent twice the box's width and read x4.35.
    constexpr double kMaxMipRatio = 2.5;
    if (v.name == "vssm mip") {
      EXPECT_LE(m.rmse, kMaxMipRatio * mPcss.rmse);
    }
  }
}

// V at fixed world points while the camera makes 8 small moves (the shimmer measure) on pen, whose
// spot map does not move with the camera: with `<filter>.footprint=off` the filter box is fixed in
// the map, so nothing may change; with the footprint, the box follows each point's projection and
// changes only a little. The footprint once started from the pixel a point was first seen at,
// which after a move is a ray that misses the point: 3.2 % (vsm) and 3.4 % (msm) of the edge
// points then changed by more than 0.1.
TEST(VarianceFilters, FootprintFollowsThePointAsTheCameraMoves) {
  const Scene pen = makeBuiltinScene("pen");
  ShimmerOptions o;
  o.steps = 8;
  const RenderOptions render{.width = 256, .height = 144};
  constexpr double kMaxShimmerPct = 0.1;
  for (const char* filter : {"vsm", "msm"}) {
    for (const char* footprint : {"off", "on"}) {
      const std::string key = std::string(filter) + ".footprint";
      const std::unique_ptr<Renderer> r = makeTestRenderer(pen, "uniform", filter, {{key, footprint}}, kMapSize);
      const ShimmerResult s = measureShimmer(*r, render, o);
      std::printf("  pen %s %s=%s: shimmer_pct %.3f over %zu edge points\n", filter, key.c_str(), footprint,
                  s.shimmerPct, s.edgePoints);
      ASSERT_GT(s.edgePoints, 100u) << filter;
      if (std::string(footprint) == "off")
        EXPECT_EQ(s.shimmerPct, 0.0) << filter;
      else
        EXPECT_LE(s.shimmerPct, kMaxShimmerPct) << filter;
    }
  }
}

namespace {

// Visibility-pass times of two configurations (a, b) measured frame by frame in alternation, with
// both renderers kept alive, so that drift on a shared CPU (llvmpipe runs on it) hits both alike.
// Reported: each one's median and the median and quartiles of the per-pair ratio b / a.
struct PairedTimes {
  double medianA = 0.0, medianB = 0.0, ratio = 0.0, ratioLo = 0.0, ratioHi = 0.0;
};

double quantile(std::vector<double> v, double q) {
  std::sort(v.begin(), v.end());
  return v[static_cast<size_t>(q * static_cast<double>(v.size() - 1) + 0.5)];
}

PairedTimes pairedVisibilityMs(const Scene& sceneA, const std::string& filterA, const Params& paramsA,
                               const Scene& sceneB, const std::string& filterB, const Params& paramsB, int mapSize) {
  constexpr int kWarmUp = 2, kPairs = 21;
  const std::unique_ptr<Renderer> a = makeTestRenderer(sceneA, "uniform", filterA, paramsA, mapSize);
  const std::unique_ptr<Renderer> b = makeTestRenderer(sceneB, "uniform", filterB, paramsB, mapSize);
  RenderOptions o;
  o.width = 320;
  o.height = 180;
  for (int i = 0; i < kWarmUp; ++i) {  // includes the shaders' JIT compile
    a->render(o);
    b->render(o);
  }
  std::vector<double> msA, msB, ratios;
  for (int i = 0; i < kPairs; ++i) {
    // Alternate which goes first: a pass right after the other configuration's frame may find
    // the caches cold.
    Renderer& first = i % 2 == 0 ? *a : *b;
    Renderer& second = i % 2 == 0 ? *b : *a;
    first.render(o);
    second.render(o);
    msA.push_back(a->timings().get("visibility"));
    msB.push_back(b->timings().get("visibility"));
    ratios.push_back(msB.back() / msA.back());
  }
  return {quantile(msA, 0.5), quantile(msB, 0.5), quantile(ratios, 0.5), quantile(ratios, 0.25), quantile(ratios, 0.75)};
}

}  // namespace

// Benchmark (run with --gtest_also_run_disabled_tests): the issue's note. vssm's and msm-soft's
// visibility pass as the light grows ×8 (O(1): flat), next to pcss (a fixed number of taps over a
// growing region); msm's visibility pass against vsm's at the same filter width.
TEST(VarianceFilters, DISABLED_BenchmarkVisibilityPass) {
  constexpr int kMapSize2k = 2048;
  const Scene pen = makeBuiltinScene("pen");
  std::printf("visibility pass, 320x180, map %d, 21 alternated frame pairs after 2 warm-up, glFinish+steady_clock on %s\n"
              "  ratio: median [quartiles] of the per-pair ratio\n",
              kMapSize2k, glContext().info().renderer.c_str());
  for (const auto& [name, filter, params] : std::vector<std::tuple<std::string, std::string, Params>>{
           {"vssm sat", "vssm", {{"vssm.source", "sat"}}},
           {"vssm sat, near-plane search", "vssm", {{"vssm.source", "sat"}, {"vssm.tightSearch", "off"}}},
           {"vssm mip", "vssm", {{"vssm.source", "mip"}}},
           {"msm-soft", "msm-soft", {}},
           {"pcss", "pcss", {}},
           {"pcss, near-plane search", "pcss", {{"pcss.tightSearch", "off"}}}}) {
    const PairedTimes t = pairedVisibilityMs(pen, filter, with(params, {{"light.size", "0.03"}}), pen, filter,
                                             with(params, {{"light.size", "0.24"}}), kMapSize2k);
    std::printf("  pen %-28s light.size 0.03 m: %7.2f ms, 0.24 m: %7.2f ms, ratio %.2f [%.2f, %.2f]\n", name.c_str(),
                t.medianA, t.medianB, t.ratio, t.ratioLo, t.ratioHi);
    EXPECT_GT(t.medianA, 0.0);
  }
  const Scene fence = makeBuiltinScene("fence");
  for (const char* storage : {"float32", "quantized16"}) {
    const PairedTimes t = pairedVisibilityMs(fence, "vsm", {}, fence, "msm", {{"msm.storage", storage}}, kMapSize2k);
    std::printf("  fence vsm %7.2f ms, msm %-11s %7.2f ms, ratio %.2f [%.2f, %.2f]\n", t.medianA, storage, t.medianB,
                t.ratio, t.ratioLo, t.ratioHi);
    EXPECT_GT(t.medianA, 0.0);
  }
}

// Benchmark (run with --gtest_also_run_disabled_tests): the cost columns of docs/esm.md's, evsm.md's
// and evsm-soft.md's tables, fence from behind the wall. Every configuration's renderer is kept alive
// and one frame of each is rendered per round, the order rotated each round, so that drift on a
// shared CPU (llvmpipe runs on it) hits all alike; per pass, the median and quartiles over the
// rounds, after 2 warm-up rounds (the first frame compiles the shaders).
TEST(VarianceFilters, DISABLED_BenchmarkFenceBehindTheWallPasses) {
  Scene scene = makeBuiltinScene("fence");
  scene.camera = parseCameraArgument("4,3,-6:0,0,-3.5:50", scene.camera);
  std::vector<Variant> list = {variant("vsm"), variant("msm float32"), variant("esm"), variant("evsm 2"),
                               variant("evsm 4"), variant("evsm 4 float16"), variant("vssm sat"), variant("msm-soft"),
                               variant("evsm-soft")};
  constexpr int kWarmUp = 2, kRounds = 15;
  const char* passes[] = {"shadow", "prefilter", "visibility"};
  for (const auto& [width, height, mapSize] : {std::tuple{kFenceW, kFenceH, kMapSize}, std::tuple{256, 256, 2048}}) {
    std::vector<std::unique_ptr<Renderer>> renderers;
    for (const Variant& v : list) renderers.push_back(makeTestRenderer(scene, "uniform", v.filter, v.params, mapSize));
    RenderOptions o;
    o.width = width;
    o.height = height;
    std::vector<std::vector<std::vector<double>>> ms(list.size(), std::vector<std::vector<double>>(std::size(passes)));
    for (int round = 0; round < kWarmUp + kRounds; ++round)
      for (size_t k = 0; k < list.size(); ++k) {
        const size_t i = (k + static_cast<size_t>(round)) % list.size();
        renderers[i]->render(o);
        if (round < kWarmUp) continue;
        for (size_t p = 0; p < std::size(passes); ++p) ms[i][p].push_back(renderers[i]->timings().get(passes[p]));
      }
    std::printf("fence behind the wall, %dx%d, map %d, %d rounds after %d warm-up, glFinish+steady_clock on %s\n"
                "  ms: median [quartiles]\n  %-16s %-22s %-22s %-22s %8s\n",
                width, height, mapSize, kRounds, kWarmUp, glContext().info().renderer.c_str(), "filter", "shadow",
                "prefilter", "visibility", "sum");
    for (size_t i = 0; i < list.size(); ++i) {
      std::printf("  %-16s", list[i].name.c_str());
      double sum = 0.0;
      for (size_t p = 0; p < std::size(passes); ++p) {
        sum += quantile(ms[i][p], 0.5);
        std::printf(" %7.2f [%5.2f, %5.2f]", quantile(ms[i][p], 0.5), quantile(ms[i][p], 0.25), quantile(ms[i][p], 0.75));
      }
      std::printf(" %8.2f\n", sum);
      EXPECT_GT(quantile(ms[i][2], 0.5), 0.0) << list[i].name;
    }
  }
}
