#pragma once
// The viewer's script runner: where a script (Script.h) stands from frame to frame, and the
// dispatch of its actions. At the start of each frame it runs actions, in order, until one lets
// the frame be drawn, and holds the waits (`wait N`, `wait-heatmap`, `wait-reload`) between them.
// Each action goes to the part that does it: the session (parameters, what `print` reports), the
// camera rig, playback, the heatmap, hot reload, or the viewer itself (ScriptedViewer: scenes,
// techniques, views, panels, lights, screenshots). A failure is rethrown naming the script line.
#include "viewer/CameraRig.h"
#include "viewer/HeatmapView.h"
#include "viewer/HotReload.h"
#include "viewer/Playback.h"
#include "viewer/Script.h"
#include "viewer/StatusLine.h"
#include "viewer/ViewSession.h"

#include <chrono>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace penumbra::viewer {

/// What a script asks of the viewer itself. The actions report problems in the status line and
/// return false (a refused technique), or throw for unknown names.
class ScriptedViewer {
public:
  virtual bool selectScene(const std::string& nameOrPath) = 0;
  virtual bool selectFilter(const std::string& id) = 0;
  virtual bool selectProjection(const std::string& id) = 0;
  /// The main view's or the inset's image (`view NAME`, `inset NAME|none`).
  virtual void showView(bool inset, const std::string& name) = 0;
  virtual void flipReference() = 0;
  /// The split view's right half ("" = off).
  virtual bool setSplit(const std::string& filter, const std::string& projection) = 0;
  /// Opens the tab of that script name on the next frame (an unknown one opens none).
  virtual void openPanel(const std::string& id) = 0;
  enum class Shot { View, Window, Inset };
  /// Takes that screenshot after this frame.
  virtual void requestScreenshot(Shot shot, const std::filesystem::path& path) = 0;
  virtual void executeLight(const ScriptAction& a) = 0;
  virtual void saveSettings(const std::filesystem::path& path) = 0;
  virtual void showUi(bool show) = 0;
  /// `print layout`.
  virtual std::string layoutText() const = 0;
  /// The last frame's wall time (`print timings`).
  virtual double lastFrameMs() const = 0;

protected:
  ~ScriptedViewer() = default;
};

class ScriptRunner {
public:
  /// `script` outlives the runner (the viewer's options hold it), as do the parts.
  struct Parts {
    ScriptedViewer& viewer;
    ViewSession& session;
    CameraRig& camera;
    Playback& playback;
    HeatmapView& heatmap;
    HotReload& reload;
    const StatusLine& status;
  };
  ScriptRunner(const std::vector<ScriptAction>& script, const Parts& parts) : mScript(script), mParts(parts) {}

  /// This frame's actions.
  void run();
  /// After the last action, or `quit`.
  bool finished() const { return mQuit; }

  /// `wait-reload` gives up after this long: a file that was never saved.
  static constexpr std::chrono::seconds kMaxReloadWait{60};

private:
  /// True while a wait holds the script at this frame.
  bool waiting();
  /// Hands one action to the part that does it; true = let this frame be drawn before the next.
  bool execute(const ScriptAction& a);
  /// `print WHAT`: one line on stdout.
  void print(const std::string& what) const;

  const std::vector<ScriptAction>& mScript;
  Parts mParts;
  size_t mIndex = 0;
  int mWaitFrames = 0;
  bool mWaitHeatmap = false;
  std::optional<int> mWaitReloadFrom;  ///< HotReload::reloads() when `wait-reload` started
  std::chrono::steady_clock::time_point mWaitReloadSince;
  bool mQuit = false;
};

}  // namespace penumbra::viewer
