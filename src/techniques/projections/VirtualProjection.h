#pragma once
// virtual: virtual (paged) shadow maps with page caching, the sun as a clipmap around the camera
// (docs/virtual.md). Each level is one view: an orthographic virtual map of virtual.virtualSize²
// texels centred on the camera, twice as wide as the level before it, snapped to whole pages so
// that a page keeps its place in the world while the camera moves; all levels share the light's
// rotation and one depth range (the scene's), so a page stays valid until its casters or the
// light move. Which pages are drawn, where they live and when they are drawn again is the
// frame's (frame/VirtualPages): this class only places the levels and states the layout. A spot
// light is one perspective view of the scene in mips, a point light its six cube faces in mips
// (perspectiveMips), fixed while the camera moves.
#include "frame/Projection.h"

namespace penumbra {

class VirtualProjection final : public Projection {
public:
  VirtualProjection();
  std::string_view id() const override { return "virtual"; }
  std::string_view description() const override {
    return "virtual maps in pages drawn only where pixels need them and cached across frames (sun: a clipmap of levels; spot: one view in mips; point: six faces in mips)";
  }
  std::string incompatibility(const Light& light) const override;
  /// One view per level; `mapSize` is not used (the virtual size is the projection's).
  LightFrusta computeFrusta(const Camera& camera, float aspect, const Light& light, const SceneExtent& scene,
                            int mapSize) const override;
  std::optional<PageLayout> pageLayout() const override;

private:
  /// Levels of each perspective view (a spot's one, a point light's faces).
  int mipLevels(const Light& light, const PageLayout& layout) const;
  static void appendMips(const ShadowView& base, int levels, LightFrusta& f);
  LightFrusta perspectiveMips(const Light& light, const SceneExtent& scene, const PageLayout& layout) const;
};

}  // namespace penumbra
