#pragma once
// Per-pass times of a frame, with the clock that produced them (docs/design.md, Timing).
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace penumbra {

/// Per-pass times of the last frame, in the order the passes ran.
struct PassTimings {
  std::vector<std::pair<std::string, double>> ms;  ///< pass name → milliseconds
  std::string clock;                               ///< "gl-timer-query" or "glFinish+steady_clock"
  double get(std::string_view pass) const;         ///< 0 for a pass that did not run
  double total() const;
};

}  // namespace penumbra
