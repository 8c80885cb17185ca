#pragma once
// Every projection and filter by id; adding a technique adds one line in Registry.cpp.
#include <penumbra/Filter.h>
#include <penumbra/Projection.h>

#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace penumbra {

std::vector<std::string> projectionIds();
std::vector<std::string> filterIds();
/// Throw a usage Error naming the id and listing the known ones.
std::unique_ptr<Projection> makeProjection(std::string_view id);
std::unique_ptr<Filter> makeFilter(std::string_view id);

/// A parameter group any filter can take: a pass the core runs after the filter's own.
struct AddOnGroup {
  std::string_view label;             ///< "Contact shadows"
  std::span<const ParamDesc> params;  ///< keys "prefix.name"
};
/// Every add-on group: contact shadows ("contact.*", docs/contact.md) and temporal accumulation
/// ("temporal.*", docs/temporal.md).
std::span<const AddOnGroup> addOnGroups();
/// Every add-on group's parameters in one set, at their defaults (what Shadows::addOns holds).
std::unique_ptr<Parameterized> makeAddOns();

/// Applies "key" → "value" settings: "light.size" to the scene's first light, the others to
/// the projection, the filter or `addOns` (makeAddOns) by key. Usage Error for a key none of
/// them has.
void applyParams(const std::vector<std::pair<std::string, std::string>>& settings, Scene& scene,
                 Projection& projection, Filter& filter, Parameterized* addOns = nullptr);

}  // namespace penumbra
