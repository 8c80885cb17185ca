#pragma once
// Which shadow maps a frame updates under MapUpdates. Under a Budget a frame updates the N maps
// of its pool that were updated least recently (ties in light then view order: round-robin once
// every map has been drawn): the pool is every light that follows Shadows' policy, or one light
// with a budget of its own. Every other map keeps what it holds, and its light's frusta get back
// the view it was drawn with, so that the shadow block the visibility pass reads matches the
// map. Each map's staleness (frames since its update) is recorded for the stats. Lights are
// known by their LightKey, so a light keeps its maps' schedule when the lights are reordered,
// added or removed. No GL.
#include <penumbra/Light.h>
#include <penumbra/MapUpdates.h>
#include <penumbra/ShadowViews.h>

#include <compare>
#include <cstddef>
#include <cstdint>
#include <map>
#include <span>
#include <vector>

namespace penumbra::core {

/// A light as the core knows it from frame to frame: the engine's Light::id, or for a light
/// without one (id 0) its position in the frame's list.
struct LightKey {
  uint64_t id = 0;
  size_t index = 0;  ///< only for id 0
  static LightKey of(const Light& light, size_t index) { return light.id != 0 ? LightKey{light.id, 0} : LightKey{0, index}; }
  auto operator<=>(const LightKey&) const = default;
};

class MapUpdateSchedule {
public:
  /// Forgets every map (a new policy): the next frame draws them all.
  void reset();
  /// Forgets one light's maps (its filter was remade): its next frame draws them all.
  void forget(const LightKey& light);
  /// One light's policy in a frame.
  struct LightPolicy {
    LightKey key;
    bool shadowed = true;     ///< false: casts no shadow, holds no map
    MapUpdates updates;       ///< what the light follows this frame
    bool ownBudget = false;   ///< its Budget counts its own maps only (else it shares the others')
  };
  /// Starts a frame of these lights (in the frame's order): picks the maps each Budget updates
  /// among those held from earlier frames. The maps of lights not in the frame are forgotten.
  void beginFrame(std::span<const LightPolicy> lights);
  /// The same with every light following `updates` (one shared budget), known by its index.
  void beginFrame(const MapUpdates& updates, const std::vector<bool>& shadowed);
  /// A light's views this frame: returns, per view, 1 where its map is kept as it is (and then
  /// its view in `frusta` is replaced by the one it was drawn with; the cascade's split stays
  /// this frame's), 0 where it is updated. A light whose map size or view count changed, or whose
  /// maps are not held, is updated in full outside the budget.
  std::vector<uint8_t> apply(const LightKey& light, LightFrusta& frusta, int mapSize);

  /// Kept maps and staleness since the last reset.
  size_t kept() const { return mKept; }
  int maxStaleness() const { return mMaxStaleness; }
  /// The oldest of a light's maps in this frame (frames; 0 when all were updated).
  int staleness(const LightKey& light) const;
  double meanStaleness() const { return mSamples ? static_cast<double>(mStalenessSum) / static_cast<double>(mSamples) : 0.0; }

private:
  struct HeldMap {
    ShadowView view;    ///< the view it was drawn with
    int staleness = 0;  ///< frames since it was drawn
    bool update = false;  ///< this frame updates it
  };
  struct HeldLight {
    int mapSize = 0;
    std::vector<HeldMap> maps;
  };
  std::map<LightKey, HeldLight> mLights;
  size_t mKept = 0, mSamples = 0;
  int64_t mStalenessSum = 0;
  int mMaxStaleness = 0;
};

}  // namespace penumbra::core
