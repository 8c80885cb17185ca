#include "viewer/HeatmapJob.h"

#include "comparison/FrameComparison.h"

#include <penumbra/Error.h>
#include <penumbra/Reference.h>

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <utility>

namespace penumbra::viewer {
namespace {

// Rows traced per call: small enough that progress moves and cancelling is quick, large enough
// that Embree's threads stay busy within a band.
constexpr int kBandRows = 8;

/// Rows [y0, y1) of a per-pixel array; an empty array (an optional G-buffer field) stays empty.
template <class T>
std::vector<T> rows(const std::vector<T>& all, int width, int y0, int y1) {
  if (all.empty()) return {};
  const auto w = static_cast<std::ptrdiff_t>(width);
  return std::vector<T>(all.begin() + y0 * w, all.begin() + y1 * w);
}

}  // namespace

HeatmapJob::~HeatmapJob() { cancel(); }

void HeatmapJob::cancel() {
  mCancel = true;
  if (mThread.joinable()) mThread.join();
  mCancel = false;
  mRunning = false;
}

void HeatmapJob::start(const Scene& scene, GBufferData gbuffer, std::vector<float> visibility, ColorImage color,
                       int samples, uint64_t version) {
  cancel();
  {
    std::lock_guard lock(mMutex);
    mError.clear();
    mResult.reset();
  }
  mProgress = 0.0f;
  mRunning = true;
  mThread = std::thread(&HeatmapJob::run, this, scene, std::move(gbuffer), std::move(visibility), std::move(color),
                        samples, version);
}

std::optional<HeatmapResult> HeatmapJob::takeResult() {
  std::lock_guard lock(mMutex);
  return std::exchange(mResult, std::nullopt);
}

bool HeatmapJob::untaken() const {
  std::lock_guard lock(mMutex);
  return mResult.has_value() || !mError.empty();
}

std::string HeatmapJob::takeError() {
  std::lock_guard lock(mMutex);
  return std::exchange(mError, std::string());
}

void HeatmapJob::run(Scene scene, GBufferData g, std::vector<float> v, ColorImage color, int samples, uint64_t version) {
  try {
    const auto start = std::chrono::steady_clock::now();
    const ReferenceTracer tracer(scene);
    ReferenceOptions options;
    options.samples = samples;
    options.progress = false;  // the viewer draws its own progress bar
    options.useCache = false;  // per-band results are not worth a cache file each
    const size_t n = static_cast<size_t>(g.width) * static_cast<size_t>(g.height);
    // Every light is traced, so the reference view is lit like the frame; the heatmap and its
    // metrics are the first light's (the one the frame's visibility image shows).
    const size_t lights = scene.lights.size();
    std::vector<std::vector<float>> vRef(lights, std::vector<float>(n, 1.0f));
    std::vector<uint8_t> mask(n, 0);
    int spp = 0;
    const int bands = (g.height + kBandRows - 1) / kBandRows;
    for (size_t l = 0; l < lights; ++l)
      for (int y0 = 0; y0 < g.height; y0 += kBandRows) {
        if (mCancel) return;
        const int y1 = std::min(g.height, y0 + kBandRows);
        GBufferData band;
        band.width = g.width;
        band.height = y1 - y0;
        band.position = rows(g.position, g.width, y0, y1);
        band.geoNormal = rows(g.geoNormal, g.width, y0, y1);
        band.normal = rows(g.normal, g.width, y0, y1);
        band.albedo = rows(g.albedo, g.width, y0, y1);
        band.triangle = rows(g.triangle, g.width, y0, y1);
        const ReferenceResult r = tracer.trace(band, scene.lights[l], options);
        std::copy(r.visibility.begin(), r.visibility.end(), vRef[l].begin() + static_cast<std::ptrdiff_t>(y0) * g.width);
        if (l == 0) {
          std::copy(r.litMask.begin(), r.litMask.end(), mask.begin() + static_cast<std::ptrdiff_t>(y0) * g.width);
          spp = r.samplesPerPixel;
        }
        mProgress = static_cast<float>(static_cast<int>(l) * bands + y0 / kBandRows + 1) /
                    static_cast<float>(static_cast<int>(lights) * bands);
      }
    HeatmapResult result;
    result.metrics = compareVisibility(v, vRef.at(0), mask, g.width);
    result.image = errorHeatmap(v, vRef.at(0), mask, g.width, g.height, color.rgba.empty() ? nullptr : &color, report::kLabHeatmap);
    result.samplesPerPixel = spp;
    result.vRef = std::move(vRef);
    result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    result.version = version;
    std::lock_guard lock(mMutex);
    mResult = std::move(result);
  } catch (const std::exception& e) {
    std::lock_guard lock(mMutex);
    mError = e.what();
  }
  mRunning = false;
}

}  // namespace penumbra::viewer
