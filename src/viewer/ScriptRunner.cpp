// The viewer's scripted mode (ScriptRunner.h): where the script stands, its waits, and the
// dispatch that hands each of Script.h's actions to the part that does it.
#include "viewer/ScriptRunner.h"

#include "gl/Objects.h"

#include <penumbra/Error.h>
#include <penumbra/Technique.h>

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cstdio>

namespace penumbra::viewer {
namespace {

void requireKnown(const ScriptAction& a, const std::vector<std::string>& known, const char* what) {
  if (std::find(known.begin(), known.end(), a.args[0]) == known.end()) {
    std::string list;
    for (const std::string& k : known) list += (list.empty() ? "" : ", ") + k;
    throw usageError(fmt::format("{}: unknown {} '{}' (known: {})", a.where, what, a.args[0], list));
  }
}

}  // namespace

bool ScriptRunner::waiting() {
  if (mWaitFrames > 0) {
    --mWaitFrames;
    return true;
  }
  if (mWaitHeatmap) {
    if (mParts.heatmap.busy()) return true;
    mWaitHeatmap = false;
  }
  if (mWaitReloadFrom) {
    if (mParts.reload.reloads() == *mWaitReloadFrom) {
      if (std::chrono::steady_clock::now() - mWaitReloadSince < kMaxReloadWait) return true;
      const ScriptAction& a = mScript[mIndex - 1];
      throw usageError(fmt::format("{}: wait-reload: nothing was saved and reloaded in {} s{}", a.where, kMaxReloadWait.count(),
                                   mParts.reload.active() ? "" : " (hot reload is off: --no-hot-reload, or no source tree and no technique folder)"));
    }
    mWaitReloadFrom.reset();
  }
  return false;
}

void ScriptRunner::run() {
  if (waiting()) return;
  while (mIndex < mScript.size()) {
    const ScriptAction& a = mScript[mIndex++];
    try {
      if (execute(a)) return;
    } catch (const Error& e) {
      const std::string msg = e.what();
      if (msg.rfind(a.where, 0) == 0) throw;  // already names the script line
      throw Error(fmt::format("{}: {}: {}", a.where, a.verb, msg), e.kind());
    }
  }
  mQuit = true;
}

bool ScriptRunner::execute(const ScriptAction& a) {
  ScriptedViewer& viewer = mParts.viewer;
  const std::string& v = a.verb;
  const std::string arg = a.args.empty() ? "" : a.args[0];
  auto refused = [&] {
    std::printf("refused %s=%s: %s\n", v.c_str(), arg.c_str(), mParts.status.text.c_str());
    std::fflush(stdout);
  };
  if (v == "scene") {
    if (!viewer.selectScene(arg)) throw usageError(mParts.status.text);
  } else if (v == "filter") {
    requireKnown(a, filterIds(), "filter");
    if (!viewer.selectFilter(arg)) refused();
  } else if (v == "projection") {
    requireKnown(a, projectionIds(), "projection");
    if (!viewer.selectProjection(arg)) refused();
  } else if (v == "set") {
    mParts.session.setParam(arg);
  } else if (v == "camera") {
    mParts.camera.runAction(a, mParts.session);
  } else if (v == "light") {
    viewer.executeLight(a);
  } else if (v == "view") {
    viewer.showView(false, arg);
  } else if (v == "inset") {
    viewer.showView(true, arg);
  } else if (v == "flip") {
    viewer.flipReference();
    return true;
  } else if (v == "split") {
    if (arg == "off") {
      viewer.setSplit("", "");
    } else {
      requireKnown(a, filterIds(), "filter");
      const std::string projection = a.args.size() > 1 ? a.args[1] : mParts.session.projectionId();
      const std::vector<std::string> projections = projectionIds();
      if (std::find(projections.begin(), projections.end(), projection) == projections.end())
        throw usageError(fmt::format("{}: unknown projection '{}'", a.where, projection));
      if (!viewer.setSplit(arg, projection)) refused();
    }
  } else if (v == "panel") {
    viewer.openPanel(arg);
    return true;
  } else if (v == "wait") {
    const int n = scriptInt(a, 0, 0, 1 << 30);
    if (n == 0) return false;
    mWaitFrames = n - 1;
    return true;
  } else if (v == "screenshot") {
    viewer.requestScreenshot(ScriptedViewer::Shot::View, arg);
    return true;
  } else if (v == "screenshot-window") {
    viewer.requestScreenshot(ScriptedViewer::Shot::Window, arg);
    return true;
  } else if (v == "screenshot-inset") {
    viewer.requestScreenshot(ScriptedViewer::Shot::Inset, arg);
    return true;
  } else if (v == "print") {
    print(arg);
  } else if (v == "time" || v == "play" || v == "pause") {
    mParts.playback.runAction(a);
  } else if (v == "heatmap") {
    mParts.heatmap.request(a.args.empty() ? std::nullopt : std::optional<int>(scriptInt(a, 0, 1, 1 << 16)));
    return true;
  } else if (v == "wait-heatmap") {
    mWaitHeatmap = true;
    return true;
  } else if (v == "reload") {
    if (!mParts.reload.reloadShaders()) throw usageError(mParts.status.text);
  } else if (v == "wait-reload") {
    mWaitReloadFrom = mParts.reload.reloads();
    mWaitReloadSince = std::chrono::steady_clock::now();
    return true;
  } else if (v == "save") {
    viewer.saveSettings(arg);
  } else if (v == "ui") {
    viewer.showUi(arg == "on");
  } else if (v == "quit") {
    mQuit = true;
    return true;
  }
  return false;
}

void ScriptRunner::print(const std::string& what) const {
  const ViewSession& session = mParts.session;
  if (what == "gl-objects") {
    std::printf("gl-objects %d\n", gl::liveObjectCount());
  } else if (what == "lights") {
    const Scene& scene = session.scene();
    std::string line = fmt::format("lights {} selected {}:", scene.lights.size(), session.selectedLight());
    for (size_t i = 0; i < scene.lights.size(); ++i) line += fmt::format(" {}={}", i, lightTypeName(scene.lights[i].type));
    std::printf("%s\n", line.c_str());
  } else if (what == "layout") {
    std::printf("%s\n", mParts.viewer.layoutText().c_str());
  } else if (what == "time") {
    std::printf("time %.3f of %.3f s %s\n", session.time(), session.duration(), mParts.playback.playing() ? "playing" : "paused");
  } else if (what == "params") {
    const Technique& t = session.technique();
    std::string line = "params";
    for (const Parameterized* values : {&t.projectionValues(), &t.filterValues()})
      for (const ParamDesc& d : values->paramDescs()) line += fmt::format(" {}={}", d.key, formatParamValue(d, values->param(d.key)));
    std::printf("%s\n", line.c_str());
  } else if (what == "technique") {
    std::printf("technique scene=%s projection=%s filter=%s\n", session.scene().name.c_str(), session.projectionId().c_str(),
                session.filterId().c_str());
  } else {
    const PassTimings& t = session.renderer().timings();
    std::string line = "timings";
    for (const auto& [pass, ms] : t.ms) line += fmt::format(" {}={:.3f}", pass, ms);
    std::printf("%s frame=%.3f clock=%s\n", line.c_str(), mParts.viewer.lastFrameMs(), t.clock.c_str());
  }
  std::fflush(stdout);
}

}  // namespace penumbra::viewer
