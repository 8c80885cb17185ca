#pragma once
// Shader hot reload: watches the source tree's copies of the embedded shader files (the
// ShaderLibrary reads the tree first once setSourceTree() is called) and the GLSL of every
// technique folder loaded (docs/own-technique.md), and recompiles every cached program when one
// changes. A program that fails keeps its last good version; the errors are kept for the viewer
// to show. It also watches every folder's technique.json and lists those saved since the last
// poll (the viewer's HotReload reads them again: a description is no program).
#include "shader/ShaderLibrary.h"

#include <chrono>
#include <filesystem>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace penumbra::viewer {

class ShaderWatcher {
public:
  /// Points `shaders` at `sourceTree` (the folder holding shaders/ and src/); an empty path
  /// watches the technique folders only.
  ShaderWatcher(ShaderLibrary& shaders, std::filesystem::path sourceTree);
  const std::filesystem::path& sourceTree() const { return mTree; }

  /// Checks modification times at most every kPollInterval; reloads the programs when a GLSL
  /// file changed. Returns true when a program reload happened or a description was saved.
  bool poll();
  /// The technique.json files saved since the last call (each once).
  std::vector<std::filesystem::path> takeSavedDescriptions() { return std::exchange(mSavedDescriptions, {}); }
  /// Reloads now. Returns the error messages (empty = every program compiled).
  const std::vector<std::string>& reload();
  const std::vector<std::string>& errors() const { return mErrors; }
  int reloads() const { return mReloads; }

  static constexpr std::chrono::milliseconds kPollInterval{500};

private:
  using Times = std::map<std::filesystem::path, std::filesystem::file_time_type>;
  Times snapshot() const;
  static Times descriptionTimes();

  ShaderLibrary& mShaders;
  std::filesystem::path mTree;
  Times mTimes, mDescriptionTimes;
  std::vector<std::filesystem::path> mSavedDescriptions;
  std::chrono::steady_clock::time_point mLastPoll;
  std::vector<std::string> mErrors;
  int mReloads = 0;
};

}  // namespace penumbra::viewer
