#include "techniques/filters/SmrtFilter.h"

#include "frame/FrameContext.h"
#include "techniques/filters/smrt.shared.h"
#include "shared/Bindings.h"

namespace penumbra {
namespace {

constexpr ParamDesc kParams[] = {
    {"smrt.rays", "Rays", "rays a pixel traces toward points spread over the light's disk (sunflower spirals turned per pixel and per frame) "
     "where its first rays disagree", "rays",
     32.0f, 1.0f, 128.0f, 1.0f, {}, "PN_SMRT_RAYS"},
    {"smrt.probeRays", "Probe rays", "rays every pixel traces first, toward the light's centre and around a ring just outside its disk: where they "
     "all agree the pixel is lit or in umbra without more rays (0 = off)", "rays",
     8.0f, 0.0f, 16.0f, 1.0f, {}, "PN_SMRT_PROBE_RAYS"},
    {"smrt.steps", "Steps", "map reads along each ray, from the receiver to the nearest surface in the light's footprint, denser near the receiver", "steps",
     12.0f, 1.0f, 64.0f, 1.0f, {}, "PN_SMRT_STEPS"},
    {"smrt.thicknessM", "Thickness", "how far behind a caster's surface in the map a ray step still counts as inside it, in metres along the "
     "light's axis (a ray that crosses the surface between two steps is blocked whatever the thickness)", "m",
     0.02f, 0.0f, 100.0f, 0.0f},
    {"smrt.constantBias", "Constant bias", "a step's map surface must lie this far in front of the ray, in linear light-depth units (fraction of the map's depth range)", "depth range",
     0.0002f, 0.0f, 0.05f, 0.0f},
    {"smrt.slopeBias", "Slope bias", "… plus this many texels of the receiver plane's depth slope (the map's flat texels on a tilted receiver)", "texels",
     1.0f, 0.0f, 16.0f, 0.0f},
    {"smrt.filterRadiusPx", "Spatial filter", "radius in pixels of the tent that averages V over the pixel's neighbours on its own surface, "
     "where its rays disagree (0 = off: the rays' noise is left to temporal.accumulate)", "pixels",
     0.0f, 0.0f, 8.0f, 1.0f},
};

}  // namespace

SmrtFilter::SmrtFilter() : Filter(kParams) {}

void SmrtFilter::renderShadowMaps(FrameContext& frame) {
  frame.ensureMaps(mMaps, "smrt shadow map");
  frame.renderViews(mMaps, frame.shadowProgram());
}

void SmrtFilter::prefilter(FrameContext& frame) { mNearest.build(frame, true, mMaps.depth()); }

void SmrtFilter::computeVisibility(FrameContext& frame) {
  gpu::SmrtUniforms u{};
  u.params = glm::vec4(frame.param("smrt.constantBias"), frame.param("smrt.slopeBias"), frame.param("smrt.thicknessM"), 0.0f);
  u.spatial = glm::vec4(frame.param("smrt.filterRadiusPx"), 0.0f, 0.0f, 0.0f);
  frame.setFilterBlock(u);
  ShaderDefines defines;
  mNearest.bind(true, defines);
  mMaps.depth().bindUnit(PN_TEX_FILTER0);
  frame.dispatchScreen(frame.visibilityProgram("techniques/filters/smrt.glsl", defines));
  if (u.spatial.x > 0.0f && !frame.pointsMode()) filterSpatially(frame);
}

void SmrtFilter::filterSpatially(FrameContext& frame) {
  const glm::ivec2 screen = frame.screen();
  if (mMeans.width() != screen.x || mMeans.height() != screen.y)
    mMeans = gl::Texture("smrt spatial filter means", {GL_TEXTURE_2D, GL_R32F, screen.x, screen.y, 1, 1});
  const gl::Program& program = frame.screenProgram("techniques/filters/smrt_filter.glsl", frame.params());
  mMeans.bindImage(PN_IMG_AUX0, GL_READ_WRITE);
  for (int copy = 0; copy < 2; ++copy) {  // the means along the edges, then back into the layer
    glProgramUniform1i(program.id(), PN_LOC_SWITCH, copy);
    frame.dispatchScreen(program, true);
  }
}

std::vector<DebugImage> SmrtFilter::debugImages() const { return {{std::string(kShadowMapImage), &mMaps.depth(), kShadowMapMeaning}}; }

}  // namespace penumbra
