#pragma once
// What a frame's passes cost, with the clock that measured them (docs/design.md, Timing), and
// what a technique made once for the casters it was given.
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

/// Work a filter does once and keeps while the casters do not move (a baked distance field): in
/// no frame's time, and valid only for static casters: a caster that moves makes it again.
struct OneOffCost {
  std::string what;      ///< what was made, e.g. "distance-field bake, 128 voxels on the longest side"
  double seconds = 0.0;  ///< what making it took (read from a cache: what the original work took)
  bool cached = false;   ///< this time it came from an on-disk cache (seconds is still the work's)
};

}  // namespace penumbra
