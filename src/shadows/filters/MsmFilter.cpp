#include "shadows/filters/MsmFilter.h"

#include "common/MomentQuantization.h"
#include "frame/FrameContext.h"
#include "frame/MipBuilder.h"
#include "shadows/filters/FootprintParams.h"
#include "shadows/filters/MomentBias.h"
#include "shadows/filters/msm.shared.h"
#include "shared/Bindings.h"

namespace penumbra {
namespace {

constexpr std::string_view kStorageNames[] = {"float32", "quantized16"};
constexpr int kStorageFloat32 = 0;

constexpr ParamDesc kParams[] = {
    {"msm.storage", "Storage", "float32: RGBA32F moments (128 bits/texel); quantized16: RGBA16 in the optimised basis of Peters & Klein (64 bits/texel)", "",
     kStorageFloat32, 0, 1, 1, kStorageNames, "PN_MSM_QUANTIZED"},
    momentBiasParam("msm.bias"),
    {"msm.depthBias", "Depth bias", "the receiver depth is moved toward the light by this much, in linear depth units (fraction of the map's depth range)", "depth range",
     0.0f, 0.0f, 0.05f, 0.0f},
    footprintWidthParam("msm.filterTexels"),
    footprintParam("msm.footprint"),
    footprintAnisotropyParam("msm.anisotropy"),
};

bool quantized(const FrameContext& f) { return f.paramInt("msm.storage") != kStorageFloat32; }

}  // namespace

MsmFilter::MsmFilter() : Filter(kParams) {}

void MsmFilter::renderShadowMaps(FrameContext& frame) {
  constexpr int kFullMipChain = 0;
  const bool q = quantized(frame);
  mMaps.ensure("msm moments", frame.mapSize(), frame.viewCount(), q ? GL_RGBA16 : GL_RGBA32F, kFullMipChain);
  ShaderDefines defines;
  defines.set("PN_MOMENT_COUNT", 4);
  if (q) defines.set("PN_MOMENTS_QUANTIZED");
  // Cleared to the moments of the far plane, z = 1: (1, 1, 1, 1), or that vector's encoding.
  glm::vec4 far(1.0f);
  if (q) {
    far = glm::mat4(PN_MSM16_ENCODE_MATRIX) * far;
    far.x += static_cast<float>(PN_MSM16_ENCODE_OFFSET_X);
  }
  frame.renderViews(mMaps, frame.shadowProgram("passes/moments.frag.glsl", defines), far);
}

void MsmFilter::prefilter(FrameContext& frame) {
  (void)frame;
  MipBuilder::build(mMaps.color());
}

void MsmFilter::computeVisibility(FrameContext& frame) {
  gpu::MsmUniforms u{};
  u.params = glm::vec4(frame.param("msm.bias"), frame.param("msm.depthBias"), frame.param("msm.filterTexels"), 0.0f);
  u.mode = glm::ivec4(frame.paramInt("msm.anisotropy"), 0, 0, 0);
  frame.setFilterBlock(u);
  MipBuilder::setTrilinear(mMaps.color());
  mMaps.color().bindUnit(PN_TEX_FILTER0);
  frame.dispatchScreen(frame.visibilityProgram("shadows/filters/msm.glsl"));
}

std::vector<DebugImage> MsmFilter::debugImages() const { return {{std::string(kShadowMapImage), &mMaps.depth(), kShadowMapMeaning},
          {std::string(kMomentsImage), &mMaps.color(), "moments (z, z², z³, z⁴) of the linear light depth z (msm.storage basis)"}};
}

}  // namespace penumbra
