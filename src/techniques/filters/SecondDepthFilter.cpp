#include "techniques/filters/SecondDepthFilter.h"

#include "frame/FrameContext.h"
#include "shared/Bindings.h"

namespace penumbra {

SecondDepthFilter::SecondDepthFilter() : Filter({}) {}

void SecondDepthFilter::renderShadowMaps(FrameContext& frame) {
  const int size = frame.mapSize(), layers = frame.viewCount();
  mFirst.ensure("second-depth first layer", size, layers, GL_R32F);
  mSecond.ensure("second-depth second layer", size, layers);
  if (!mMidpoint || mMidpoint.width() != size || mMidpoint.layers() != layers) {
    mMidpoint = gl::Texture("second-depth midpoint", {GL_TEXTURE_2D_ARRAY, GL_R32F, size, size, layers, 1});
    mMidpoint.setSampling(GL_NEAREST, GL_NEAREST);
  }
  const glm::vec4 noSlope(0.0f);
  frame.renderViews(mFirst, frame.shadowProgram("passes/depth_peel.frag.glsl", ShaderDefines().set("PN_PEEL_LAYER", 0)), noSlope);
  mFirst.depth().bindUnit(PN_TEX_FILTER0);
  frame.renderViews(mSecond, frame.shadowProgram("passes/depth_peel.frag.glsl", ShaderDefines().set("PN_PEEL_LAYER", 1)));

  ProgramDesc combine;
  combine.label = "second-depth midpoint";
  combine.compute = {"passes/second_depth_combine.comp.glsl"};
  mFirst.depth().bindUnit(PN_TEX_FILTER0);
  mFirst.color().bindUnit(PN_TEX_FILTER1);
  mSecond.depth().bindUnit(PN_TEX_FILTER2);
  mMidpoint.bindImage(PN_IMG_AUX0, GL_WRITE_ONLY);
  FrameContext::dispatch2D(frame.program(combine), size, size, PN_SCREEN_GROUP);
}

void SecondDepthFilter::computeVisibility(FrameContext& frame) {
  mMidpoint.bindUnit(PN_TEX_FILTER0);
  frame.dispatchScreen(frame.visibilityProgram("techniques/filters/second_depth.glsl"));
}

std::vector<DebugImage> SecondDepthFilter::debugImages() const {
  // Its shadow map is the midpoint of the first two surfaces: what a receiver is compared with.
  return {{std::string(kShadowMapImage), &mMidpoint, "linear light depth midway between the first two surfaces: 0 = near plane, 1 = far plane"},
          {"first-layer", &mFirst.depth(), "linear light depth of the nearest surface"},
          {"second-layer", &mSecond.depth(), "linear light depth of the surface behind the nearest"}};
}

}  // namespace penumbra
