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

/// Applies "key=value" settings: `light.*` to the scene, the rest to the projection or the
/// filter that declares the key. Throws a usage Error for an unknown key or a bad value.
void applyParams(const std::vector<std::pair<std::string, std::string>>& settings, Scene& scene,
                 Projection& projection, Filter& filter);

}  // namespace penumbra
