#pragma once
// The reference's ray throughput against plain Embree loops over the very same rays (issue #20
// asks the reference for ≥ 0.95× a plain loop's rate). The rays are recorded once with the
// tracer's own generator, and how many of them are blocked; the bench's micro table times the ways
// of casting them, interleaved, each checked to find the same rays blocked (report/
// ReferenceBaseline.cpp, docs/bench.md).
#include <penumbra/Image.h>
#include <penumbra/Scene.h>

#include <cstddef>
#include <memory>

namespace penumbra::reference {

class RayBenchmark {
public:
  /// Records the rays ReferenceTracer::trace casts for `g` (a G-buffer of `scene`) toward `light`,
  /// a soft light, at `samples` per pixel. Throws penumbra::Error for a hard light or bad inputs.
  RayBenchmark(const Scene& scene, const GBufferData& g, const Light& light, int samples);
  ~RayBenchmark();
  RayBenchmark(const RayBenchmark&) = delete;
  RayBenchmark& operator=(const RayBenchmark&) = delete;

  /// Rays cast per run (the same count by both).
  size_t rays() const;
  /// ReferenceTracer::trace of the G-buffer, cache off: rays generated, cast and summed into
  /// the result, over every core. Wall seconds.
  double traceReference() const;
  /// The recorded rays through a plain Embree loop over the same BVH: each pixel's rays one
  /// coherent rtcOccluded1M stream that skips its triangle, pixel rows over every core as the
  /// tracer does; nothing else. Wall seconds.
  double tracePlainLoop() const;

  /// The recorded rays cast the plainest way: one rtcOccluded1 call a ray (no stream, no
  /// coherence hint), skipping the pixel's triangle, pixel rows over every core. Wall seconds.
  double traceSingleRays() const;

  /// The plain loop generating the rays as it goes (the tracer's generator, per pixel), casting
  /// them as tracePlainLoop does and counting them (checked against the recorded rays): Embree's
  /// answers are not read, and there is no result, no cache key, no per-pixel sum. What the tracer
  /// adds to this is its own bookkeeping. Wall seconds.
  double traceGeneratingLoop() const;

private:
  struct Impl;
  std::unique_ptr<Impl> mImpl;
};

}  // namespace penumbra::reference
