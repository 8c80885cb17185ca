#include "frame/PassTimer.h"

#include <numeric>

namespace penumbra {

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
    e.cpuMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - mStart).count();
  } else {
    glEndQuery(GL_TIME_ELAPSED);
  }
}

PassTimings PassTimer::endFrame() {
  PassTimings t;
  t.clock = mCpuClock ? "glFinish+steady_clock" : "gl-timer-query";
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
