#pragma once
// Which shadow maps a frame updates under MapUpdates. Under a Budget a frame updates the N maps
// of its pool that were updated least recently (ties in light then view order: round-robin once
// every map has been drawn): the pool is every light that follows Shadows' policy, or one light
// with a budget of its own. Every other map keeps what it holds, and its light's frusta get back
// the view it was drawn with, so that the shadow block the visibility pass reads matches the
// map. Each map's staleness (frames since its update) is recorded for the stats. No GL.
#include <penumbra/Projection.h>
#include <penumbra/Shadows.h>

#include <cstdint>
#include <span>
#include <vector>

namespace penumbra::core {

class MapUpdateSchedule {
public:
  /// Forgets every map (a new policy, a new technique): the next frame draws them all.
  void reset();
  /// Forgets light `light`'s maps only (its technique objects were remade).
  void forgetLight(size_t light);
  /// One light's policy in a frame.
  struct LightPolicy {
    bool shadowed = true;     ///< false: casts no shadow, holds no map
    MapUpdates updates;       ///< what the light follows this frame
    bool ownBudget = false;   ///< its Budget counts its own maps only (else it shares the others')
  };
  /// Starts a frame of `lights.size()` lights: picks the maps each Budget updates among those held
  /// from earlier frames.
  void beginFrame(std::span<const LightPolicy> lights);
  /// The same with every light following `updates` (one shared budget).
  void beginFrame(const MapUpdates& updates, const std::vector<bool>& shadowed);
  /// Light `light`'s views this frame: returns, per view, 1 where its map is kept as it is (and
  /// then its view in `frusta` is replaced by the one it was drawn with; the cascade's split stays
  /// this frame's), 0 where it is updated. A light whose map size or view count changed, or whose
  /// maps are not held, is updated in full outside the budget.
  std::vector<uint8_t> apply(size_t light, LightFrusta& frusta, int mapSize);

  /// Kept maps and staleness since the last reset.
  size_t kept() const { return mKept; }
  int maxStaleness() const { return mMaxStaleness; }
  /// The oldest of light `light`'s maps in this frame (frames; 0 when all were updated).
  int staleness(size_t light) const;
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
  std::vector<HeldLight> mLights;
  size_t mKept = 0, mSamples = 0;
  int64_t mStalenessSum = 0;
  int mMaxStaleness = 0;
};

}  // namespace penumbra::core
