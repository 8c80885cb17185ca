// The viewer's scripted mode: the runner (ScriptRunner.h), and the dispatch that hands each of
// Script.h's actions to the part that does it.
#include "viewer/ScriptRunner.h"
#include "viewer/Viewer.h"

#include "viewer/LightEdit.h"

#include <penumbra/Error.h>
#include "techniques/Registry.h"

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

void ScriptRunner::waitReload() {
  mWaitReloadFrom = mReload.reloads();
  mWaitReloadSince = std::chrono::steady_clock::now();
}

bool ScriptRunner::waiting() {
  if (mWaitFrames > 0) {
    --mWaitFrames;
    return true;
  }
  if (mWaitHeatmap) {
    if (mHeatmap.busy()) return true;
    mWaitHeatmap = false;
  }
  if (mWaitReloadFrom) {
    if (mReload.reloads() == *mWaitReloadFrom) {
      if (std::chrono::steady_clock::now() - mWaitReloadSince < kMaxReloadWait) return true;
      const ScriptAction& a = mScript[mIndex - 1];
      throw usageError(fmt::format("{}: wait-reload: nothing was saved and reloaded in {} s{}", a.where, kMaxReloadWait.count(),
                                   mReload.active() ? "" : " (hot reload is off: --no-hot-reload, or no source tree and no technique folder)"));
    }
    mWaitReloadFrom.reset();
  }
  return false;
}

void ScriptRunner::run(const std::function<bool(const ScriptAction&)>& execute) {
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

bool Viewer::execute(const ScriptAction& a) {
  const std::string& v = a.verb;
  const std::string arg = a.args.empty() ? "" : a.args[0];
  auto refused = [&] {
    std::printf("refused %s=%s: %s\n", v.c_str(), arg.c_str(), mStatus.text.c_str());
    std::fflush(stdout);
  };
  if (v == "scene") {
    if (!selectScene(arg)) throw usageError(mStatus.text);
  } else if (v == "filter") {
    requireKnown(a, filterIds(), "filter");
    if (!selectFilter(arg)) refused();
  } else if (v == "projection") {
    requireKnown(a, projectionIds(), "projection");
    if (!selectProjection(arg)) refused();
  } else if (v == "set") {
    mSession.setParam(arg);
  } else if (v == "camera") {
    mCamera.runAction(a, mSession);
  } else if (v == "light") {
    executeLight(a);
  } else if (v == "view") {
    setView(mMain, arg, "main view");
  } else if (v == "inset") {
    setView(mInset, arg, "inset");
  } else if (v == "flip") {
    flipReference();
    return true;
  } else if (v == "split") {
    if (arg == "off") {
      setSplit("", "");
    } else {
      requireKnown(a, filterIds(), "filter");
      const std::string projection = a.args.size() > 1 ? a.args[1] : mSession.projectionId();
      const std::vector<std::string> projections = projectionIds();
      if (std::find(projections.begin(), projections.end(), projection) == projections.end())
        throw usageError(fmt::format("{}: unknown projection '{}'", a.where, projection));
      if (!setSplit(arg, projection)) refused();
    }
  } else if (v == "panel") {
    for (const PanelInfo& p : kPanels)
      if (arg == p.id) mSelectPanel = p.panel;
    return true;
  } else if (v == "wait") {
    const int n = scriptInt(a, 0, 0, 1 << 30);
    if (n == 0) return false;
    mScript.waitFrames(n - 1);
    return true;
  } else if (v == "screenshot") {
    mViewShot = arg;
    return true;
  } else if (v == "screenshot-window") {
    mWindowShot = arg;
    return true;
  } else if (v == "screenshot-inset") {
    if (mInset.name == kNoInset) throw usageError("no inset is shown (inset NAME first)");
    mInsetShot = arg;
    return true;
  } else if (v == "print") {
    if (arg == "gl-objects") {
      std::printf("gl-objects %d\n", gl::liveObjectCount());
    } else if (arg == "lights") {
      const Scene& scene = mSession.scene();
      std::string line = fmt::format("lights {} selected {}:", scene.lights.size(), mSession.selectedLight());
      for (size_t i = 0; i < scene.lights.size(); ++i) line += fmt::format(" {}={}", i, lightTypeName(scene.lights[i].type));
      std::printf("%s\n", line.c_str());
    } else if (arg == "layout") {
      std::printf("%s\n", layoutText().c_str());
    } else if (arg == "time") {
      std::printf("time %.3f of %.3f s %s\n", mSession.time(), mSession.duration(), mPlayback.playing() ? "playing" : "paused");
    } else if (arg == "params") {
      const Technique& t = mSession.technique();
      std::string line = "params";
      for (const Parameterized* values : {&t.projectionValues(), &t.filterValues()})
        for (const ParamDesc& d : values->paramDescs()) line += fmt::format(" {}={}", d.key, formatParamValue(d, values->param(d.key)));
      std::printf("%s\n", line.c_str());
    } else if (arg == "technique") {
      std::printf("technique scene=%s projection=%s filter=%s\n", mSession.scene().name.c_str(), mSession.projectionId().c_str(),
                  mSession.filterId().c_str());
    } else {
      const PassTimings& t = mSession.renderer().timings();
      std::string line = "timings";
      for (const auto& [pass, ms] : t.ms) line += fmt::format(" {}={:.3f}", pass, ms);
      std::printf("%s frame=%.3f clock=%s\n", line.c_str(), mLastFrameMs, t.clock.c_str());
    }
    std::fflush(stdout);
  } else if (v == "time" || v == "play" || v == "pause") {
    mPlayback.runAction(a);
  } else if (v == "heatmap") {
    mHeatmap.request(a.args.empty() ? std::nullopt : std::optional<int>(scriptInt(a, 0, 1, 1 << 16)));
    return true;
  } else if (v == "wait-heatmap") {
    mScript.waitHeatmap();
    return true;
  } else if (v == "reload") {
    if (!mHotReload.reloadShaders()) throw usageError(mStatus.text);
  } else if (v == "wait-reload") {
    mScript.waitReload();
    return true;
  } else if (v == "save") {
    saveSettings(arg);
  } else if (v == "ui") {
    mOptions.showUi = arg == "on";
  } else if (v == "quit") {
    mScript.quit();
    return true;
  }
  return false;
}

}  // namespace penumbra::viewer
