// Every technique by id. Adding one = one line here + its own files.
#include <penumbra/Error.h>
#include <penumbra/Registry.h>

#include "shadows/filters/EsmFilter.h"
#include "shadows/filters/EvsmFilter.h"
#include "shadows/filters/EvsmSoftFilter.h"
#include "shadows/filters/HardFilter.h"
#include "shadows/filters/PcfFilter.h"
#include "shadows/filters/PcssFilter.h"
#include "shadows/filters/SecondDepthFilter.h"
#include "shadows/filters/SmrtFilter.h"
#include "shadows/filters/MsmFilter.h"
#include "shadows/filters/MsmSoftFilter.h"
#include "shadows/filters/VsmFilter.h"
#include "shadows/filters/VssmFilter.h"
#include "shadows/contact/ContactShadows.h"
#include "shadows/projections/CascadedProjection.h"
#include "shadows/projections/LightSpacePerspectiveProjection.h"
#include "shadows/projections/PerspectiveProjection.h"
#include "shadows/projections/SampleDistributionProjection.h"
#include "shadows/projections/TrapezoidalProjection.h"
#include "shadows/projections/UniformProjection.h"
#include "shadows/sdf/SdfFilter.h"
#include "shadows/temporal/TemporalAccumulation.h"

#include <fmt/format.h>

#include <functional>

namespace penumbra {
namespace {

template <class T>
struct Entry {
  std::string_view id;
  std::function<std::unique_ptr<T>()> make;
};

const std::vector<Entry<Projection>>& projections() {
  static const std::vector<Entry<Projection>> list = {
      {"uniform", [] { return std::make_unique<UniformProjection>(); }},
      {"csm", [] { return std::make_unique<CascadedProjection>(); }},
      {"psm", [] { return std::make_unique<PerspectiveProjection>(); }},
      {"tsm", [] { return std::make_unique<TrapezoidalProjection>(); }},
      {"lispsm", [] { return std::make_unique<LightSpacePerspectiveProjection>(); }},
      {"sdsm", [] { return std::make_unique<SampleDistributionProjection>(); }},
  };
  return list;
}

const std::vector<Entry<Filter>>& filters() {
  static const std::vector<Entry<Filter>> list = {
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
  };
  return list;
}

template <class T>
std::vector<std::string> ids(const std::vector<Entry<T>>& list) {
  std::vector<std::string> out;
  for (const Entry<T>& e : list) out.emplace_back(e.id);
  return out;
}

template <class T>
std::unique_ptr<T> make(const std::vector<Entry<T>>& list, std::string_view id, const char* what) {
  for (const Entry<T>& e : list)
    if (e.id == id) return e.make();
  const std::string known = joinNames(ids(list));
  throw usageError(fmt::format("unknown {} '{}' (known: {})", what, id, known));
}

}  // namespace

std::vector<std::string> projectionIds() { return ids(projections()); }
std::vector<std::string> filterIds() { return ids(filters()); }
std::unique_ptr<Projection> makeProjection(std::string_view id) { return make(projections(), id, "projection"); }
std::unique_ptr<Filter> makeFilter(std::string_view id) { return make(filters(), id, "filter"); }

std::span<const AddOnGroup> addOnGroups() {
  static const AddOnGroup groups[] = {{"Contact shadows", ContactShadows::params()},
                                      {"Temporal accumulation", TemporalAccumulation::params()}};
  return groups;
}

std::unique_ptr<Parameterized> makeAddOns() {
  static const std::vector<ParamDesc> all = [] {
    std::vector<ParamDesc> out;
    for (const AddOnGroup& g : addOnGroups()) out.insert(out.end(), g.params.begin(), g.params.end());
    return out;
  }();
  return std::make_unique<Parameterized>(all);
}

void applyParams(const std::vector<std::pair<std::string, std::string>>& settings, Scene& scene,
                 Projection& projection, Filter& filter, Parameterized* addOns) {
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
    } else if (projection.hasParam(key)) {
      projection.setParam(key, std::string_view(value));
    } else if (filter.hasParam(key)) {
      filter.setParam(key, std::string_view(value));
    } else if (addOns && addOns->hasParam(key)) {
      addOns->setParam(key, std::string_view(value));
    } else {
      throw usageError(fmt::format("unknown parameter '{}' for --projection {} --filter {} (penumbra list shows them all)",
                                   key, projection.id(), filter.id()));
    }
  }
}

}  // namespace penumbra
