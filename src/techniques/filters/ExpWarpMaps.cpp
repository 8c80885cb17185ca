#include "techniques/filters/ExpWarpMaps.h"

#include "frame/FrameContext.h"
#include "frame/MipBuilder.h"
#include "techniques/filters/exp_warp.shared.h"
#include "shared/Bindings.h"

#include <penumbra/Error.h>

#include <cmath>
#include <fmt/format.h>

namespace penumbra {
namespace {

float maxWarpLog(ExpWarpStorage storage) {
  return storage == ExpWarpStorage::Float16 ? PN_EXP_WARP_MAX_LOG_FLOAT16 : PN_EXP_WARP_MAX_LOG_FLOAT32;
}

GLenum colorFormat(int components, ExpWarpStorage storage) {
  const bool half = storage == ExpWarpStorage::Float16;
  switch (components) {
    case 1: return half ? GL_R16F : GL_R32F;
    case 2: return half ? GL_RG16F : GL_RG32F;
    case 4: return half ? GL_RGBA16F : GL_RGBA32F;
    default: break;
  }
  throw Error(fmt::format("exponential warp maps hold 1, 2 or 4 components, not {}", components));
}

}  // namespace

float maxWarpExponent(ExpWarpStorage storage, int highestPower) {
  return maxWarpLog(storage) / static_cast<float>(highestPower);
}

float minRelativeWarpVariance(ExpWarpStorage storage) {
  return storage == ExpWarpStorage::Float16 ? PN_EXP_WARP_MIN_RELATIVE_VARIANCE_FLOAT16
                                            : PN_EXP_WARP_MIN_RELATIVE_VARIANCE_FLOAT32;
}

void ExpWarpMaps::render(FrameContext& frame, std::string_view label, const Warp& warp) {
  [[maybe_unused]] const int highestPower = warp.components == 1 ? 1 : 2;
  PN_ASSERT(warp.positive <= maxWarpExponent(warp.storage, highestPower) &&
            warp.negative <= maxWarpExponent(warp.storage, highestPower));
  constexpr int kFullMipChain = 0;
  mMaps.ensure(std::string(label), frame.mapSize(), frame.viewCount(), colorFormat(warp.components, warp.storage),
               kFullMipChain);
  gpu::ExpWarpUniforms u{};
  u.warp = glm::vec4(warp.positive, warp.negative, std::exp(maxWarpLog(warp.storage)), 0.0f);
  frame.setFilterBlock(u);
  const ShaderDefines defines = ShaderDefines().set("PN_EXP_WARP_COMPONENTS", warp.components);
  // Cleared to the moments of the far plane (z = 1): no occluder where nothing was drawn.
  const glm::vec4 far = gpu::expWarpMoments(1.0f, warp.positive, warp.negative);
  frame.renderViews(mMaps, frame.shadowProgram("passes/exp_warp.frag.glsl", defines), far);
}

void ExpWarpMaps::buildMips() const { MipBuilder::build(mMaps.color()); }

void ExpWarpMaps::bindForFiltering() const {
  MipBuilder::setTrilinear(mMaps.color());
  mMaps.color().bindUnit(PN_TEX_FILTER0);
}

}  // namespace penumbra
