#pragma once
// pcf: percentage-closer filtering with a box or Poisson kernel of fixed radius (pcf.glsl).
#include "gl/Objects.h"
#include "frame/ShadowMaps.h"

#include "frame/Filter.h"

#include <numbers>
#include <string_view>

namespace penumbra {

/// Names of PN_KERNEL_* (pcf.kernel, pcss.pattern), in enum order.
inline constexpr std::string_view kKernelNames[] = {"box", "poisson"};

/// A GL sampler object that turns on hardware depth comparison (sampler2DArrayShadow: lit when
/// ref ≤ stored) with bilinear filtering, bound over a depth texture's unit for one dispatch:
/// the texture's own state (raw depths, nearest) stays as other passes expect. Created on first
/// use, so filters can be made without a GL context; a gl::Sampler, so gl::liveObjectCount sees it.
/// The largest radius (texels) of a kernel of taps in a map of mapSize texels per side: turned, a
/// kernel reaches √2 × its radius from its centre, and common/depth_compare.glsl's tapKernel
/// moves it inward at the map's edge but never narrows it. pcf and pcss keep their radii to it.
inline float maxKernelRadiusTexels(int mapSize) {
  return 0.5f * static_cast<float>(mapSize - 1) / std::numbers::sqrt2_v<float>;
}

class ComparisonSampler {
public:
  void bind(GLuint unit);
  static void unbind(GLuint unit) { gl::Sampler::unbindUnit(unit); }

private:
  gl::Sampler mSampler;
};

class PcfFilter final : public Filter {
public:
  PcfFilter();
  bool readsPagedMaps() const override { return true; }
  std::string_view id() const override { return "pcf"; }
  std::string_view description() const override {
    return "percentage-closer filtering: average of depth comparisons over a box or rotated Poisson kernel";
  }
  void renderShadowMaps(FrameContext& frame) override;
  void computeVisibility(FrameContext& frame) override;
  std::vector<DebugImage> debugImages() const override;

private:
  ShadowMapArray mMaps;
  ComparisonSampler mCompare;
};

}  // namespace penumbra
