#pragma once
// What the core keeps for one light from frame to frame, under the light's key (its Light::id):
// the technique it runs (Shadows' technique with the light's own settings merged in) and what
// was made from it: the projection (its parameter values), the filter (its maps, prefiltered
// textures and tables: its GPU storage), the accumulated V, the uniform blocks its passes read.
// Reordering, adding or removing lights moves no state from one light to another. A technique
// that needs more of its own per light (a page table of virtual maps, a reduction of the depth
// buffer for its fit) keeps it in the filter or projection instance, which is the light's alone.
#include "core/MapUpdateSchedule.h"
#include "frame/Filter.h"
#include "frame/Projection.h"
#include "frame/ScreenTarget.h"
#include "frame/VirtualPages.h"
#include "gl/Objects.h"
#include "techniques/temporal/TemporalAccumulation.h"
#include "techniques/translucent/TranslucentShadows.h"
#include "shared/Frame.h"
#include "shared/Shadow.h"

#include <penumbra/Light.h>
#include <penumbra/Technique.h>

#include <cstdint>
#include <memory>
#include <vector>

namespace penumbra::core {

struct LightState {
  explicit LightState(const LightKey& k) : key(k) {}

  LightKey key;
  /// The light's technique: Shadows' with the light's settings merged (Technique::forLight).
  Technique technique;
  std::unique_ptr<Projection> projection;  ///< made from `technique` (its values)
  std::unique_ptr<Filter> filter;          ///< of technique.filter(): the light's maps
  uint64_t filterMadeAt = 0;               ///< filterRevision() of the id when `filter` was made
  /// A paged projection's pages (Projection::pageLayout): which are resident where, the page
  /// table; none for whole maps.
  std::unique_ptr<VirtualPages> pages;
  TemporalHistory history;                 ///< V accumulated over earlier frames
  TranslucentShadows translucent;          ///< the translucent casters' maps (translucent.*)
  gl::Buffer frameBlock{"frame block", sizeof(gpu::FrameUniforms)};
  gl::Buffer shadowBlock{"shadow block", sizeof(gpu::ShadowUniforms)};

  // This frame's (or the last frame's, between render() calls):
  Light light;
  size_t layer = 0;                ///< its layer of the visibility array (its place in the lights)
  LightFrusta frusta;              ///< its views as its maps were drawn
  int mapSize = 0;                 ///< what the budget granted (0: never rendered)
  std::vector<uint8_t> keptViews;  ///< per view: kept from an earlier frame (MapUpdates::Budget)

  /// Makes the state run `merged` (the light's technique this frame): a new filter when its kind
  /// changed (the old maps go), a new projection when the projection or its values did; the
  /// same objects otherwise. Returns true when the filter was remade.
  bool adopt(const Technique& merged);
};

/// What a light's accumulated V depends on besides the surfaces: its technique but the
/// accumulation's own parameters (temporal.*).
uint64_t accumulationKey(const Technique& technique);

}  // namespace penumbra::core
