#pragma once
// The viewer's hot reload: what is saved while the viewer runs takes effect on the next frame.
//  - GLSL (the source tree's shaders with --shader-dir, a technique folder's visibility file):
//    every cached program is compiled again (ShaderWatcher); a program that fails keeps its last
//    good version and the errors are listed.
//  - A technique folder's technique.json (docs/own-technique.md): the description is read again
//    and replaces the registry's entry (reloadTechniqueFolder), the views that run it rebuild
//    their technique (the panels' parameters follow: a parameter added, a default or a range
//    changed, a map declared) and redraw. A description that cannot be read, or that the views'
//    lights refuse, is reported in the status line (the file and the field) while the last good
//    one keeps running.
#include "viewer/ShaderWatcher.h"
#include "viewer/StatusLine.h"

#include <filesystem>
#include <memory>
#include <optional>
#include <vector>

namespace penumbra::viewer {

class ViewSession;

class HotReload {
public:
  /// Watches `shaderTree` when given and, when `watchFolders`, the technique folders loaded;
  /// nothing (inactive) when neither.
  HotReload(ShaderLibrary& shaders, const std::optional<std::filesystem::path>& shaderTree, bool watchFolders, StatusLine& status);

  bool active() const { return mWatcher != nullptr; }
  /// Once a frame: reloads what was saved (when auto reload is on). `views` = the sessions whose
  /// techniques follow a reloaded description (the main view, the split view's right half).
  void poll(const std::vector<ViewSession*>& views);
  /// F5, the Tools tab's button, the script's `reload`: every program now. False when inactive.
  bool reloadShaders();
  /// Reads `descriptionFile` (a loaded folder's technique.json) again; see the header comment.
  void reloadDescription(const std::filesystem::path& descriptionFile, const std::vector<ViewSession*>& views);
  /// Reloads done so far (programs and descriptions, failed ones included): what the script's
  /// `wait-reload` waits on.
  int reloads() const { return mReloads; }

  /// The Tools tab's section: auto reload, the reload button, what is watched, the errors.
  void drawControls();

private:
  std::unique_ptr<ShaderWatcher> mWatcher;
  StatusLine& mStatus;
  bool mAutoReload = true;
  int mReloads = 0;
};

}  // namespace penumbra::viewer
