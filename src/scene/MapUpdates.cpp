#include <penumbra/Error.h>
#include <penumbra/MapUpdates.h>

#include <fmt/format.h>

#include <charconv>

namespace penumbra {

MapUpdates parseMapUpdates(std::string_view text) {
  if (text == "every") return {};
  if (text == "invalid") return {MapUpdates::Policy::WhenInvalid};
  int maps = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), maps);
  if (ec != std::errc() || end != text.data() + text.size() || maps < 1 || maps > kMaxBudgetMaps)
    throw usageError(fmt::format("map updates '{}': expected every, invalid or a number of maps per frame in [1, {}]", text,
                                 kMaxBudgetMaps));
  return {MapUpdates::Policy::Budget, maps};
}

std::string mapUpdatesText(const MapUpdates& updates) {
  switch (updates.policy) {
    case MapUpdates::Policy::EveryFrame: return "every";
    case MapUpdates::Policy::WhenInvalid: return "invalid";
    case MapUpdates::Policy::Budget: break;
  }
  return std::to_string(updates.budgetMaps);
}

std::string mapUpdatesName(const MapUpdates& updates) {
  return updates.policy == MapUpdates::Policy::Budget ? "budget " + mapUpdatesText(updates) : mapUpdatesText(updates);
}

}  // namespace penumbra
