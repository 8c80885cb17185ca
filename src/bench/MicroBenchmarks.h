#pragma once
// Micro-benchmarks: building blocks timed alone, each next to the baseline it is measured
// against. The prefilter blocks (this file's runMicroBenchmarks) run on a texture of the bench's
// shadow-map size next to a plain copy of the same texture (the memory-bandwidth floor any pass
// that reads and writes it pays); the visibility passes next to their minimal lookup kernels
// (bench/VisibilityBaselines.h). Both go through runMicroItems: items interleaved round by
// round, so the machine's load falls on an item and its baseline alike, and each ratio is taken
// within a round.
#include "bench/BenchResults.h"

#include <functional>
#include <string>
#include <vector>

namespace penumbra::report {

/// One row of the micro table. `prepare` makes its inputs (untimed; compiles its programs) and
/// returns the timed work, which runs once and returns its own time in milliseconds.
struct MicroItem {
  std::string name;
  std::string description;  ///< what is timed, on what data
  std::string baseline;     ///< the item it is measured against; "" = none
  std::function<std::function<double()>()> prepare;
  /// Non-empty: not run; the times of the item of this name, measured against another baseline
  /// (a second yardstick for the same work). `prepare` is then unused.
  std::string sameAs = {};
};

/// `work` timed with the renderer's clock (GL timer queries, or glFinish + steady_clock when
/// cpuClock): the timed function of a MicroItem whose work is GL commands.
std::function<double()> timedWork(bool cpuClock, std::string name, std::function<void()> work);

/// Prepares every item (in order), runs each once untimed (the first dispatch of a program
/// includes its JIT, the first touch of memory its faults), then `rounds` rounds, each running
/// every item once in order. An item whose baseline is in the list gets `ratio`: the median and
/// 10th/90th percentiles over the rounds of its time over its baseline's time in the same round.
/// An item that throws (a GL error, …) is returned with `error` set and no times, and is not run
/// again; the others still run. Needs a current GL context.
std::vector<MicroResult> runMicroItems(const std::vector<MicroItem>& items, int rounds);

/// The prefilter building blocks on mapSize² textures, `repetitions` rounds (after one untimed
/// run), with the renderer's clock (GL timer queries, or glFinish + steady_clock when cpuClock).
std::vector<MicroResult> runMicroBenchmarks(int mapSize, int repetitions, bool cpuClock);

}  // namespace penumbra::report
