#pragma once
// The reference tracer against a plain Embree loop over the very same rays (reference/
// RayBenchmark.h), as two rows of the micro table: its ratio is the tracer's overhead over casting
// its rays (issue #20: ≥ 0.95× the plain loop's rate, a ratio ≤ 1.05). docs/bench.md.
#include "report/BenchResults.h"

#include <vector>

namespace penumbra::report {

/// On boxes' G-buffer at width × height (Penumbra's renderer; needs a current GL context) and its
/// sun at kReferenceBaselineSamples per pixel: "reference: plain Embree loop" (the baseline) and
/// "reference: ReferenceTracer::trace", `rounds` interleaved rounds, wall clock.
std::vector<MicroResult> runReferenceBaseline(int width, int height, int rounds);

/// Light samples per pixel of the rows: 64 keep a 256×144 run near a second on two cores.
inline constexpr int kReferenceBaselineSamples = 64;

}  // namespace penumbra::report
