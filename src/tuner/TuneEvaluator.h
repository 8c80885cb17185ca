#pragma once
// The measuring side of `penumbra tune` (TuneRunner.cpp runs the stages): each configuration on
// every view through runBench, rows remembered in OUT/evaluations.jsonl (resume, merge), the
// views aggregated (worst or mean), the work model, and the progress line on stderr.
#include "tuner/TuneRunner.h"

#include <chrono>
#include <filesystem>
#include <map>
#include <set>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

namespace penumbra::report {

/// One technique searched: its space and the full-size rows measured so far.
struct TuneTechnique {
  std::string projection, filter;
  std::vector<TuneDim> space;
  TuneMapDefault maps;  ///< the default's map side and texels
  /// Parameters that count taps per pixel (unit "taps") and their default values (the work model).
  std::vector<std::pair<std::string, float>> taps;
  std::vector<std::pair<TuneCandidate, TuneRow>> full;  ///< full-size evaluations: candidate and row
  TuneCandidate center;
  bool descending = true;
};

/// A candidate of a technique (an index into the techniques).
struct TuneJob {
  size_t technique = 0;
  TuneCandidate candidate;
};

/// The progress line on stderr: measurements done of the stage's, and the run's time left.
/// Redrawn in place on a terminal; elsewhere (a log, a pipe) at the first measurement and then
/// at most every kLineSeconds.
class TuneProgress {
public:
  explicit TuneProgress(bool wanted);
  ~TuneProgress();
  TuneProgress(const TuneProgress&) = delete;
  TuneProgress& operator=(const TuneProgress&) = delete;

  /// A stage of `total` measurements starts; after it, `laterSeconds` more are expected.
  void stage(std::string name, size_t total, double laterSeconds);
  /// One measurement finished; a measurement now takes `secondsEach`.
  void advance(double secondsEach);
  /// Ends a redrawn line, so that what follows starts on its own.
  void finish();

  static constexpr double kRedrawSeconds = 0.25;  ///< a terminal: smooth enough, no flicker
  static constexpr double kLineSeconds = 15.0;    ///< a log: a few lines a minute

private:
  bool mWanted, mTerminal, mPrinted = false, mOpen = false;
  std::string mName;
  size_t mTotal = 0, mDone = 0;
  double mLaterSeconds = 0.0;
  std::chrono::steady_clock::time_point mLast;
};

/// One row for a configuration measured on several views: each metric, error and cost the
/// worst (highest) or the mean of the views'; memory the largest; the first view's command.
TuneRow aggregateTuneRows(TuneAggregate a, std::vector<TuneRow> views);

/// Measures jobs through runBench on every view, remembering every view's row (in memory and in
/// OUT/evaluations.jsonl) so that a configuration is never measured twice, not even across runs.
class TuneEvaluator {
public:
  TuneEvaluator(gl::Context& context, const TuneRequest& request, const TuneSetupFactory& makeSetup,
                const std::vector<TuneTechnique>& techniques, TuneProgress& progress);

  size_t measured() const { return mMeasured; }
  size_t resumed() const { return mResumed; }
  const std::string& clock() const { return mClock; }

  /// Seconds one view of one job takes at this image size: measured so far, else guessed.
  double secondsPerJob(int width, int height) const;
  /// Measurements (job × view) not in the memo.
  size_t unmeasured(const std::vector<TuneJob>& jobs, int width, int height, int frames) const;
  /// One row per job (aggregated over the views), nothing where a view failed or was refused
  /// (reported on stderr).
  std::vector<std::optional<TuneRow>> run(const std::vector<TuneJob>& jobs, int width, int height, int frames);

  /// Times the jobs in interleaved rounds on every view (timeInterleaved): [view][job][round],
  /// each round's whole cost. Each job is in a renderer of its own for the rounds.
  std::vector<std::vector<std::vector<double>>> timeRounds(const std::vector<TuneJob>& jobs, int width, int height, int rounds);

  /// Before any full-size configuration is measured, one is guessed to take this many times a
  /// screen-stage one (fixed costs, shader compiles and the reference load do not scale with pixels).
  static constexpr double kFullOverScreenGuess = 4.0;

private:
  void measure(const std::vector<TuneJob>& jobs, const std::vector<size_t>& indices, size_t viewIndex, int width,
               int height, int frames);
  TuneMaps mapsOf(const TuneJob& j) const;
  double work(const TuneJob& j, const TuneRow& r) const;
  BenchConfig config(const TuneJob& j, const TuneView& v) const;
  std::string key(const TuneJob& j, const TuneView& v, int width, int height, int frames) const;
  TuneRow tuneRow(const BenchResults& results, const BenchRow& b) const;
  void remember(const std::string& k, const TuneRow& r);

  gl::Context& mContext;
  const TuneRequest& mRequest;
  const TuneSetupFactory& mMakeSetup;
  const std::vector<TuneTechnique>& mTechniques;
  TuneProgress& mProgress;
  std::filesystem::path mLogPath;
  std::string mClock;
  std::map<std::string, TuneRow> mMemo;
  std::set<std::string> mLoaded;  // keys read from an earlier run and not used yet
  size_t mMeasured = 0, mResumed = 0;
  std::map<std::pair<int, int>, std::pair<double, size_t>> mSeconds;  // by image size: seconds, measurements
};

}  // namespace penumbra::report
