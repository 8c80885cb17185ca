#pragma once
// A progress bar on stderr for long CPU loops, safe to advance from worker threads. It draws
// only when asked to and stderr is a terminal, so logs and pipes never receive control codes;
// in Lines mode a log or a pipe gets a plain line instead, at the first unit and then every
// kLineInterval, so a long run says how far it got wherever its output goes.
#include <atomic>
#include <chrono>
#include <cstddef>
#include <mutex>
#include <string>

namespace penumbra {

class ProgressBar {
public:
  /// Where stderr is not a terminal: nothing, or a line now and then.
  enum class Elsewhere { Nothing, Lines };
  /// A log gets a line at most this often (a few a minute).
  static constexpr auto kLineInterval = std::chrono::seconds(15);

  ProgressBar(std::string label, size_t total, bool wanted, Elsewhere elsewhere = Elsewhere::Nothing);
  ~ProgressBar();  // finishes the line if anything was drawn
  ProgressBar(const ProgressBar&) = delete;
  ProgressBar& operator=(const ProgressBar&) = delete;

  /// Counts `done` more units; redraws at most every kRedrawInterval, from whichever thread.
  void advance(size_t done);
  bool enabled() const { return mEnabled; }

private:
  void draw(size_t done);

  std::string mLabel;
  size_t mTotal;
  bool mEnabled;
  bool mLines = false;  // stderr is not a terminal: plain lines
  bool mDrawn = false;
  std::atomic<size_t> mDone{0};
  std::mutex mDrawMutex;
  std::chrono::steady_clock::time_point mStart, mLastDraw;
};

}  // namespace penumbra
