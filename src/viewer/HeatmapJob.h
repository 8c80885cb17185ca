#pragma once
// The error heatmap of the viewer: the frame's visibility against the Embree reference
// (include/penumbra/Reference.h, Metrics.h), traced on a background thread so that the window
// never freezes. The G-buffer is traced in bands of rows, which gives a progress fraction and
// lets a new request or closing the window cancel the work between bands.
#include <penumbra/Metrics.h>
#include <penumbra/Renderer.h>
#include <penumbra/Scene.h>

#include <atomic>
#include <cstdint>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

namespace penumbra::viewer {

struct HeatmapResult {
  ColorImage image;           ///< errorHeatmap() over the frame's colour, row 0 = top
  /// The reference's V of every light (G-buffer order, row 0 = bottom): the reference view.
  std::vector<std::vector<float>> vRef;
  VisibilityMetrics metrics;  ///< the first light's V against its V_ref over the pixels that face it
  int samplesPerPixel = 0;
  double seconds = 0.0;       ///< wall-clock time of the trace
  uint64_t version = 0;       ///< ViewSession::version() of the frame it measures
};

class HeatmapJob {
public:
  HeatmapJob() = default;
  ~HeatmapJob();  ///< cancels and joins
  HeatmapJob(const HeatmapJob&) = delete;
  HeatmapJob& operator=(const HeatmapJob&) = delete;

  /// Starts a new job (cancelling a running one) on a copy of one frame's data: the scene (its
  /// casters and lights: the heatmap is the first light's, the reference view lit by all), its
  /// G-buffer, the first light's visibility and colour (the heatmap's backdrop; empty
  /// = V_ref in grey). `samples` = light samples per pixel for a light of size > 0.
  void start(const Scene& scene, GBufferData gbuffer, std::vector<float> visibility, ColorImage color,
             int samples, uint64_t version);
  void cancel();
  bool running() const { return mRunning.load(); }
  /// Fraction of the rows traced, 0..1.
  float progress() const { return mProgress.load(); }
  /// The finished result, once (then empty until the next job finishes).
  std::optional<HeatmapResult> takeResult();
  /// A finished result or error not taken yet: the job is done, its images not yet shown.
  bool untaken() const;
  /// The last job's error message, once ("" if none).
  std::string takeError();

private:
  void run(Scene scene, GBufferData gbuffer, std::vector<float> visibility, ColorImage color, int samples,
           uint64_t version);

  std::thread mThread;
  std::atomic<bool> mCancel{false}, mRunning{false};
  std::atomic<float> mProgress{0.0f};
  mutable std::mutex mMutex;
  std::optional<HeatmapResult> mResult;
  std::string mError;
};

}  // namespace penumbra::viewer
