#pragma once
// Every projection and filter by id; adding a technique adds one line in Registry.cpp.
#include <penumbra/Filter.h>
#include <penumbra/Projection.h>

#include <memory>
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

/// The add-on parameter group every filter can take: contact shadows ("contact.*",
/// docs/contact.md), with its defaults.
std::unique_ptr<Parameterized> makeContactShadows();

/// Applies "key" → "value" settings: "light.size" to the scene's first light, the others to
/// the projection, the filter or `addOns` (makeContactShadows) by key. Usage Error for a key
/// none of them has.
void applyParams(const std::vector<std::pair<std::string, std::string>>& settings, Scene& scene,
                 Projection& projection, Filter& filter, Parameterized* addOns = nullptr);

}  // namespace penumbra
