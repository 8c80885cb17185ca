#pragma once
// sdf: soft shadows by sphere tracing a signed distance field of the casters (docs/sdf.md).
// No shadow map: renderShadowMaps only makes sure the field of the current scene is on the GPU
// (made once per set of caster triangles by the installed baker, sdf::setBaker: src/bake/ bakes it
// with Embree and caches it on disk); the visibility pass marches it toward the light.
#include "gl/Objects.h"
#include "techniques/sdf/SdfVolume.h"
#include "techniques/sdf/sdf.shared.h"

#include "frame/Filter.h"

#include <cstdint>

namespace penumbra {

class SdfFilter final : public Filter {
public:
  SdfFilter();
  std::string_view id() const override { return "sdf"; }
  std::string_view description() const override {
    return "sphere-traced signed distance field of the casters (baked per scene, no shadow map); k from the light size or set";
  }
  /// Its field is baked from every caster's triangles (CasterGeometry carries no transmittance).
  std::string_view translucentCasters() const override {
    return "treated as opaque, with translucent.shadows on too (the field is baked from every caster's triangles)";
  }
  /// Refused when no baker is installed (sdf::setBaker): Penumbra::shadows has none of its own.
  std::string incompatibility(std::string_view projectionId, const Light& light) const override;
  /// Uploads the casters' field as an R32F 3D texture the first time, and again only when the
  /// casters' geometry or sdf.resolution changes (one hash of the casters per frame).
  void renderShadowMaps(FrameContext& frame) override;
  void computeVisibility(FrameContext& frame) override;
  /// "sdf-slice": the field's middle z slice (m), as a 2D texture.
  std::vector<DebugImage> debugImages() const override;
  /// The field's bake (its original time when the field came from the cache).
  std::vector<OneOffCost> oneOffCosts() const override;

  /// The field on the GPU: grid dims (0 = none), lo, voxel, sheets, bake stats; the grid's
  /// distances are not kept on the CPU.
  const sdf::SdfVolume& field() const { return mGrid; }
  const gl::Texture& fieldTexture() const { return mField; }
  /// Uploads `volume` as the field (what renderShadowMaps does after loading or baking). For
  /// tests and tools: the next frame still checks the casters' key and replaces it.
  void setField(const sdf::SdfVolume& volume);
  /// How many fields were uploaded so far (one per scene: the per-frame check is a hash).
  int fieldUploads() const { return mUploads; }
  /// The visibility pass's uniform block for the current field and the parameters `p`.
  gpu::SdfUniforms uniforms(const Parameterized& p) const;

private:
  sdf::SdfVolume mGrid;
  uint64_t mKey = 0;
  bool mHaveField = false;
  int mUploads = 0;
  gl::Texture mField, mSlice;
};

}  // namespace penumbra
