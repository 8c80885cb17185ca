#include "core/MapUpdateSchedule.h"

#include <algorithm>
#include <map>

namespace penumbra::core {

void MapUpdateSchedule::reset() { *this = {}; }

void MapUpdateSchedule::forgetLight(size_t light) {
  if (light < mLights.size()) mLights[light] = {};
}

void MapUpdateSchedule::beginFrame(std::span<const LightPolicy> lights) {
  mLights.resize(lights.size());
  struct Candidate {
    int staleness;
    size_t light, view;
  };
  // Budget pools: every light that shares the common budget (key lights.size()), and each light
  // with a budget of its own (key: its index).
  std::map<size_t, std::pair<int, std::vector<Candidate>>> pools;
  for (size_t l = 0; l < mLights.size(); ++l) {
    if (!lights[l].shadowed) mLights[l] = {};
    const bool budget = lights[l].updates.policy == MapUpdates::Policy::Budget;
    auto& pool = pools[lights[l].ownBudget ? l : lights.size()];
    if (budget) pool.first = std::max(1, lights[l].updates.budgetMaps);
    for (size_t v = 0; v < mLights[l].maps.size(); ++v) {
      HeldMap& m = mLights[l].maps[v];
      m.update = !budget;
      if (budget) pool.second.push_back({m.staleness, l, v});
    }
  }
  for (auto& [key, pool] : pools) {
    auto& [budget, held] = pool;
    // The least recently updated first; on ties, light then view order.
    std::stable_sort(held.begin(), held.end(), [](const Candidate& a, const Candidate& b) { return a.staleness > b.staleness; });
    for (size_t i = 0; i < held.size() && i < static_cast<size_t>(budget); ++i) mLights[held[i].light].maps[held[i].view].update = true;
  }
}

void MapUpdateSchedule::beginFrame(const MapUpdates& updates, const std::vector<bool>& shadowed) {
  std::vector<LightPolicy> lights;
  for (const bool s : shadowed) lights.push_back({s, updates, false});
  beginFrame(lights);
}

int MapUpdateSchedule::staleness(size_t light) const {
  int oldest = 0;
  if (light < mLights.size())
    for (const HeldMap& m : mLights[light].maps) oldest = std::max(oldest, m.staleness);
  return oldest;
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
