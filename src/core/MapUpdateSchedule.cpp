#include "core/MapUpdateSchedule.h"

#include <algorithm>

namespace penumbra::core {

void MapUpdateSchedule::reset() { *this = {}; }

void MapUpdateSchedule::forgetLight(size_t light) {
  if (light < mLights.size()) mLights[light] = {};
}

void MapUpdateSchedule::beginFrame(const MapUpdates& updates, const std::vector<bool>& shadowed) {
  mUpdates = updates;
  mLights.resize(shadowed.size());
  struct Candidate {
    int staleness;
    size_t light, view;
  };
  std::vector<Candidate> held;
  for (size_t l = 0; l < mLights.size(); ++l) {
    if (!shadowed[l]) mLights[l] = {};
    for (size_t v = 0; v < mLights[l].maps.size(); ++v) {
      HeldMap& m = mLights[l].maps[v];
      m.update = updates.policy != MapUpdates::Policy::Budget;
      held.push_back({m.staleness, l, v});
    }
  }
  if (updates.policy != MapUpdates::Policy::Budget) return;
  // The least recently updated first; on ties, light then view order.
  std::stable_sort(held.begin(), held.end(), [](const Candidate& a, const Candidate& b) { return a.staleness > b.staleness; });
  const size_t budget = static_cast<size_t>(std::max(1, updates.budgetMaps));
  for (size_t i = 0; i < held.size() && i < budget; ++i) mLights[held[i].light].maps[held[i].view].update = true;
}

std::vector<uint8_t> MapUpdateSchedule::apply(size_t light, LightFrusta& frusta, int mapSize) {
  if (light >= mLights.size()) mLights.resize(light + 1);
  HeldLight& h = mLights[light];
  std::vector<uint8_t> kept(frusta.views.size(), 0);
  if (h.mapSize != mapSize || h.maps.size() != frusta.views.size()) {  // nothing held to keep: all drawn
    h.mapSize = mapSize;
    h.maps.assign(frusta.views.size(), {});
    for (HeldMap& m : h.maps) m.update = true;
  }
  for (size_t v = 0; v < h.maps.size(); ++v) {
    HeldMap& m = h.maps[v];
    if (m.update) {
      m.view = frusta.views[v];
      m.staleness = 0;
    } else {
      const float splitFarM = frusta.views[v].splitFarM;  // the camera's cascade ranges are this frame's
      frusta.views[v] = m.view;
      frusta.views[v].splitFarM = splitFarM;
      ++m.staleness;
      kept[v] = 1;
      ++mKept;
    }
    m.update = false;
    mStalenessSum += m.staleness;
    mMaxStaleness = std::max(mMaxStaleness, m.staleness);
    ++mSamples;
  }
  return kept;
}

}  // namespace penumbra::core
