#include "core/MapUpdateSchedule.h"

#include <algorithm>

namespace penumbra::core {

void MapUpdateSchedule::reset() { *this = {}; }

void MapUpdateSchedule::forget(const LightKey& light) { mLights.erase(light); }

void MapUpdateSchedule::beginFrame(std::span<const LightPolicy> lights) {
  std::map<LightKey, HeldLight> held;
  for (const LightPolicy& l : lights)
    if (auto it = mLights.find(l.key); it != mLights.end() && l.shadowed) held.insert(mLights.extract(it));
  mLights = std::move(held);
  struct Candidate {
    int staleness;
    HeldMap* map;
  };
  // Budget pools: every light that shares the common budget (key: none), and each light with a
  // budget of its own (key: the light's).
  struct Pool {
    int budget = 0;
    std::vector<Candidate> held;
  };
  Pool shared;
  std::map<LightKey, Pool> own;
  for (const LightPolicy& l : lights) {
    const bool budget = l.updates.policy == MapUpdates::Policy::Budget;
    Pool& pool = l.ownBudget ? own[l.key] : shared;
    if (budget) pool.budget = std::max(1, l.updates.budgetMaps);
    const auto it = mLights.find(l.key);
    if (it == mLights.end()) continue;
    for (HeldMap& m : it->second.maps) {
      m.update = !budget;
      if (budget) pool.held.push_back({m.staleness, &m});
    }
  }
  const auto pick = [](Pool& pool) {
    // The least recently updated first; on ties, light then view order.
    std::stable_sort(pool.held.begin(), pool.held.end(), [](const Candidate& a, const Candidate& b) { return a.staleness > b.staleness; });
    for (size_t i = 0; i < pool.held.size() && i < static_cast<size_t>(pool.budget); ++i) pool.held[i].map->update = true;
  };
  pick(shared);
  for (auto& [key, pool] : own) pick(pool);
}

void MapUpdateSchedule::beginFrame(const MapUpdates& updates, const std::vector<bool>& shadowed) {
  std::vector<LightPolicy> lights;
  for (size_t i = 0; i < shadowed.size(); ++i) lights.push_back({LightKey{0, i}, shadowed[i], updates, false});
  beginFrame(lights);
}

int MapUpdateSchedule::staleness(const LightKey& light) const {
  int oldest = 0;
  if (const auto it = mLights.find(light); it != mLights.end())
    for (const HeldMap& m : it->second.maps) oldest = std::max(oldest, m.staleness);
  return oldest;
}

std::vector<uint8_t> MapUpdateSchedule::apply(const LightKey& light, LightFrusta& frusta, int mapSize) {
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
