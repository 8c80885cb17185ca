#pragma once
// Every projection and filter by id; adding a technique adds one line in Registry.cpp. The
// public face of the registry is penumbra/Technique.h (ids, descriptions, parameter tables, the
// technique as a value); this header makes the objects that run one: a light's projection (its
// parameter values) and a light's filter (its GPU storage).
#include "frame/Filter.h"
#include "frame/Projection.h"

#include <penumbra/Scene.h>
#include <penumbra/Technique.h>

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace penumbra {

/// A projection at its defaults; a usage Error names an unknown id and lists the known ones.
std::unique_ptr<Projection> makeProjection(std::string_view id);
/// The technique's projection with the technique's values.
std::unique_ptr<Projection> makeProjection(const Technique& technique);
/// One light's filter: its storage, empty until its first frame (no GL object is made here).
std::unique_ptr<Filter> makeFilter(std::string_view id);

/// Why a projection (or a filter with a projection) cannot shadow `light`; empty when it can.
/// Usage Errors for unknown ids.
std::string projectionIncompatibility(std::string_view projection, const Light& light);
std::string filterIncompatibility(std::string_view filter, std::string_view projection, const Light& light);
/// Whether the filter shadows through translucent casters itself with these values
/// (Filter::shadowsThroughTranslucent).
bool filterShadowsThroughTranslucent(std::string_view filter, const Parameterized& values);

/// Adds a filter of the caller's to the registry under its own id (Filter::id), after the
/// built-in ones: techniques name it like any other, and every light that runs it gets its own
/// instance from `make`. Throws a usage Error when the id is taken.
void registerFilter(const std::function<std::unique_ptr<Filter>()>& make);
/// How many times filter `id`'s maker was replaced (reloadTechniqueFolder): a light whose filter
/// was made at another revision makes a new one. 0 for a filter never replaced.
uint64_t filterRevision(std::string_view id);

/// Every add-on group's parameters in one set, at their defaults.
Parameterized makeAddOns();

/// Applies "key" → "value" settings of a command line or a scene: "light.size" to the scene's
/// first light, "light.count" to its light list, the others to the technique
/// (Technique::set: a usage Error for a key that is not the technique's).
void applySettings(const std::vector<std::pair<std::string, std::string>>& settings, Scene& scene, Technique& technique);

}  // namespace penumbra
