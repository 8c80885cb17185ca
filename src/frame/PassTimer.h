#pragma once
// Per-pass GPU times. Real GPUs: GL_TIME_ELAPSED queries. Software rasterisers (llvmpipe),
// whose timer queries read 0 for real work: glFinish + std::chrono::steady_clock around the
// pass, or with PENUMBRA_CLOCK=cpu the CPU time of the whole process (every driver thread), which
// a shared, loaded machine disturbs far less. Which clock produced a number is recorded with it
// (PassTimings::clock).
#include "gl/Objects.h"

#include <penumbra/Timings.h>

#include <chrono>
#include <string>
#include <vector>

namespace penumbra {

/// PENUMBRA_CLOCK=cpu: time by the process's CPU time (every thread) rather than the wall clock.
bool processCpuClockWanted();
/// The process's CPU time so far, ms (CLOCK_PROCESS_CPUTIME_ID).
double processCpuMs();

class PassTimer {
public:
  /// useCpuClock: a software rasteriser (time on the CPU side, see above).
  explicit PassTimer(bool useCpuClock);
  void beginFrame();
  void begin(std::string name);
  void end();
  /// Collects the frame's results (waits for the queries).
  PassTimings endFrame();

private:
  struct Entry {
    std::string name;
    gl::Query query;
    double cpuMs = 0.0;
  };
  bool mCpuClock;
  bool mProcessTime;  ///< PENUMBRA_CLOCK=cpu: process CPU time instead of the wall clock
  double mStartCpuMs = 0.0;
  std::vector<Entry> mEntries;
  std::vector<gl::Query> mPool;  // reused across frames: no GL object growth
  std::chrono::steady_clock::time_point mStart;
};

/// Times one pass for the lifetime of the scope.
class ScopedPass {
public:
  /// Also opens a GL debug group named after the pass, so captures show the frame's structure.
  ScopedPass(PassTimer& t, std::string name) : mT(t) {
    glPushDebugGroup(GL_DEBUG_SOURCE_APPLICATION, 0, static_cast<GLsizei>(name.size()), name.c_str());
    mT.begin(std::move(name));
  }
  ~ScopedPass() {
    mT.end();
    glPopDebugGroup();
  }
  ScopedPass(const ScopedPass&) = delete;
  ScopedPass& operator=(const ScopedPass&) = delete;

private:
  PassTimer& mT;
};

}  // namespace penumbra
