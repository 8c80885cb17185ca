// Every technique by id. Adding one = one line here + its own files.
#include "techniques/Registry.h"

#include "techniques/filters/EsmFilter.h"
#include "techniques/filters/EvsmFilter.h"
#include "techniques/filters/EvsmSoftFilter.h"
#include "techniques/filters/HardFilter.h"
#include "techniques/filters/PcfFilter.h"
#include "techniques/filters/PcssFilter.h"
#include "techniques/filters/SecondDepthFilter.h"
#include "techniques/filters/SmrtFilter.h"
#include "techniques/filters/MsmFilter.h"
#include "techniques/filters/MsmSoftFilter.h"
#include "techniques/filters/VsmFilter.h"
#include "techniques/filters/VssmFilter.h"
#include "techniques/contact/ContactShadows.h"
#include "techniques/projections/CascadedProjection.h"
#include "techniques/projections/LightSpacePerspectiveProjection.h"
#include "techniques/projections/PerspectiveProjection.h"
#include "techniques/projections/SampleDistributionProjection.h"
#include "techniques/projections/TrapezoidalProjection.h"
#include "techniques/projections/UniformProjection.h"
#include "techniques/projections/VirtualProjection.h"
#include "techniques/folder/FolderTechnique.h"
#include "techniques/sdf/SdfFilter.h"
#include "techniques/temporal/TemporalAccumulation.h"
#include "techniques/translucent/TranslucentShadows.h"

#include <penumbra/Error.h>

#include <fmt/format.h>

#include <algorithm>
#include <functional>
#include <map>
#include <mutex>
#include <utility>

