// penumbra view: the interactive viewer (src/viewer), and its scripted mode for tests and demos.
#include "Commands.h"
#include "Common.h"

#include "viewer/Script.h"
#include "viewer/Viewer.h"

#include <penumbra/Error.h>

#include <fmt/format.h>

#include <filesystem>
#include <memory>

namespace penumbra::app {
namespace {
constexpr int kMaxViewerFrames = 1000000000;  // --frames: about 200 days at 60 frames a second
}  // namespace

void addViewCommand(CLI::App& app, std::vector<Command>& commands) {
  struct Options {
    TechniqueOptions technique;
    int frames = 0;
    std::string script, shaderDir;
    bool hideUi = false, noVsync = false, noHotReload = false;
  };
  auto o = std::make_shared<Options>();
  o->technique.size = "1280x720";
  CLI::App* sub = app.add_subcommand("view", "interactive viewer: panels for every parameter, debug views, timings, heatmap");
  addTechniqueOptions(*sub, o->technique);
  sub->add_option("--frames", o->frames, "stop after this many frames (0 = when the window is closed)")->check(CLI::Range(0, kMaxViewerFrames));
  sub->add_option("--script", o->script, "run the actions in this file (listed below; docs/viewer.md), then exit");
  sub->add_option("--shader-dir", o->shaderDir,
                  "source tree to hot-reload shaders from (default: this build's source tree, if present)");
  sub->add_flag("--no-hot-reload", o->noHotReload, "use the shaders built into the binary only, and leave a technique folder's GLSL as it was first read");
  sub->add_flag("--hide-ui", o->hideUi, "start with the panels hidden (F1 or Tab toggles them)");
  sub->add_flag("--no-vsync", o->noVsync, "do not wait for the display's refresh between frames");
  sub->footer("--size is the window size. Keys: F1/Tab panels, C orbit/fly camera, right-drag light, F5 reload shaders,\n"
              "F12 screenshot (Shift: with panels), H error heatmap.\nScript actions (one per line, # comments):\n" +
              viewer::scriptHelp());
  commands.push_back({sub, [o] {
    viewer::ViewerOptions v;
    std::tie(v.width, v.height) = parseSize(o->technique.size);
    v.frames = o->frames;
    if (!o->script.empty()) {
      v.script = viewer::loadScript(o->script);
      v.scripted = true;
    }
    v.showUi = !o->hideUi;
    v.vsync = !o->noVsync && !v.scripted && v.frames == 0;  // scripts and frame counts run flat out
    v.verbose = o->technique.verbose;
    v.reloadTechniqueFolders = !o->noHotReload;
    if (!o->shaderDir.empty()) {
      if (!std::filesystem::is_directory(std::filesystem::path(o->shaderDir) / "shaders"))
        throw usageError(fmt::format("--shader-dir {}: no shaders/ folder there", o->shaderDir));
      v.shaderTree = o->shaderDir;
    } else if (!o->noHotReload && std::filesystem::is_directory(std::filesystem::path(PENUMBRA_SOURCE_DIR) / "shaders")) {
      v.shaderTree = PENUMBRA_SOURCE_DIR;
    }
    Setup s = makeSetup(o->technique);
    viewer::Viewer viewer(std::move(s.scene), s.technique, std::move(v));
    return viewer.run();
  }});
}

}  // namespace penumbra::app
