#include "viewer/ShaderWatcher.h"

#include <penumbra/Technique.h>

#include <system_error>

namespace penumbra::viewer {

ShaderWatcher::ShaderWatcher(ShaderLibrary& shaders, std::filesystem::path sourceTree)
    : mShaders(shaders), mTree(std::move(sourceTree)) {
  if (!mTree.empty()) mShaders.setSourceTree(mTree);
  mTimes = snapshot();
  mLastPoll = std::chrono::steady_clock::now();
}

std::map<std::filesystem::path, std::filesystem::file_time_type> ShaderWatcher::snapshot() const {
  std::map<std::filesystem::path, std::filesystem::file_time_type> times;
  for (const std::filesystem::path& p : techniqueFolderFiles()) {
    std::error_code ec;
    const auto t = std::filesystem::last_write_time(p, ec);
    if (!ec) times[p] = t;
  }
  if (!mTree.empty())
    for (const std::string& key : mShaders.keys())
    for (const char* top : {"shaders", "src"}) {
      const std::filesystem::path p = mTree / top / key;
      std::error_code ec;
      const auto t = std::filesystem::last_write_time(p, ec);
      if (!ec) times[p] = t;
    }
  return times;
}

bool ShaderWatcher::poll() {
  const auto now = std::chrono::steady_clock::now();
  if (now - mLastPoll < kPollInterval) return false;
  mLastPoll = now;
  auto times = snapshot();
  if (times == mTimes) return false;
  mTimes = std::move(times);
  reload();
  return true;
}

const std::vector<std::string>& ShaderWatcher::reload() {
  mErrors = mShaders.reloadAll();
  ++mReloads;
  return mErrors;
}

}  // namespace penumbra::viewer
