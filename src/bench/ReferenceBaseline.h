#pragma once
// The reference tracer against plain Embree loops over the very same rays (reference/
// RayBenchmark.h), as rows of the micro table (docs/bench.md). Issue #20 asks for ≥ 0.95× a plain
// loop's rate, a time ratio ≤ 1.05: the plain loop casting the recorded rays one rtcOccluded1 call
// a ray is that yardstick; the loop casting them as the tracer does (a coherent stream a pixel) is
// a stricter one, and its ratio is what making the rays costs on top of casting them.
#include "bench/BenchResults.h"

#include <vector>

namespace penumbra::report {

/// On boxes' G-buffer at width × height (Penumbra's renderer; needs a current GL context) and its
/// sun at kReferenceBaselineSamples per pixel: "reference: plain Embree loop" (recorded rays, a
/// stream a pixel: the baseline), the recorded rays one call each, the loop that generates them,
/// and "reference: ReferenceTracer::trace" over the stream and again over one call a ray; `rounds`
/// interleaved rounds, wall clock or the process's CPU time (PENUMBRA_CLOCK=cpu).
std::vector<MicroResult> runReferenceBaseline(int width, int height, int rounds);

/// Light samples per pixel of the rows: 64 keep a 256×144 run near a second on two cores.
inline constexpr int kReferenceBaselineSamples = 64;

}  // namespace penumbra::report
