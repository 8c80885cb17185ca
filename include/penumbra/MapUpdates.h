#pragma once
// When shadow maps are drawn again: for every light (Shadows::setMapUpdates) or for one light
// (LightShadowSettings::updates, a scene file's "shadow": {"updates": …}).
#include <string>
#include <string_view>

namespace penumbra {

/// When each shadow map (a view: a cascade, a cube face, a spot's or sun's map) is drawn again.
/// Cached policies keep each map's static casters (CasterMesh::dynamic false) in a copy that is
/// restored while the map's view, the shadow pass's programs and parameters and the static casters
/// are unchanged, draw the dynamic casters over it, and fit the light's views to the static
/// casters and the receivers only (so that a moving caster does not move them; depth clamping
/// keeps casters in front of the near plane). Prefilters run on the result as before.
struct MapUpdates {
  enum class Policy {
    EveryFrame,   ///< every map drawn anew every frame, every caster in the views' fit (no cache)
    WhenInvalid,  ///< cached: every map updated every frame, its static casters redrawn only when invalid
    /// Cached, and only `budgetMaps` maps updated per frame, the least recently updated first
    /// (round-robin): across every light that follows Shadows::setMapUpdates, or across one
    /// light's own maps when the light sets it (LightShadowSettings::updates). The others keep
    /// what an earlier frame drew (dynamic casters included) with the view it was drawn with,
    /// which the visibility pass then reads (Shadows::frusta gives it). A map never drawn yet
    /// (the first frame, a new light, a new map size or view count) is drawn outside the budget.
    Budget,
  };
  Policy policy = Policy::EveryFrame;
  int budgetMaps = 1;  ///< Budget: maps updated per frame, ≥ 1
  bool cached() const { return policy != Policy::EveryFrame; }
  bool operator==(const MapUpdates&) const = default;
};

/// Most maps a budget names: any budget of at least one map works, and one above every map a
/// scene has (16 lights, at most 6 views each) updates them all; a larger number is a typo.
inline constexpr int kMaxBudgetMaps = 1000000;

/// "every", "invalid" or a number of maps per frame in [1, kMaxBudgetMaps] (a budget). Throws a
/// usage Error that names the text otherwise.
MapUpdates parseMapUpdates(std::string_view text);
/// "every", "invalid" or "budget N".
std::string mapUpdatesName(const MapUpdates& updates);
/// The text parseMapUpdates reads back: "every", "invalid" or "N".
std::string mapUpdatesText(const MapUpdates& updates);

}  // namespace penumbra
