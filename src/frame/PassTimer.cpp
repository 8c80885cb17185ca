#include "frame/PassTimer.h"

#include <cstdlib>
#include <ctime>
#include <numeric>
#include <string_view>

namespace penumbra {

// PENUMBRA_CLOCK=cpu: software rasterisers are timed by the CPU time of the whole process (all
// of the driver's threads) instead of the wall clock: on a machine shared with other work a
// pass's wall time grows with the load, its CPU time barely does.
bool processCpuClockWanted() {
  const char* v = std::getenv("PENUMBRA_CLOCK");
  return v && std::string_view(v) == "cpu";
}

double processCpuMs() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) * 1e3 + static_cast<double>(t.tv_nsec) * 1e-6;
}

PassTimer::PassTimer(bool useCpuClock) : mCpuClock(useCpuClock), mProcessTime(useCpuClock && processCpuClockWanted()) {}

double PassTimings::get(std::string_view pass) const {
  double sum = 0.0;
  for (const auto& [name, ms] : this->ms)
    if (name == pass) sum += ms;
  return sum;
}

double PassTimings::total() const {
  double sum = 0.0;
  for (const auto& [name, ms] : this->ms) sum += ms;
  return sum;
}

void PassTimer::beginFrame() {
  for (Entry& e : mEntries)
    if (e.query) mPool.push_back(std::move(e.query));
  mEntries.clear();
}

void PassTimer::begin(std::string name) {
  Entry e;
  e.name = std::move(name);
  if (mCpuClock) {
    glFinish();
    mStart = std::chrono::steady_clock::now();
    mStartCpuMs = mProcessTime ? processCpuMs() : 0.0;
  } else {
    if (mPool.empty()) mPool.emplace_back("pass timer", GL_TIME_ELAPSED);
    e.query = std::move(mPool.back());
    mPool.pop_back();
    glBeginQuery(GL_TIME_ELAPSED, e.query.id());
  }
  mEntries.push_back(std::move(e));
}

void PassTimer::end() {
  Entry& e = mEntries.back();
  if (mCpuClock) {
    glFinish();
    e.cpuMs = mProcessTime ? processCpuMs() - mStartCpuMs
                           : std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - mStart).count();
  } else {
    glEndQuery(GL_TIME_ELAPSED);
  }
}

PassTimings PassTimer::endFrame() {
  PassTimings t;
  t.clock = !mCpuClock ? "gl-timer-query" : mProcessTime ? "glFinish+process_cpu_time" : "glFinish+steady_clock";
  for (Entry& e : mEntries) {
    double ms = e.cpuMs;
    if (!mCpuClock) {
      GLuint64 ns = 0;
      glGetQueryObjectui64v(e.query.id(), GL_QUERY_RESULT, &ns);
      ms = static_cast<double>(ns) * 1e-6;
    }
    // Sub-passes with the same name (e.g. one per cascade) add up.
    bool merged = false;
    for (auto& [name, sum] : t.ms)
      if (name == e.name) { sum += ms; merged = true; }
    if (!merged) t.ms.emplace_back(e.name, ms);
  }
  return t;
}

}  // namespace penumbra
