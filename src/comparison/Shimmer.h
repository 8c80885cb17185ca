#pragma once
// The shimmer measure: how much shadow edges crawl while the camera moves a little. The world
// points seen in the first frame are kept fixed and each frame's visibility is evaluated at them
// (Renderer::visibilityAt), so only a change of the shadow maps can change it: pixels that move
// with the camera would change for reasons that are not shimmer.
#include <penumbra/Renderer.h>

#include <cstddef>
#include <vector>

namespace penumbra {

struct ShimmerOptions {
  int steps = 50;                ///< camera moves (frames after the first), ≥ 1
  float changeThresholdV = 0.1f; ///< a point "changes" when |ΔV| between consecutive frames exceeds this
  /// A point is "near a shadow edge" when frame 0's V at some pixel within this many pixels
  /// differs from its own by more than 0.5, or its own V is strictly between 0.02 and 0.98.
  int edgeRadiusPx = 2;
  /// The camera path (shimmerCameraPath): step sizes in texels of the first shadow view's map at
  /// frame 0 (the finest cascade for csm): sub-texel and a few texels.
  float subTexelStep = 0.3f, fewTexelStep = 2.5f;
  /// Points are kept only if they stay this far inside the image (NDC) in every frame.
  float screenMarginNdc = 0.05f;
};

struct ShimmerResult {
  double shimmerPct = 0.0;  ///< shimmer_pct: % of (edge point, consecutive frame pair) with |ΔV| > threshold
  size_t edgePoints = 0;    ///< points near shadow edges that stayed in view
  size_t changes = 0;       ///< (point, frame pair) changes counted
  int steps = 0;
  float texelM = 0.0f;      ///< the step unit: one texel of view 0 at frame 0 (m)
};

/// The camera path: `steps` cameras after `start`, cycling through a sub-texel sideways move, a
/// sub-texel move forward, a few-texel move sideways and up, and a small turn (the target moves
/// across the view by subTexelStep texels at 20 m); directions flip every cycle so the camera
/// stays near the start.
std::vector<Camera> shimmerCameraPath(const Camera& start, int steps, float texelM, const ShimmerOptions& options = {});

/// Renders frame 0 with the renderer's scene camera, then one frame per camera of the path, and
/// measures shimmer at frame 0's edge points. The renderer must have a scene and a technique; it
/// is left at the scene's own camera afterwards (the frame rendered last is the path's end).
/// Throws penumbra::Error if options are out of range.
ShimmerResult measureShimmer(Renderer& renderer, const RenderOptions& render, const ShimmerOptions& options = {});

}  // namespace penumbra
