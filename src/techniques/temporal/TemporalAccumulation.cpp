#include "techniques/temporal/TemporalAccumulation.h"

#include "frame/FrameContext.h"
#include "techniques/temporal/temporal.shared.h"
#include "shared/Bindings.h"

#include <penumbra/Error.h>

namespace penumbra {
namespace {

constexpr std::string_view kClampModes[] = {"off", "minmax", "variance"};
static_assert(PN_TEMPORAL_CLAMP_OFF == 0 && PN_TEMPORAL_CLAMP_MINMAX == 1 && PN_TEMPORAL_CLAMP_VARIANCE == 2,
              "temporal.clamp's choices are indexed by the shader's modes");

constexpr ParamDesc kParams[] = {
    {"temporal.accumulate", "Accumulate",
     "on: V is averaged over frames by reprojection into the previous frame (history dropped where that frame saw another "
     "surface, held to this frame's 3x3 range of V); pcf's and pcss's Poisson disks, smrt's rays and the contact march turn every frame",
     "", 0.0f, 0.0f, 1.0f, 1.0f, kOffOn},
    {"temporal.alpha", "New-frame weight",
     "weight of this frame's V in the blend with the history: about 1/alpha frames are averaged; smaller is smoother and lags more",
     "fraction", 0.1f, 0.02f, 1.0f, 0.0f},
    {"temporal.clamp", "History clamp",
     "how the history is held to this frame's 3x3 neighbourhood of V before the blend: off, its min..max, or its mean +- "
     "temporal.clipSigma standard deviations (within min..max)", "", 1.0f, 0.0f, 2.0f, 1.0f, kClampModes},
    {"temporal.clipSigma", "Clip width", "temporal.clamp=variance: the range's half-width in standard deviations of the neighbourhood's V",
     "sigma", 1.0f, 0.25f, 4.0f, 0.0f},
    {"temporal.snapV", "Snap difference",
     "where this frame's V and the clamped history differ by more than this, this frame's V is taken as it is (the weight "
     "rises from alpha to 1 over the next 0.25): a shadow that arrives or leaves whole is not smeared; 1 = never", "V", 0.2f, 0.0f, 1.0f, 0.0f},
    {"temporal.tolerancePx", "Surface tolerance",
     "a history texel counts where the previous frame's surface there lies within this many pixel footprints of the pixel's "
     "tangent plane (farther: another surface, disoccluded or moved)", "pixels", 1.0f, 0.05f, 16.0f, 0.0f},
};

// The sampling frame cycles through this many values: float(frame) · golden ratio keeps its
// fraction's precision (common/sampling.glsl) while the values stay this small.
constexpr int kSamplingPeriod = 1024;

}  // namespace

std::span<const ParamDesc> TemporalAccumulation::params() { return kParams; }

bool TemporalAccumulation::enabled(const Parameterized& addOns) { return addOns.paramInt("temporal.accumulate") != 0; }

int TemporalAccumulation::beginFrame(bool on, const TemporalFrame& f) {
  mFrame = f;
  if (!on) {
    mSurface = gl::Texture();
    mNormal = gl::Texture();
    mHavePrevious = false;
    mHistoryFrames = 0;
    return 0;
  }
  if (!mSurface || mSurface.width() != f.screen.x || mSurface.height() != f.screen.y) {
    mSurface = gl::Texture("temporal previous surface", {GL_TEXTURE_2D, GL_RGBA32F, f.screen.x, f.screen.y, 1, 1});
    mSurface.setSampling(GL_NEAREST, GL_NEAREST);
    mNormal = gl::Texture("temporal previous normal", {GL_TEXTURE_2D, GL_RGBA16F, f.screen.x, f.screen.y, 1, 1});
    mNormal.setSampling(GL_NEAREST, GL_NEAREST);
    mHavePrevious = false;
  }
  mFresh = !mHavePrevious || f.cut;
  if (mFresh) mHistoryFrames = 0;
  mFrameCount = (mFrameCount + 1) % kSamplingPeriod;
  return mFrameCount + 1;  // never 0 while on: 0 is the still pattern
}

void TemporalAccumulation::apply(FrameContext& frame, const Parameterized& addOns, TemporalHistory& history,
                                 uint64_t techniqueKey) {
  PN_ASSERT(mSurface);
  const glm::ivec2 screen = frame.screen();
  // The history holds what the visibility array does: one channel, or RGB (translucent casters).
  const GLenum format = static_cast<GLenum>(frame.colourVisibility() ? GL_RGBA32F : GL_R32F);
  if (!history.images[0] || history.images[0].width() != screen.x || history.images[0].height() != screen.y ||
      history.images[0].desc().format != format) {
    for (int i = 0; i < 2; ++i) {
      history.images[i] = gl::Texture(i == 0 ? "temporal history 0" : "temporal history 1", {GL_TEXTURE_2D, format, screen.x, screen.y, 1, 1});
      history.images[i].setSampling(GL_NEAREST, GL_NEAREST);
    }
    history.valid = false;
  }
  const bool valid = history.valid && !mFresh && history.techniqueKey == techniqueKey;
  history.techniqueKey = techniqueKey;
  const int layer = frame.visibilityLayer();
  gpu::TemporalUniforms u{};
  u.previousClipFromWorld = mPrevious.clipFromWorld;
  u.blend = glm::vec4(addOns.param("temporal.alpha"), addOns.param("temporal.tolerancePx"), mFrame.pixelFootprintPerM,
                      valid ? 1.0f : 0.0f);
  u.clip = glm::vec4(addOns.param("temporal.clamp"), addOns.param("temporal.clipSigma"), addOns.param("temporal.snapV"), 0.0f);
  u.layer = glm::ivec4(layer, 0, 0, 0);
  frame.setFilterBlock(u);
  const gl::Texture& written = history.images[mWrite];
  history.images[1 - mWrite].bindUnit(PN_TEX_HISTORY);
  mSurface.bindUnit(PN_TEX_PREVIOUS_SURFACE);
  mNormal.bindUnit(PN_TEX_PREVIOUS_NORMAL);
  written.bindImage(PN_IMG_OUTPUT, GL_WRITE_ONLY);
  frame.dispatchScreen(frame.screenProgram("techniques/temporal/temporal_accumulate.glsl", addOns), true);
  glCopyImageSubData(written.id(), GL_TEXTURE_2D, 0, 0, 0, 0, frame.visibility().id(), GL_TEXTURE_2D_ARRAY, 0, 0, 0,
                     layer, written.width(), written.height(), 1);
  history.written = true;
}

void TemporalAccumulation::endFrame(FrameContext& frame, const Parameterized& addOns, std::span<TemporalHistory* const> histories) {
  if (!mSurface) return;
  mSurface.bindImage(PN_IMG_OUTPUT, GL_WRITE_ONLY);
  mNormal.bindImage(PN_IMG_AUX0, GL_WRITE_ONLY);
  FrameContext::dispatch2D(frame.screenProgram("techniques/temporal/temporal_surface.glsl", addOns), mSurface.width(),
                           mSurface.height(), PN_SCREEN_GROUP);
  for (TemporalHistory* h : histories) {
    h->valid = h->written;
    h->written = false;
  }
  mWrite = 1 - mWrite;
  mPrevious = mFrame;
  mHavePrevious = true;
  ++mHistoryFrames;
}

}  // namespace penumbra
