#pragma once
// Temporal accumulation (docs/temporal.md): V averaged over frames by reprojection, so that a
// stochastic filter's noise (a Poisson disk turned per pixel and, with accumulation on, per
// frame) converges to its many-sample result over a few frames. Not a filter: one parameter
// group ("temporal.*") any filter can take, run by the core after each light's visibility (and
// contact) pass. It keeps, across frames, a history of V per light (in the light's state) and the
// previous frame's camera and surface positions: history is rejected where the previous frame saw
// another surface, held to this frame's neighbourhood of V, and blended with weight α. A light's
// history is dropped when its technique changes, every one when the screen changes and on a
// camera cut. Known
// artifacts: a lag where the shadow moves faster than the clamp's range follows (ghosting), and
// moving surfaces start afresh (no motion vectors: they are found again only within the
// tolerance).
#include "gl/Objects.h"

#include <penumbra/Params.h>

#include <glm/glm.hpp>

#include <cstdint>
#include <span>
#include <vector>

namespace penumbra {

class FrameContext;

/// One light's accumulated V (kept in the light's state, so it follows the light when the
/// lights are reordered): two R32F images of the surfaces' size, one read and one written each
/// frame, in step with every other light's.
struct TemporalHistory {
  gl::Texture images[2];
  bool valid = false;         ///< the image read next holds this light's V of the frame before
  bool written = false;       ///< this frame wrote the other one
  uint64_t techniqueKey = 0;  ///< the light's technique it was accumulated with
};

/// What the core tells the accumulation at the start of a frame.
struct TemporalFrame {
  glm::ivec2 screen{0};
  bool cut = false;                    ///< a camera cut: every history is dropped
  glm::mat4 clipFromWorld{1.0f};       ///< this frame's camera
  /// A pixel's width per metre of distance from the camera (an orthographic camera: in metres,
  /// the same everywhere).
  float pixelFootprintPerM = 0.0f;
};

class TemporalAccumulation {
public:
  /// The "temporal.*" parameters (one group of the add-ons, Technique.h's addOnGroups).
  static std::span<const ParamDesc> params();
  /// True when temporal.accumulate is on in `addOns` (a light's technique's add-on values).
  static bool enabled(const Parameterized& addOns);

  /// Starts a frame in which some light accumulates (`on`) or none does; returns the sampling
  /// frame the filters turn their patterns by (common/frame.glsl's samplingFrame): 0 when off,
  /// so nothing changes then. Off, the previous frame's surfaces are released.
  int beginFrame(bool on, const TemporalFrame& frame);
  /// Blends the light's history into its V (the frame's visibility layer). `techniqueKey` says
  /// what the light's V depends on besides the surfaces (its technique but the accumulation's
  /// own parameters): a history of another key is dropped. The surfaces and the frame block must
  /// be bound, the visibility written (the core calls it after the filter and the contact pass).
  void apply(FrameContext& frame, const Parameterized& addOns, TemporalHistory& history, uint64_t techniqueKey);
  /// Ends the frame: its surface positions (the surfaces bound) become the next frame's, and
  /// each history written this frame is the next frame's to read (the others are dropped).
  void endFrame(FrameContext& frame, const Parameterized& addOns, std::span<TemporalHistory* const> histories);

  /// Frames accumulated since the histories were last dropped together (0 after a cut, a resize
  /// or a frame without accumulation).
  int historyFrames() const { return mHistoryFrames; }

private:
  gl::Texture mSurface;        ///< RGBA32F: the previous frame's world positions
  gl::Texture mNormal;         ///< RGBA16F: … and geometric normals
  int mWrite = 0;              ///< which of each history's images is written this frame
  TemporalFrame mFrame, mPrevious;
  bool mHavePrevious = false;  ///< mPrevious and the surfaces hold the frame before
  bool mFresh = true;          ///< this frame reads no history (a cut, a resize, the first frame)
  int mHistoryFrames = 0;
  int mFrameCount = 0;
};

}  // namespace penumbra
