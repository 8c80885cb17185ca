#pragma once
// Micro-benchmarks: building blocks of the prefilter passes timed alone on a texture of the
// bench's shadow-map size, each next to a plain copy of the same texture (the memory-bandwidth
// floor any pass that reads and writes it pays). Generic: a new building block is one entry in
// the table of MicroBenchmarks.cpp; no filter is asked or named.
#include "report/BenchResults.h"

#include <vector>

namespace penumbra::report {

/// Runs every micro-benchmark `repetitions` times (after one untimed run) on mapSize² textures,
/// with the renderer's clock (GL timer queries, or glFinish + steady_clock when cpuClock).
/// Needs a current GL context. A block that fails (a GL error) is returned with its `error` set
/// and no times; the others still run.
std::vector<MicroResult> runMicroBenchmarks(int mapSize, int repetitions, bool cpuClock);

}  // namespace penumbra::report
