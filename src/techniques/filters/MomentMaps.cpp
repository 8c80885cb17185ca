#include "techniques/filters/MomentMaps.h"

#include "common/MomentQuantization.h"
#include "frame/FrameContext.h"
#include "frame/MipBuilder.h"
#include "shared/Bindings.h"

#include <penumbra/Error.h>

#include <fmt/format.h>

namespace penumbra {
namespace {

GLenum colorFormat(const MomentMaps::Moments& m) {
  if (m.count == 2 && !m.quantized) return GL_RG32F;
  if (m.count == 4) return m.quantized ? GL_RGBA16 : GL_RGBA32F;
  throw Error(fmt::format("moment maps hold 2 moments (float) or 4 (float or quantized), not {}{}", m.count,
                          m.quantized ? " quantized" : ""));
}

}  // namespace

void MomentMaps::render(FrameContext& frame, std::string_view label, const Moments& moments) {
  mMoments = moments;
  if (moments.source == Source::Sat) {
    // Linear depth only: the table's build forms the powers of z itself, in exact fixed point.
    mMaps.ensure(std::string(label), frame.mapSize(), frame.viewCount());
    frame.renderViews(mMaps, frame.shadowProgram());
    return;
  }
  constexpr int kFullMipChain = 0;
  mMaps.ensure(std::string(label), frame.mapSize(), frame.viewCount(), colorFormat(moments), kFullMipChain);
  ShaderDefines defines;
  defines.set("PN_MOMENT_COUNT", moments.count);
  if (moments.count == 2) defines.set("PN_MOMENT_SLOPE_VARIANCE");
  if (moments.quantized) defines.set("PN_MOMENTS_QUANTIZED");
  // Cleared to the moments of the far plane, z = 1: (1, 1, 1, 1), or that vector's encoding.
  glm::vec4 far(1.0f);
  if (moments.quantized) {
    far = glm::mat4(PN_MSM16_ENCODE_MATRIX) * far;
    far.x += static_cast<float>(PN_MSM16_ENCODE_OFFSET_X);
  }
  frame.renderViews(mMaps, frame.shadowProgram("passes/moments.frag.glsl", defines), far);
}

void MomentMaps::prefilter(FrameContext& frame) {
  if (mMoments.source == Source::Sat)
    mSat.build(frame.shaders(), mMaps.depth(), mMoments.count);
  else
    MipBuilder::build(mMaps.color());
}

void MomentMaps::bind() const {
  if (mMoments.source == Source::Sat) {
    mSat.bindTable();
    return;
  }
  MipBuilder::setTrilinear(mMaps.color());
  mMaps.color().bindUnit(PN_TEX_FILTER0);
}

const gl::Texture& MomentMaps::linearDepth() const { return mMoments.source == Source::Sat ? mMaps.depth() : mMaps.color(); }

std::vector<DebugImage> MomentMaps::debugImages(std::string_view momentsMeaning) const {
  std::vector<DebugImage> out = {{std::string(kShadowMapImage), &mMaps.depth(), kShadowMapMeaning}};
  if (mMaps.color()) out.push_back({std::string(kMomentsImage), &mMaps.color(), momentsMeaning});
  return out;
}

}  // namespace penumbra
