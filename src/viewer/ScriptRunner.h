#pragma once
// The viewer's script runner: where a script (Script.h) stands from frame to frame. At the start
// of each frame it hands actions, in order, to the viewer's dispatch until one lets the frame be
// drawn, and holds the waits (`wait N`, `wait-heatmap`, `wait-reload`) between them. A failure
// is rethrown naming the script line.
#include "viewer/HeatmapView.h"
#include "viewer/HotReload.h"
#include "viewer/Script.h"

#include <chrono>
#include <functional>
#include <optional>
#include <vector>

namespace penumbra::viewer {

class ScriptRunner {
public:
  /// `script` outlives the runner (the viewer's options hold it).
  ScriptRunner(const std::vector<ScriptAction>& script, const HeatmapView& heatmap, const HotReload& reload)
      : mScript(script), mHeatmap(heatmap), mReload(reload) {}

  /// One frame's actions: `execute` returns true to let the frame be drawn before the next.
  void run(const std::function<bool(const ScriptAction&)>& execute);
  /// After the last action, or `quit`.
  bool finished() const { return mQuit; }
  void quit() { mQuit = true; }
  /// The waits the actions ask for: `frames` more frames; until the heatmap is done; until the
  /// next reload (at most kMaxReloadWait).
  void waitFrames(int frames) { mWaitFrames = frames; }
  void waitHeatmap() { mWaitHeatmap = true; }
  void waitReload();

  /// `wait-reload` gives up after this long: a file that was never saved.
  static constexpr std::chrono::seconds kMaxReloadWait{60};

private:
  /// True while a wait holds the script at this frame.
  bool waiting();

  const std::vector<ScriptAction>& mScript;
  const HeatmapView& mHeatmap;
  const HotReload& mReload;
  size_t mIndex = 0;
  int mWaitFrames = 0;
  bool mWaitHeatmap = false;
  std::optional<int> mWaitReloadFrom;  ///< HotReload::reloads() when `wait-reload` started
  std::chrono::steady_clock::time_point mWaitReloadSince;
  bool mQuit = false;
};

}  // namespace penumbra::viewer
