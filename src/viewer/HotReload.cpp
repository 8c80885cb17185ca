#include "viewer/HotReload.h"

#include "viewer/ViewSession.h"
#include "viewer/Widgets.h"

#include <penumbra/Error.h>
#include <penumbra/Technique.h>

#include <fmt/format.h>
#include <imgui.h>

#include <algorithm>
#include <set>

namespace penumbra::viewer {
namespace {

std::set<std::string> paramKeys(std::string_view filterId) {
  std::set<std::string> keys;
  for (const ParamDesc& d : filterParams(filterId)) keys.emplace(d.key);
  return keys;
}

// "a, b" of the keys in `of` that `without` lacks.
std::string missingFrom(const std::set<std::string>& of, const std::set<std::string>& without) {
  std::vector<std::string> out;
  std::set_difference(of.begin(), of.end(), without.begin(), without.end(), std::back_inserter(out));
  return joinNames(out);
}

}  // namespace

HotReload::HotReload(ShaderLibrary& shaders, const std::optional<std::filesystem::path>& shaderTree, bool watchFolders,
                     StatusLine& status)
    : mStatus(status) {
  if (shaderTree || (watchFolders && !techniqueFolderFiles().empty()))
    mWatcher = std::make_unique<ShaderWatcher>(shaders, shaderTree.value_or(std::filesystem::path()));
}

void HotReload::poll(const std::vector<ViewSession*>& views) {
  if (!mWatcher || !mAutoReload || !mWatcher->poll()) return;
  const std::vector<std::filesystem::path> saved = mWatcher->takeSavedDescriptions();
  if (saved.empty()) {  // GLSL only
    ++mReloads;
    const size_t errors = mWatcher->errors().size();
    mStatus.set(errors == 0 ? "shaders reloaded" : fmt::format("shader reload: {} error(s), last good kept", errors), errors != 0);
    return;
  }
  for (const std::filesystem::path& file : saved) reloadDescription(file, views);
}

bool HotReload::reloadShaders() {
  if (!mWatcher) {
    mStatus.set("no shader source tree: start with --shader-dir DIR to reload shaders", true);
    return false;
  }
  ++mReloads;
  const std::vector<std::string>& errors = mWatcher->reload();
  if (errors.empty()) mStatus.set(fmt::format("shaders reloaded from {}", mWatcher->sourceTree().string()), false);
  else mStatus.set(fmt::format("shader reload: {} error(s), last good programs kept:\n{}", errors.size(), joinNames(errors, "\n")), true);
  return true;
}

void HotReload::reloadDescription(const std::filesystem::path& descriptionFile, const std::vector<ViewSession*>& views) {
  ++mReloads;
  const std::filesystem::path folder = descriptionFile.parent_path();
  std::string filter;  // the id it was loaded under (a reload keeps it)
  for (const std::string& f : filterIds())
    if (techniqueFolder(f) == folder) filter = f;
  if (filter.empty()) return mStatus.set(fmt::format("{}: not a loaded technique folder's description", descriptionFile.string()), true);
  const std::set<std::string> before = paramKeys(filter);
  try {
    reloadTechniqueFolder(folder);
  } catch (const Error& e) {
    return mStatus.set(fmt::format("{} (the last good description keeps running)", e.what()), true);
  }
  std::vector<std::string> refused;
  try {
    for (ViewSession* v : views)
      if (v && v->filterId() == filter)
        for (std::string& key : v->refreshFilter()) refused.push_back(std::move(key));
  } catch (const Error& e) {
    // A view's lights refuse the new description: the previous one comes back, everywhere.
    restorePreviousTechniqueFolder(folder);
    for (ViewSession* v : views)
      if (v && v->filterId() == filter) v->refreshFilter();
    return mStatus.set(fmt::format("{}: {} (the last good description keeps running)", descriptionFile.string(), e.what()), true);
  }
  const std::set<std::string> after = paramKeys(filter);
  std::string message = fmt::format("reloaded {}: {}, {} parameter{}", descriptionFile.string(), filter, after.size(), after.size() == 1 ? "" : "s");
  if (const std::string added = missingFrom(after, before); !added.empty()) message += "; new: " + added;
  if (const std::string gone = missingFrom(before, after); !gone.empty()) message += "; gone: " + gone;
  if (!refused.empty()) message += "; outside the new range, back to the default: " + joinNames(refused);
  mStatus.set(message, false);
}

void HotReload::drawControls() {
  if (!mWatcher) {
    ImGui::TextDisabled("shader hot reload: start with --shader-dir");
    return;
  }
  ImGui::Checkbox("Auto reload", &mAutoReload);
  ImGui::SameLine();
  if (ImGui::Button("Reload shaders (F5)")) reloadShaders();
  if (!mWatcher->sourceTree().empty()) ImGui::TextDisabled("from %s", mWatcher->sourceTree().string().c_str());
  for (const std::filesystem::path& f : techniqueFolderFiles()) ImGui::TextDisabled("and %s", f.string().c_str());
  for (const std::filesystem::path& f : techniqueFolderDescriptions()) ImGui::TextDisabled("and %s", f.string().c_str());
  for (const std::string& e : mWatcher->errors()) {
    ImGui::PushTextWrapPos(0.0f);
    ImGui::TextColored(kErrorColor, "%s", e.c_str());
    ImGui::PopTextWrapPos();
  }
}

}  // namespace penumbra::viewer
