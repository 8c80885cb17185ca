#pragma once
// Shader hot reload: watches the source tree's copies of the embedded shader files (the
// ShaderLibrary reads the tree first once setSourceTree() is called) and the GLSL of every
// technique folder loaded (docs/own-technique.md), and recompiles every cached program when one
// changes. A program that fails keeps its last good version; the
// errors are kept for the viewer to show.
#include "shader/ShaderLibrary.h"

#include <chrono>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace penumbra::viewer {

class ShaderWatcher {
public:
  /// Points `shaders` at `sourceTree` (the folder holding shaders/ and src/); an empty path
  /// watches the technique folders only.
  ShaderWatcher(ShaderLibrary& shaders, std::filesystem::path sourceTree);
  const std::filesystem::path& sourceTree() const { return mTree; }

  /// Checks modification times at most every kPollInterval; reloads when any changed.
  /// Returns true when a reload happened.
  bool poll();
  /// Reloads now. Returns the error messages (empty = every program compiled).
  const std::vector<std::string>& reload();
  const std::vector<std::string>& errors() const { return mErrors; }
  int reloads() const { return mReloads; }

  static constexpr std::chrono::milliseconds kPollInterval{500};

private:
  std::map<std::filesystem::path, std::filesystem::file_time_type> snapshot() const;

  ShaderLibrary& mShaders;
  std::filesystem::path mTree;
  std::map<std::filesystem::path, std::filesystem::file_time_type> mTimes;
  std::chrono::steady_clock::time_point mLastPoll;
  std::vector<std::string> mErrors;
  int mReloads = 0;
};

}  // namespace penumbra::viewer
