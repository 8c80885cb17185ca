#pragma once
// Temporal accumulation (docs/temporal.md): V averaged over frames by reprojection, so that a
// stochastic filter's noise (a Poisson disk turned per pixel and, with accumulation on, per
// frame) converges to its many-sample result over a few frames. Not a filter: one parameter
// group ("temporal.*") any filter can take, run by the core after each light's visibility (and
// contact) pass. It keeps, across frames, a history of V per light layer and the previous
// frame's camera and surface positions: history is rejected where the previous frame saw
// another surface, held to this frame's neighbourhood of V, and blended with weight α. It is
// reset when the screen, the light count or the technique changes, and on a camera cut. Known
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

/// What the core tells the accumulation at the start of a frame.
struct TemporalFrame {
  glm::ivec2 screen{0};
  int layers = 0;                      ///< lights (history layers)
  uint64_t techniqueKey = 0;           ///< changes when the technique or its parameters do: the history is reset
  bool cut = false;                    ///< a camera cut: the history is reset
  glm::mat4 clipFromWorld{1.0f};       ///< this frame's camera
  float pixelFootprintPerM = 0.0f;     ///< a pixel's width per metre of distance from the camera
};

class TemporalAccumulation {
public:
  /// The "temporal.*" parameters (one group of the add-ons, Registry.h's addOnGroups).
  static std::span<const ParamDesc> params();
  /// True when temporal.accumulate is on in `addOns`.
  static bool enabled(const Parameterized& addOns);

  /// Starts a frame; returns the sampling frame the filters turn their patterns by (common/
  /// frame.glsl's samplingFrame): 0 when accumulation is off, so nothing changes then. With it
  /// off the history is released.
  int beginFrame(const Parameterized& addOns, const TemporalFrame& frame);
  /// Blends the history of the frame's light (its visibility layer) into its V. The surfaces and
  /// the frame block must be bound, the visibility written (the core calls it after the filter
  /// and the contact pass).
  void apply(FrameContext& frame, const Parameterized& addOns);
  /// A light whose layer was not accumulated this frame (it casts no shadow): no history next frame.
  void skip(int layer);
  /// Ends the frame: its surface positions (the surfaces bound) become the next frame's.
  void endFrame(FrameContext& frame, const Parameterized& addOns);

  /// Frames accumulated since the history was last reset (0 after a reset).
  int historyFrames() const { return mHistoryFrames; }

private:
  void reset();

  gl::Texture mHistory[2];     ///< R32F 2D arrays, a layer per light: read one, write the other, swap
  gl::Texture mSurface;        ///< RGBA32F: the previous frame's world positions
  gl::Texture mNormal;         ///< RGBA16F: … and geometric normals
  int mWrite = 0;              ///< the history array written this frame
  std::vector<uint8_t> mValid, mWritten;  ///< per layer: history readable this frame, written this frame
  TemporalFrame mFrame, mPrevious;
  bool mHavePrevious = false;
  int mHistoryFrames = 0;
  int mFrameCount = 0;
};

}  // namespace penumbra
