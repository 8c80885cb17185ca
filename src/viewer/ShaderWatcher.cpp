#include "viewer/ShaderWatcher.h"

#include <penumbra/Technique.h>

#include <system_error>

namespace penumbra::viewer {

ShaderWatcher::ShaderWatcher(ShaderLibrary& shaders, std::filesystem::path sourceTree)
    : mShaders(shaders), mTree(std::move(sourceTree)) {
  if (!mTree.empty()) mShaders.setSourceTree(mTree);
  mTimes = snapshot();
  mDescriptionTimes = descriptionTimes();
  mLastPoll = std::chrono::steady_clock::now();
}

namespace {

void addTime(std::map<std::filesystem::path, std::filesystem::file_time_type>& times, const std::filesystem::path& p) {
  std::error_code ec;
  const auto t = std::filesystem::last_write_time(p, ec);
  if (!ec) times[p] = t;
}

}  // namespace

ShaderWatcher::Times ShaderWatcher::descriptionTimes() {
  Times times;
  for (const std::filesystem::path& p : techniqueFolderDescriptions()) addTime(times, p);
  return times;
}

ShaderWatcher::Times ShaderWatcher::snapshot() const {
  Times times;
  for (const std::filesystem::path& p : techniqueFolderFiles()) addTime(times, p);
  if (!mTree.empty())
    for (const std::string& key : mShaders.keys())
      for (const char* top : {"shaders", "src"}) addTime(times, mTree / top / key);
  return times;
}

bool ShaderWatcher::poll() {
  const auto now = std::chrono::steady_clock::now();
  if (now - mLastPoll < kPollInterval) return false;
  mLastPoll = now;
  Times descriptions = descriptionTimes();
  bool saved = false;
  for (const auto& [file, time] : descriptions)
    if (const auto it = mDescriptionTimes.find(file); it == mDescriptionTimes.end() || it->second != time) {
      mSavedDescriptions.push_back(file);
      saved = true;
    }
  mDescriptionTimes = std::move(descriptions);
  Times times = snapshot();
  if (times == mTimes) return saved;
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
