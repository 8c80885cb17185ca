#pragma once
// The softness axis: what the shadow map stores and how visibility is computed from it.
// A filter is one class + one GLSL file (src/techniques/filters/), registered in one line
// (src/techniques/Registry.cpp). An instance is one light's GPU storage (its maps, mips and tables)
// and the passes over it: it renders its maps, optionally prefilters them, and writes the
// visibility (R32F, 1 = lit), the contract read by everything downstream. Its parameter values
// are not its own: they are the light's technique's (FrameContext::param), so one light's
// settings never reach another light's maps.
#include <penumbra/Light.h>
#include <penumbra/Params.h>
#include <penumbra/Timings.h>

#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace penumbra {

class FrameContext;  // frame/FrameContext.h: what a filter may use during a frame

namespace gl { class Texture; }

/// An intermediate a filter can show: dumped by --dump, shown by the viewer (with `meaning` as
/// the legend of its values).
struct DebugImage {
  std::string name;              ///< file-name friendly: "shadow-map", "moments"
  const gl::Texture* texture;    ///< 2D or 2D array (layer 0 shown)
  std::string_view meaning;      ///< what a value is, with its unit: "linear light depth: 0 = near, 1 = far"
  /// A value that means "nothing here" rather than a measure (−1 = no blocker found): a viewer
  /// leaves it out of a measured range and shows it apart. Empty: every value is a measure.
  std::optional<float> noData = {};
};

/// Debug images that many filters have are named alike, so that a viewer showing one keeps
/// showing it across a filter switch: the depth map the filter compares against, and the
/// moments (or warped depths) it stores.
inline constexpr std::string_view kShadowMapImage = "shadow-map";
inline constexpr std::string_view kShadowMapMeaning = "linear light depth of the nearest caster: 0 = near plane, 1 = far plane";
inline constexpr std::string_view kMomentsImage = "moments";

class Filter {
public:
  /// `params`: the filter's parameter table, static (its values live in techniques).
  explicit Filter(std::span<const ParamDesc> params) : mParams(params) {}
  virtual ~Filter() = default;
  Filter(const Filter&) = delete;
  Filter& operator=(const Filter&) = delete;

  virtual std::string_view id() const = 0;
  virtual std::string_view description() const = 0;
  std::span<const ParamDesc> params() const { return mParams; }
  /// What the filter does with a translucent caster (CasterMesh::transmittance), for users
  /// (penumbra list, the docs). Every filter whose maps go through FrameContext::renderViews
  /// draws it as opaque, and with the translucent add-on on leaves it out of its maps while the
  /// add-on tints V by it (kTranslucentThroughAddOn).
  virtual std::string_view translucentCasters() const { return kTranslucentThroughAddOn; }
  static constexpr std::string_view kTranslucentThroughAddOn =
      "drawn as opaque; with translucent.shadows on, shadowed through: translucent.method=map leaves them "
      "out of its maps and tints V by their transmittance map (colour), translucent.method=stochastic dithers "
      "them into its maps by their opacity (V one channel, resolved by temporal.accumulate)";
  /// Whether, with these parameter values, the filter shadows through translucent casters
  /// itself: its maps then hold the opaque casters alone (FrameContext::translucentCasters is
  /// Skip), its visibility pass writes RGB, and the translucent add-on is refused beside it
  /// (Technique::problemWith). msm with msm.translucent on; no other filter.
  virtual bool shadowsThroughTranslucent(const Parameterized& values) const {
    (void)values;
    return false;
  }
  /// Empty when this filter works with the given projection and light; otherwise the reason,
  /// shown to the user (a pair that cannot work is refused, never rendered wrong).
  virtual std::string incompatibility(std::string_view projectionId, const Light& light) const {
    (void)projectionId; (void)light;
    return {};
  }
  /// Whether it reads its depth maps only through the shared addressing (common/shadow.glsl:
  /// mapTexel, fetchMapDepth), which a paged projection's maps (FrameContext::paged) answer
  /// through their page table. Filters that build mips, summed-area tables or moments over whole
  /// maps cannot read paged ones: the registry refuses such pairs.
  virtual bool readsPagedMaps() const { return false; }
  /// Rasterises the shadow map(s), one per view of FrameContext::frusta().
  virtual void renderShadowMaps(FrameContext& frame) = 0;
  /// Builds mip chains / summed-area tables from the maps (timed as the "prefilter" pass).
  virtual void prefilter(FrameContext& frame) { (void)frame; }
  /// Writes V for every surface pixel into the frame's visibility layer.
  virtual void computeVisibility(FrameContext& frame) = 0;
  virtual std::vector<DebugImage> debugImages() const { return {}; }
  /// What the filter made once for the current casters (after a frame); none for techniques
  /// that redo all their work every frame.
  virtual std::vector<OneOffCost> oneOffCosts() const { return {}; }

private:
  std::span<const ParamDesc> mParams;
};

}  // namespace penumbra
