#include "base/ProgressBar.h"

#include <fmt/format.h>

#include <cstdio>
#include <utility>
#include <unistd.h>

namespace penumbra {
namespace {

// Ten redraws a second look live; more would only cost terminal bandwidth.
constexpr auto kRedrawInterval = std::chrono::milliseconds(100);
constexpr int kBarWidthChars = 40;

}  // namespace

ProgressBar::ProgressBar(std::string label, size_t total, bool wanted, Elsewhere elsewhere)
    : mLabel(std::move(label)), mTotal(total), mStart(std::chrono::steady_clock::now()), mLastDraw(mStart) {
  const bool terminal = isatty(STDERR_FILENO) == 1;
  mLines = !terminal && elsewhere == Elsewhere::Lines;
  mEnabled = wanted && total > 0 && (terminal || mLines);
}

ProgressBar::~ProgressBar() {
  if (!mEnabled) return;
  const std::lock_guard lock(mDrawMutex);
  if (mDrawn && !mLines) {
    draw(mDone.load());
    std::fputc('\n', stderr);
  }
}

void ProgressBar::advance(size_t done) {
  if (!mEnabled) return;
  const size_t now = mDone.fetch_add(done) + done;
  std::unique_lock lock(mDrawMutex, std::try_to_lock);  // a busy drawer is enough
  if (!lock.owns_lock()) return;
  const auto time = std::chrono::steady_clock::now();
  if (mLines) {  // the first unit, then every kLineInterval, and the last
    if (mDrawn && time - mLastDraw < kLineInterval && now < mTotal) return;
    mLastDraw = time;
    mDrawn = true;
    const double seconds = std::chrono::duration<double>(time - mStart).count();
    std::fputs(fmt::format("{}: {}/{} ({:.0f}%), {:.0f} s\n", mLabel, now, mTotal, 100.0 * static_cast<double>(now) / static_cast<double>(mTotal),
                           seconds).c_str(), stderr);
    std::fflush(stderr);
    return;
  }
  if (time - mLastDraw < kRedrawInterval && now < mTotal) return;
  mLastDraw = time;
  draw(now);
  mDrawn = true;
}

void ProgressBar::draw(size_t done) {
  const double fraction = static_cast<double>(done) / static_cast<double>(mTotal);
  const int filled = static_cast<int>(fraction * kBarWidthChars);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - mStart).count();
  const std::string bar = std::string(static_cast<size_t>(filled), '#') +
                          std::string(static_cast<size_t>(kBarWidthChars - filled), '.');
  std::fputs(fmt::format("\r{} [{}] {:3.0f}%  {:.1f} s", mLabel, bar, 100.0 * fraction, seconds).c_str(), stderr);
  std::fflush(stderr);
}

}  // namespace penumbra
