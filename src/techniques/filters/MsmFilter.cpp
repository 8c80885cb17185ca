#include "techniques/filters/MsmFilter.h"

#include "frame/FrameContext.h"
#include "frame/MipBuilder.h"
#include "techniques/filters/FootprintParams.h"
#include "techniques/filters/MomentParams.h"
#include "techniques/filters/msm.shared.h"
#include "shared/Bindings.h"

#include <algorithm>
#include <cmath>

namespace penumbra {
namespace {

constexpr std::string_view kStorageNames[] = {"float32", "quantized16"};
constexpr int kStorageFloat32 = 0;

constexpr ParamDesc kParams[] = {
    {"msm.storage", "Storage", "float32: RGBA32F moments (128 bits/texel); quantized16: RGBA16 in the optimised basis of Peters & Klein (64 bits/texel)", "",
     kStorageFloat32, 0, 1, 1, kStorageNames, "PN_MSM_QUANTIZED"},
    momentBiasParam("msm.bias"),
    momentDepthBiasParam("msm.depthBias"),
    footprintWidthParam("msm.filterTexels"),
    footprintParam("msm.footprint"),
    footprintAnisotropyParam("msm.anisotropy"),
    {"msm.translucent", "Translucent casters",
     "on: translucent casters are left out of the moments and summed into two maps of their own, weighted by their "
     "absorbance −ln(transmittance); V (RGB) is the opaque casters' V times exp(−absorbance × the share of it the moments "
     "put in front of the receiver)", "", 0.0f, 0.0f, 1.0f, 1.0f, kOffOn},
    {"msm.translucentScale", "Translucent map scale",
     "side of the translucent casters' two maps as a share of the light's map size (their cost and memory go with its square)",
     "× map size", 0.25f, 0.125f, 1.0f, 0.0f},
};

bool quantized(const FrameContext& f) { return f.paramInt("msm.storage") != kStorageFloat32; }

/// This frame's maps hold the opaque casters alone and the translucent ones go to their own
/// maps (msm.translucent on, and some caster translucent: the frame skips them).
bool throughTranslucent(const FrameContext& f) {
  return f.paramInt("msm.translucent") != 0 && f.translucentCasters() == CasterSet::Translucent::Skip;
}

}  // namespace

MsmFilter::MsmFilter()
    : MomentFilter(kParams, "moments (z, z², z³, z⁴) of the linear light depth z (msm.storage basis)") {}

MomentMaps::Moments MsmFilter::moments(const FrameContext& frame) const {
  return {.count = 4, .source = MomentMaps::Source::Mips, .quantized = quantized(frame)};
}

void MsmFilter::renderShadowMaps(FrameContext& frame) {
  MomentFilter::renderShadowMaps(frame);
  if (!throughTranslucent(frame)) {
    mTranslucentMoments = {};
    mAbsorbance = {};
    return;
  }
  constexpr int kFullMipChain = 0;
  constexpr int kMinSide = 16;
  const int side = std::max(kMinSide, static_cast<int>(std::lround(static_cast<float>(frame.mapSize()) * frame.param("msm.translucentScale"))));
  mTranslucentMoments.ensure("msm translucent moments", side, frame.viewCount(), GL_RGBA32F, kFullMipChain);
  mAbsorbance.ensure("msm translucent absorbance", side, frame.viewCount(), GL_RGBA32F, kFullMipChain);
  constexpr std::string_view kTranslucentPass = "techniques/filters/msm_translucent.frag.glsl";
  ShaderDefines target;
  target.set("PN_MSM_ABSORBANCE", 0);
  frame.sumTranslucentViews(mTranslucentMoments, frame.shadowProgram(kTranslucentPass, target));
  target.set("PN_MSM_ABSORBANCE", 1);
  frame.sumTranslucentViews(mAbsorbance, frame.shadowProgram(kTranslucentPass, target));
}

void MsmFilter::prefilter(FrameContext& frame) {
  MomentFilter::prefilter(frame);
  if (!throughTranslucent(frame)) return;
  MipBuilder::build(mTranslucentMoments.color());
  MipBuilder::build(mAbsorbance.color());
}

void MsmFilter::computeVisibility(FrameContext& frame) {
  gpu::MsmUniforms u{};
  // Points (visibilityAt) get the opaque casters' V, one value, as with the translucent add-on.
  const bool translucent = throughTranslucent(frame) && !frame.pointsMode();
  // The translucent maps' texels are 1/scale of the light map's per side: the moment bias in
  // their texels² is the same bias in the light map's times 1/scale².
  const float scale = static_cast<float>(translucent ? mAbsorbance.size() : frame.mapSize()) / static_cast<float>(frame.mapSize());
  u.params = glm::vec4(frame.param("msm.bias"), frame.param("msm.depthBias"), frame.param("msm.filterTexels"), 1.0f / (scale * scale));
  u.mode = glm::ivec4(frame.paramInt("msm.anisotropy"), 0, 0, 0);
  frame.setFilterBlock(u);
  ShaderDefines defines;
  if (translucent) {
    defines.set("PN_MSM_TRANSLUCENT");
    for (const ShadowMapArray* m : {&mTranslucentMoments, &mAbsorbance}) MipBuilder::setTrilinear(m->color());
    mTranslucentMoments.color().bindUnit(PN_TEX_FILTER1);
    mAbsorbance.color().bindUnit(PN_TEX_FILTER2);
  }
  dispatchVisibility(frame, "techniques/filters/msm.glsl", defines);
}

std::string_view MsmFilter::translucentCasters() const {
  return "drawn as opaque; with msm.translucent on, left out of its moments and summed into two maps of their own, "
         "weighted by their absorbance, and shadowed through (V in colour); with translucent.shadows on, as every filter";
}

bool MsmFilter::shadowsThroughTranslucent(const Parameterized& values) const { return values.paramInt("msm.translucent") != 0; }

std::vector<DebugImage> MsmFilter::debugImages() const {
  std::vector<DebugImage> out = MomentFilter::debugImages();
  if (mAbsorbance.color()) {
    out.push_back({"translucent-moments", &mTranslucentMoments.color(),
                   "sum over the translucent casters of w·(z, z², z³, z⁴), w the mean of a caster's absorbance −ln(T) over R, G, B"});
    out.push_back({"translucent-absorbance", &mAbsorbance.color(),
                   "sum over the translucent casters of their absorbance −ln(T) in R, G, B; alpha: the sum of the weights w"});
  }
  return out;
}

}  // namespace penumbra
