#pragma once
// sdf: soft shadows by sphere tracing a signed distance field of the casters (docs/sdf.md).
// No shadow map: renderShadowMaps only makes sure the field of the current scene is on the GPU
// (baked once per scene, cached on disk); the visibility pass marches it toward the light.
#include "gl/Objects.h"
#include "shadows/sdf/SdfBake.h"

#include <penumbra/Filter.h>

#include <cstdint>

namespace penumbra {

class SdfFilter final : public Filter {
public:
  SdfFilter();
  std::string_view id() const override { return "sdf"; }
  std::string_view description() const override {
    return "sphere-traced signed distance field of the casters (baked per scene, no shadow map); k from the light size or set";
  }
  /// Uploads the scene's field as an R32F 3D texture the first time, and again only when the
  /// casters' geometry or sdf.resolution changes (one hash of the casters per frame).
  void renderShadowMaps(FrameContext& frame) override;
  void computeVisibility(FrameContext& frame) override;
  /// "sdf-slice": the field's middle z slice (m), as a 2D texture.
  std::vector<DebugImage> debugImages() const override;

  /// The grid on the GPU: dims (0 = no casters), lo, voxel, bake stats; its distances are not
  /// kept on the CPU.
  const sdf::SdfVolume& grid() const { return mGrid; }

private:
  void upload(const sdf::SdfVolume& volume);

  sdf::SdfVolume mGrid;
  uint64_t mKey = 0;
  bool mHaveField = false;
  gl::Texture mField, mSlice;
};

}  // namespace penumbra
