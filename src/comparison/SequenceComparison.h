#pragma once
// Error over time: an animated scene rendered frame by frame and compared with its reference
// frame by frame (the per-frame metrics, their mean and worst frame), the flicker between
// consecutive frames (comparison/Flicker.h) and the lag on pixels whose reference changed lately
// (comparison/Lag.h). `penumbra compare --frames N` prints it.
#include "comparison/Flicker.h"
#include "comparison/Lag.h"

#include <penumbra/Metrics.h>
#include <penumbra/Reference.h>
#include <penumbra/Renderer.h>

#include <functional>
#include <optional>
#include <vector>

namespace penumbra::report {

/// The frame times: start, start + 1/fps, …
struct SequenceTiming {
  int frames = 1;        ///< ≥ 1
  float fps = 30.0f;     ///< > 0
  float startS = 0.0f;
  float timeS(int frame) const { return startS + static_cast<float>(frame) / fps; }
};

struct SequenceFrame {
  float timeS = 0.0f;
  VisibilityMetrics metrics;  ///< the combined V against the combined V_ref
  std::optional<ColourMetrics> colour;  ///< FrameComparison::colour: one shadowed light whose reference has colour
  FlickerCounts flicker;      ///< from the frame before into this one, every shadowed light's (empty for the first)
  LagCounts lag;              ///< this frame's changing pixels, every shadowed light's (empty for the first)
  std::vector<LightShadowReport> lights;  ///< what each light got in this frame (map, pages)
};

/// One shadow-casting light's flicker and lag over the sequence (its own V against its own V_ref).
struct LightSequence {
  size_t index = 0;  ///< in Scene::lights
  FlickerCounts flicker;
  LagCounts lag;
};

/// What the frames of a sequence share whatever the technique: each frame's G-buffer and its
/// references (the G-buffer pass does not depend on the technique). compareSequence fills it on a
/// first call and reads it on the next ones, so that the configurations of one scene (the bench)
/// trace each frame once and read no G-buffer back.
struct SequenceReferences {
  struct Frame {
    GBufferData gbuffer;
    std::vector<ReferenceResult> lights;
  };
  std::vector<Frame> frames;
};

/// How fast the camera walk turns (compare --walk, and the bench's scoring of a scene that does
/// not move): 12° a second around the target, 0.4° a frame at 30 fps, about 5 mm a frame at
/// pen's 0.75 m — a slow look around that still moves every projection's texel grid.
inline constexpr float kWalkDegreesPerSecond = 12.0f;

/// Replaces the scene's motion with the walk: nothing in the scene moves (its animation is
/// dropped, the scene stays as it is posed), and for each frame of `timing` the camera is turned
/// about the vertical axis through its target by kWalkDegreesPerSecond × (t − timing.startS), at
/// the same distance and height, looking at the target. Frame 0 is the view as it was.
void addCameraWalk(Scene& scene, const SequenceTiming& timing);

struct SequenceComparison {
  std::vector<SequenceFrame> frames;
  double rmseMean = 0.0;      ///< rmse_mean: the mean of the frames' RMSE
  double penumbraRmseMean = 0.0;  ///< penumbra_rmse_mean: the mean of the frames' penumbra RMSE
  size_t rmseWorstFrame = 0;  ///< rmse_worst_frame: the index of the frame with the largest RMSE
  double rmseWorst = 0.0;
  /// Every consecutive pair and every shadow-casting light together: flicker_pct = flicker.pct()
  /// (a point followed under two lights counts twice, once per light's V).
  FlickerCounts flicker;
  LagCounts lag;              ///< every frame's and light's changing pixels: lag_rmse = lag.rmse(), ghost_pct = lag.ghostPct()
  std::vector<LightSequence> lights;  ///< each shadow-casting light's own (the sums above add them)
  double referenceSeconds = 0.0;
  bool referenceCached = true;  ///< every frame's reference came from the cache
};

/// Renders `scene` (the renderer's scene with its animation, at any pose) at each frame time
/// (poseScene, Renderer::setPose), traces each frame's reference (a BVH per pose where objects
/// moved) and compares. `progress(frame)` is called after each frame when given. The renderer
/// is left at the last frame's pose. With `shared`, each frame's G-buffer and references come
/// from it when it holds the frame, and go into it when it does not. Throws penumbra::Error on
/// bad timing.
SequenceComparison compareSequence(Renderer& renderer, const Scene& scene, const RenderOptions& render,
                                   const SequenceTiming& timing, const ReferenceOptions& reference,
                                   const FlickerOptions& flicker = {}, const std::function<void(int)>& progress = {},
                                   const LagOptions& lag = {}, SequenceReferences* shared = nullptr);

}  // namespace penumbra::report
