#include "core/FrameBlocks.h"

#include "frame/FrameContext.h"

#include <penumbra/Error.h>

#include <fmt/format.h>

#include <cmath>

namespace penumbra::core {

gpu::LightGpu lightGpu(const Light& light) {
  gpu::LightGpu l{};
  l.direction = glm::vec4(glm::normalize(light.direction), shaderLightKind(light));
  l.position = glm::vec4(light.position, 0.0f);
  l.radiance = glm::vec4(light.color * light.intensity, light.size);
  l.cone = glm::vec4(std::cos(light.coneAngleRad), std::cos(light.innerConeAngleRad), light.rangeM, 0.0f);
  return l;
}

gpu::FrameUniforms frameUniforms(const ShadowCamera& camera, const Light& light, glm::ivec2 screen, int frameIndex,
                                 float sceneRadiusM) {
  gpu::FrameUniforms f{};
  f.viewFromWorld = camera.viewFromWorld;
  f.clipFromWorld = camera.clipFromView * camera.viewFromWorld;
  f.worldFromClip = glm::inverse(f.clipFromWorld);
  f.cameraPosition = glm::vec4(camera.fit.position, 1.0f);
  f.light = lightGpu(light);
  f.screen = glm::ivec4(screen.x, screen.y, frameIndex, 0);
  f.sceneInfo = glm::vec4(sceneRadiusM, 0, 0, 0);
  // Stored depth → ndc.z, and the stored depth of the far plane (where nothing was drawn): 1,
  // or 0 under reversed-Z (the near plane's ndc.z above the far plane's).
  const bool zeroToOne = camera.depth == DepthConvention::ZeroToOne;
  const glm::mat4& p = camera.clipFromView;
  const auto ndcAt = [&p](float distanceM) {  // perspective or orthographic
    const glm::vec4 clip = p * glm::vec4(0.0f, 0.0f, -distanceM, 1.0f);
    return clip.z / clip.w;
  };
  const bool reversed = ndcAt(camera.fit.nearM) > ndcAt(camera.fit.farM);
  f.depthInfo = glm::vec4(zeroToOne ? 1.0f : 2.0f, zeroToOne ? 0.0f : -1.0f, reversed ? 0.0f : 1.0f, 0.0f);
  return f;
}

gpu::ShadowUniforms shadowUniforms(const LightFrusta& frusta, int mapSize) {
  PN_CHECK(!frusta.views.empty() && frusta.views.size() <= PN_MAX_SHADOW_VIEWS,
           fmt::format("a projection produced {} shadow views (1..{} allowed)", frusta.views.size(), PN_MAX_SHADOW_VIEWS));
  gpu::ShadowUniforms s{};
  for (size_t i = 0; i < frusta.views.size(); ++i) {
    const ShadowView& v = frusta.views[i];
    s.views[i].clipFromWorld = v.clipFromWorld;
    s.views[i].depthPlane = v.depthPlane;
    s.views[i].range = glm::vec4(v.nearM, v.farM, v.perspective ? 1.0f : 0.0f, v.splitFarM);
    s.views[i].extent = glm::vec4(v.extent, frusta.blendBandM, v.warped ? 1.0f : 0.0f);
  }
  s.info = glm::ivec4(static_cast<int>(frusta.views.size()), mapSize, 0, 0);
  return s;
}

}  // namespace penumbra::core
