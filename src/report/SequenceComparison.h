#pragma once
// Error over time: an animated scene rendered frame by frame and compared with its reference
// frame by frame (the per-frame metrics, their mean and worst frame), the flicker between
// consecutive frames (metrics/Flicker.h) and the lag on pixels whose reference changed lately
// (metrics/Lag.h). `penumbra compare --frames N` prints it.
#include "metrics/Flicker.h"
#include "metrics/Lag.h"

#include <penumbra/Metrics.h>
#include <penumbra/Reference.h>
#include <penumbra/Renderer.h>

#include <functional>
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
  FlickerCounts flicker;      ///< from the frame before into this one, every shadowed light's (empty for the first)
  LagCounts lag;              ///< this frame's changing pixels, every shadowed light's (empty for the first)
};

/// One shadow-casting light's flicker and lag over the sequence (its own V against its own V_ref).
struct LightSequence {
  size_t index = 0;  ///< in Scene::lights
  FlickerCounts flicker;
  LagCounts lag;
};

struct SequenceComparison {
  std::vector<SequenceFrame> frames;
  double rmseMean = 0.0;      ///< rmse_mean: the mean of the frames' RMSE
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
/// is left at the last frame's pose. Throws penumbra::Error on bad timing.
SequenceComparison compareSequence(Renderer& renderer, const Scene& scene, const RenderOptions& render,
                                   const SequenceTiming& timing, const ReferenceOptions& reference,
                                   const FlickerOptions& flicker = {}, const std::function<void(int)>& progress = {},
                                   const LagOptions& lag = {});

}  // namespace penumbra::report
