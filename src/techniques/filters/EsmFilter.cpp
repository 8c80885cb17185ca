#include "techniques/filters/EsmFilter.h"

#include "frame/FrameContext.h"
#include "techniques/filters/FootprintParams.h"
#include "techniques/filters/esm.shared.h"
#include "techniques/filters/exp_warp.shared.h"

namespace penumbra {
namespace {

// One power of the warp is stored: c up to the whole float32 range (exp_warp.shared.h). Light
// reaches a receiver just behind its occluder as e^(-2c δ), so a larger c narrows esm's contact
// leak (fence behind the wall, umbra leak % at 256x144, 1024², 64 samples: 6.75 at c = 20, 2.12
// at 40, 0.56 at 60, 0.03 at 86; city csm 7.73, 6.02, 4.65, 3.35); but texels beyond the
// receiver weigh e^(2c Δz), and at c = 80 the footprint's share of floor beyond a shadow's edge
// lit 6 of 124 shadowed probes on boxes (V > 0.2; none at 40), and pen's RMSE grows (0.0133 at
// 40, 0.0152 at 86). 40 is the middle (docs/esm.md).
constexpr float kDefaultExponent = 40.0f;

constexpr ParamDesc kParams[] = {
    {"esm.exponent", "Exponent",
     "c of the warp exp(c (2z - 1)) of linear depth z, V = E[exp(2c (z - t))]: larger makes the test sharper and "
     "darkens contacts again, smaller softens and lightens them; at most 86, where exp(c) and exp(-c) are the "
     "extreme normal 32-bit floats", "factor",
     kDefaultExponent, 1.0f, PN_EXP_WARP_MAX_LOG_FLOAT32, 0.0f},
    footprintWidthParam("esm.filterTexels"),
    footprintParam("esm.footprint"),
    footprintAnisotropyParam("esm.anisotropy"),
};

}  // namespace

EsmFilter::EsmFilter()
    : ExpWarpFilter(kParams, "esm warp", "exp(c·(2z − 1)) of the linear light depth z (esm.exponent = c)") {}

ExpWarpMaps::Warp EsmFilter::warp(const FrameContext& frame) const {
  ExpWarpMaps::Warp w;
  w.positive = frame.param("esm.exponent");
  w.components = 1;
  w.storage = ExpWarpStorage::Float32;
  return w;
}

void EsmFilter::computeVisibility(FrameContext& frame) {
  gpu::EsmUniforms u{};
  u.params = glm::vec4(frame.param("esm.exponent"), frame.param("esm.filterTexels"), 0.0f, 0.0f);
  u.mode = glm::ivec4(frame.paramInt("esm.anisotropy"), frame.paramInt("esm.footprint"), 0, 0);
  frame.setFilterBlock(u);
  dispatchVisibility(frame, "techniques/filters/esm.glsl");
}

}  // namespace penumbra