namespace penumbra {
namespace {

template <class T>
struct Entry {
  std::string id;
  std::function<std::unique_ptr<T>()> make;
  uint64_t revision = 0;  ///< counts the times `make` was replaced (a technique folder reloaded)
};

template <class T>
struct Kinds {
  std::vector<Entry<T>> entries;
  /// One instance per id, made on first use and kept: what ids, descriptions, parameter tables
  /// and incompatibilities are read from (no GL object is made until an instance's first frame).
  std::map<std::string, std::unique_ptr<T>, std::less<>> prototypes;
};

// Registration (registerFilter) and the prototypes are shared by threads that make techniques
// (tune's shards): one lock over both, recursive because a filter's constructor may read the
// registry (a filter that wraps another takes that one's parameter table).
std::recursive_mutex& registryMutex() {
  static std::recursive_mutex m;
  return m;
}

Kinds<Projection>& projections() {
  static Kinds<Projection> kinds{{
      {"uniform", [] { return std::make_unique<UniformProjection>(); }},
      {"csm", [] { return std::make_unique<CascadedProjection>(); }},
      {"psm", [] { return std::make_unique<PerspectiveProjection>(); }},
      {"tsm", [] { return std::make_unique<TrapezoidalProjection>(); }},
      {"lispsm", [] { return std::make_unique<LightSpacePerspectiveProjection>(); }},
      {"sdsm", [] { return std::make_unique<SampleDistributionProjection>(); }},
      {"virtual", [] { return std::make_unique<VirtualProjection>(); }},
  }, {}};
  return kinds;
}

Kinds<Filter>& filters() {
  static Kinds<Filter> kinds{{
      {"hard", [] { return std::make_unique<HardFilter>(); }},
      {"pcf", [] { return std::make_unique<PcfFilter>(); }},
      {"pcss", [] { return std::make_unique<PcssFilter>(); }},
      {"smrt", [] { return std::make_unique<SmrtFilter>(); }},
      {"second-depth", [] { return std::make_unique<SecondDepthFilter>(); }},
      {"sdf", [] { return std::make_unique<SdfFilter>(); }},
      {"vsm", [] { return std::make_unique<VsmFilter>(); }},
      {"vssm", [] { return std::make_unique<VssmFilter>(); }},
      {"msm", [] { return std::make_unique<MsmFilter>(); }},
      {"msm-soft", [] { return std::make_unique<MsmSoftFilter>(); }},
      {"esm", [] { return std::make_unique<EsmFilter>(); }},
      {"evsm", [] { return std::make_unique<EvsmFilter>(); }},
      {"evsm-soft", [] { return std::make_unique<EvsmSoftFilter>(); }},
  }, {}};
  return kinds;
}

template <class T>
std::vector<std::string> ids(const Kinds<T>& kinds) {
  const std::lock_guard lock(registryMutex());
  std::vector<std::string> out;
  for (const Entry<T>& e : kinds.entries) out.push_back(e.id);
  return out;
}

template <class T>
const Entry<T>& entry(const Kinds<T>& kinds, std::string_view id, const char* what) {
  for (const Entry<T>& e : kinds.entries)
    if (e.id == id) return e;
  std::vector<std::string> known;
  for (const Entry<T>& e : kinds.entries) known.push_back(e.id);
  throw usageError(fmt::format("unknown {} '{}' (known: {})", what, id, joinNames(known)));
}

template <class T>
std::unique_ptr<T> make(const Kinds<T>& kinds, std::string_view id, const char* what) {
  std::function<std::unique_ptr<T>()> maker;
  {
    const std::lock_guard lock(registryMutex());
    maker = entry(kinds, id, what).make;
  }
  return maker();
}

template <class T>
const T& prototype(Kinds<T>& kinds, std::string_view id, const char* what) {
  const std::lock_guard lock(registryMutex());
  auto it = kinds.prototypes.find(id);
  if (it == kinds.prototypes.end()) it = kinds.prototypes.emplace(std::string(id), entry(kinds, id, what).make()).first;
  return *it->second;
}

}  // namespace

std::vector<std::string> projectionIds() { return ids(projections()); }
std::vector<std::string> filterIds() { return ids(filters()); }
std::string_view projectionDescription(std::string_view id) { return prototype(projections(), id, "projection").description(); }
std::string_view filterDescription(std::string_view id) { return prototype(filters(), id, "filter").description(); }
std::string_view filterTranslucentCasters(std::string_view id) { return prototype(filters(), id, "filter").translucentCasters(); }
std::span<const ParamDesc> projectionParams(std::string_view id) { return prototype(projections(), id, "projection").paramDescs(); }
std::span<const ParamDesc> filterParams(std::string_view id) { return prototype(filters(), id, "filter").params(); }

std::string projectionIncompatibility(std::string_view projection, const Light& light) {
  return prototype(projections(), projection, "projection").incompatibility(light);
}
bool filterShadowsThroughTranslucent(std::string_view filter, const Parameterized& values) {
  return prototype(filters(), filter, "filter").shadowsThroughTranslucent(values);
}
std::string filterIncompatibility(std::string_view filter, std::string_view projection, const Light& light) {
  const Filter& f = prototype(filters(), filter, "filter");
  if (prototype(projections(), projection, "projection").pageLayout() && !f.readsPagedMaps())
    return "its maps are paged (only the pages pixels need, in a pool, read through a page table); this filter builds mip "
           "chains, summed-area tables, moments or fields over whole maps, which pages do not make (hard, pcf, pcss and smrt "
           "read paged maps)";
  return f.incompatibility(projection, light);
}

std::unique_ptr<Projection> makeProjection(std::string_view id) { return make(projections(), id, "projection"); }

std::unique_ptr<Projection> makeProjection(const Technique& technique) {
  std::unique_ptr<Projection> p = makeProjection(technique.projection());
  static_cast<Parameterized&>(*p) = technique.projectionValues();
  return p;
}

std::unique_ptr<Filter> makeFilter(std::string_view id) { return make(filters(), id, "filter"); }

void registerFilter(const std::function<std::unique_ptr<Filter>()>& make) {
  const std::string id(make()->id());
  const std::lock_guard lock(registryMutex());
  Kinds<Filter>& kinds = filters();
  for (const Entry<Filter>& e : kinds.entries)
    if (e.id == id) throw usageError(fmt::format("registerFilter: a filter '{}' is registered already", id));
  for (const Entry<Projection>& e : projections().entries)
    if (e.id == id) throw usageError(fmt::format("registerFilter: '{}' is a projection's id", id));
  kinds.entries.push_back({id, make, 0});
}

uint64_t filterRevision(std::string_view id) {
  const std::lock_guard lock(registryMutex());
  return entry(filters(), id, "filter").revision;
}

namespace {

/// Every technique folder loaded, kept for the life of the process: the registry's entries, the
/// techniques' ParamDesc tables and the lights' instances point into them.
std::vector<std::unique_ptr<FolderDescription>>& folders() {
  static std::vector<std::unique_ptr<FolderDescription>> loaded;
  return loaded;
}

/// Descriptions a reload replaced, newest last, with the prototypes made from them: techniques
/// and lights made before the reload still point into them, so they are never freed.
struct Retired {
  std::unique_ptr<FolderDescription> description;
  std::unique_ptr<Filter> prototype;
};
std::vector<Retired>& retired() {
  static std::vector<Retired> kept;
  return kept;
}

/// Puts `next` in the place of the loaded description `slot` of the same id: the registry's
/// entry makes filters of `next` from now on (its revision counts up, so lights remake theirs)
/// and the prototype is made again. The previous one is retired.
void replaceFolder(std::unique_ptr<FolderDescription>& slot, std::unique_ptr<FolderDescription> next) {
  Kinds<Filter>& kinds = filters();
  std::unique_ptr<Filter> prototype;
  if (auto it = kinds.prototypes.find(slot->id); it != kinds.prototypes.end()) {
    prototype = std::move(it->second);
    kinds.prototypes.erase(it);
  }
  retired().push_back({std::exchange(slot, std::move(next)), std::move(prototype)});
  const FolderDescription& kept = *slot;
  for (Entry<Filter>& e : kinds.entries)
    if (e.id == kept.id) {
      e.make = [&kept] { return makeFolderFilter(kept); };
      ++e.revision;
    }
}

std::unique_ptr<FolderDescription>& loadedFolder(const std::filesystem::path& folder) {
  const std::filesystem::path canonical = std::filesystem::weakly_canonical(std::filesystem::absolute(folder));
  for (std::unique_ptr<FolderDescription>& f : folders())
    if (f->folder == canonical) return f;
  throw usageError(fmt::format("technique folder {}: not loaded", folder.string()));
}

}  // namespace

std::string loadTechniqueFolder(const std::filesystem::path& folder) {
  std::unique_ptr<FolderDescription> d = readFolderDescription(folder);
  const std::lock_guard lock(registryMutex());
  for (const std::unique_ptr<FolderDescription>& f : folders()) {
    if (f->folder == d->folder) return f->id;
    if (f->id == d->id)
      throw usageError(fmt::format("{}: id: '{}' is the id of the technique folder {} too", (folder / "technique.json").string(), d->id,
                                   f->folder.string()));
  }
  for (const Entry<Filter>& e : filters().entries)
    if (e.id == d->id) throw usageError(fmt::format("{}: id: '{}' is a built-in filter's id", (folder / "technique.json").string(), d->id));
  for (const Entry<Projection>& e : projections().entries)
    if (e.id == d->id) throw usageError(fmt::format("{}: id: '{}' is a projection's id", (folder / "technique.json").string(), d->id));
  const FolderDescription& kept = *folders().emplace_back(std::move(d));
  registerFilter([&kept] { return makeFolderFilter(kept); });
  return kept.id;
}

std::string reloadTechniqueFolder(const std::filesystem::path& folder) {
  std::unique_ptr<FolderDescription> d = readFolderDescription(folder);
  const std::lock_guard lock(registryMutex());
  std::unique_ptr<FolderDescription>& slot = loadedFolder(folder);
  if (d->id != slot->id)
    throw usageError(fmt::format("{}: id: '{}' differs from '{}', the id it was loaded under; a folder keeps its id while it is "
                                 "loaded (start again to rename it)",
                                 d->descriptionFile.string(), d->id, slot->id));
  replaceFolder(slot, std::move(d));
  return slot->id;
}

void restorePreviousTechniqueFolder(const std::filesystem::path& folder) {
  const std::lock_guard lock(registryMutex());
  std::unique_ptr<FolderDescription>& slot = loadedFolder(folder);
  std::vector<Retired>& old = retired();
  const auto previous = std::find_if(old.rbegin(), old.rend(), [&](const Retired& r) { return r.description && r.description->folder == slot->folder; });
  if (previous == old.rend()) throw usageError(fmt::format("technique folder {}: no earlier description to restore", folder.string()));
  // The restored description moves back into the registry; the one it replaces is retired in its place.
  replaceFolder(slot, std::move(previous->description));
}

std::filesystem::path techniqueFolder(std::string_view filterId) {
  const std::lock_guard lock(registryMutex());
  for (const std::unique_ptr<FolderDescription>& f : folders())
    if (f->id == filterId) return f->folder;
  return {};
}

std::string filterArgument(std::string_view filterId) {
  const std::filesystem::path folder = techniqueFolder(filterId);
  return folder.empty() ? std::string(filterId) : folder.string();
}

std::vector<std::filesystem::path> techniqueFolderFiles() {
  const std::lock_guard lock(registryMutex());
  std::vector<std::filesystem::path> out;
  for (const std::unique_ptr<FolderDescription>& f : folders()) out.push_back(f->visibilityFile);
  return out;
}

std::vector<std::filesystem::path> techniqueFolderDescriptions() {
  const std::lock_guard lock(registryMutex());
  std::vector<std::filesystem::path> out;
  for (const std::unique_ptr<FolderDescription>& f : folders()) out.push_back(f->descriptionFile);
  return out;
}

std::string resolveFilter(std::string_view text) {
  {
    const std::lock_guard lock(registryMutex());
    for (const Entry<Filter>& e : filters().entries)
      if (e.id == text) return e.id;
  }
  std::error_code ec;
  const std::filesystem::path path(text);
  if (text.find('/') != std::string_view::npos || std::filesystem::is_directory(path, ec)) return loadTechniqueFolder(path);
  return std::string(text);
}

std::span<const AddOnGroup> addOnGroups() {
  static const AddOnGroup groups[] = {{"Contact shadows", ContactShadows::params()},
                                      {"Temporal accumulation", TemporalAccumulation::params()},
                                      {"Translucent shadows", TranslucentShadows::params()}};
  return groups;
}

Parameterized makeAddOns() {
  static const std::vector<ParamDesc> all = [] {
    std::vector<ParamDesc> out;
    for (const AddOnGroup& g : addOnGroups()) out.insert(out.end(), g.params.begin(), g.params.end());
    return out;
  }();
  return Parameterized(all);
}

void applySettings(const std::vector<std::pair<std::string, std::string>>& settings, Scene& scene, Technique& technique) {
  for (const auto& [key, value] : settings) {
    if (key == "light.count") {
      const int n = static_cast<int>(parseParamValue(sceneParamDesc(key), value));
      if (n > static_cast<int>(scene.lights.size()))
        throw usageError(fmt::format("light.count={}: the scene has {} light{}", value, scene.lights.size(),
                                     scene.lights.size() == 1 ? "" : "s"));
      for (int i = static_cast<int>(scene.lights.size()) - 1; n > 0 && i >= n; --i)
        scene.animation.removeLight(static_cast<uint32_t>(i));
      if (n > 0) scene.lights.resize(static_cast<size_t>(n));
    } else if (key == "light.size") {
      const float v = parseParamValue(sceneParamDesc(key), value);
      PN_CHECK(!scene.lights.empty(), "light.size: the scene has no light");
      if (scene.lights.front().type == LightType::Directional && v > kMaxSunAngularRadiusRad)
        throw usageError(fmt::format("light.size={}: the light is a sun, whose size is an angular radius in rad, at most {}",
                                     value, kMaxSunAngularRadiusRad));
      const float rangeM = scene.lights.front().rangeM;  // as scene files: the range ends outside the sphere
      if (scene.lights.front().type != LightType::Directional && rangeM > 0.0f && v >= rangeM)
        throw usageError(fmt::format("light.size={}: the first light's range is {} m; its size (sphere radius) must stay below it", value,
                                     rangeM));
      scene.lights.front().size = v;
    } else {
      technique.set(key, std::string_view(value));
    }
  }
}

}  // namespace penumbra
