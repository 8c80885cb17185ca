#pragma once
// The visibility pass of hard, pcf, vsm, vssm and msm, each timed next to its minimal lookup
// kernel (micro/lookup.glsl: read the G-buffer position, apply one matrix, do the filter's
// taps and closing arithmetic) on the same G-buffer and the same map, interleaved round by round.
// The pass's time over its kernel's is its overhead over its own arithmetic: what view
// selection, cascade blending, bias geometry and per-view loads cost where the configuration
// does not need them (issue #20 sets ≤ 1.5× for hard and pcf, ≤ 2× for vsm, vssm and msm).
// docs/bench.md, "Micro-benchmarks", says how to read the rows.
#include "bench/BenchResults.h"

#include <string>
#include <vector>

namespace penumbra::report {

struct VisibilityBaselineSettings {
  int width = 256, height = 144;  ///< the G-buffer, pixels (bench's --size)
  int mapSize = 1024;             ///< shadow-map texels per side (bench's --shadow-map)
  int rounds = 9;                 ///< timed rounds, after one untimed one
  /// glFinish + steady_clock (llvmpipe, whose timer queries read 0); else GL timer queries. The
  /// renderer picks its own clock by the same rule (gl::isSoftwareRenderer).
  bool cpuClock = true;
  std::string scene = "boxes";  ///< a built-in scene: its camera and light, the uniform projection
};

/// Rows in pairs: "lookup: …" (a kernel, no baseline) then "visibility: <filter>" (the real pass,
/// through penumbra::Renderer with the filter's defaults, measured as the frame's "visibility"
/// pass; baseline = that kernel, `ratio` = pass / kernel per round). Where the filter's own taps
/// are more work than its minimal kernel's (pcf's turned Poisson disk, vsm's and msm's pixel
/// footprint), a second pair follows: the kernel of those taps, and "visibility: <filter>, against
/// the kernel of its own taps" (the same timings as the pass's row, measured against it). A kernel
/// is checked against its pass before it is timed: one that disagrees on the visibility (it would
/// not be measuring the same lookup) is reported as failed. Needs a current GL 4.5 context.
std::vector<MicroResult> runVisibilityBaselines(const VisibilityBaselineSettings& settings);

}  // namespace penumbra::report
