#include "techniques/projections/UniformProjection.h"

#include "techniques/projections/LightSpace.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <span>

namespace penumbra {
namespace {

constexpr ParamDesc kParams[] = {
    {"uniform.marginTexels", "Margin", "border added around the fitted region, in texels of the map", "texels", 2.0f, 0.0f, 64.0f, 1.0f},
    {"uniform.cubeGuardTexels", "Cube guard band",
     "point lights: each cube face's map reaches this many texels past the face's edge, so a kernel, blocker search or "
     "filter region near an edge reads the scene beyond it (what the neighbouring face holds) instead of clamping",
     "texels", 32.0f, 0.0f, 256.0f, 1.0f, {}, {}, kPointLightBit},
};

constexpr float kMinNearM = 0.01f;          // a spot map's nearest near plane
constexpr float kMinNearFractionOfFar = 1e-3f;
constexpr float kDepthPaddingFraction = 1e-3f;  // keeps receivers strictly inside [0,1]

// Distance along the light axis (metres) of the nearest point of any caster's box inside
// `region` (the part of the light's view that holds the receivers' shadows): a caster's whole
// box, e.g. a large ground's, would reach far beyond it. `fallback` if no caster is inside.
float nearestCasterDistance(const SceneExtent& scene, const glm::mat4& lightFromWorld, float fallback,
                            std::span<const HalfSpace> region) {
  float nearest = fallback;
  for (const SceneExtent::Body& body : scene.bodies) {
    if (!body.castsShadow) continue;
    for (const glm::vec3& p : clipBoxToConvex(body.bounds, region))
      nearest = std::min(nearest, -(lightFromWorld * glm::vec4(p, 1.0f)).z);
  }
  return nearest;
}

}  // namespace

UniformProjection::UniformProjection() : Projection(kParams) {}

LightFrusta UniformProjection::computeFrusta(const Camera& camera, float aspect, const Light& light,
                                             const SceneExtent& scene, int mapSize) const {
  if (light.type == LightType::Point) return cubeFaceViews(light, scene, mapSize, param("uniform.cubeGuardTexels"));
  const float marginFraction = param("uniform.marginTexels") / static_cast<float>(mapSize);
  ShadowView v;
  if (light.type == LightType::Directional) {
    const Aabb sceneBounds = scene.bounds();
    const float radius = std::max(sceneBounds.radius(), 1e-3f);
    const glm::vec3 eye = sceneBounds.center() - light.direction * (2.0f * radius);
    v.viewFromWorld = lightViewMatrix(eye, light.direction);
    Aabb recv = visibleReceiversInLightSpace(v.viewFromWorld, camera, aspect, scene);
    if (recv.empty()) recv = sceneBounds.transformed(v.viewFromWorld);
    // Margin: a few texels so filters that look around a texel stay inside the map.
    const glm::vec2 size = glm::vec2(recv.size());
    const glm::vec2 pad = size * marginFraction;
    const glm::vec2 lo = glm::vec2(recv.lo) - pad, hi = glm::vec2(recv.hi) + pad;
    const float farM = -recv.lo.z;
    // Casters count only inside the map's prism: their part that can shadow the receivers.
    float nearM = nearestCasterDistance(scene, v.viewFromWorld, -recv.hi.z, lightRectHalfSpaces(v.viewFromWorld, lo, hi));
    const float pad_z = (farM - nearM) * kDepthPaddingFraction + 1e-4f;
    nearM -= pad_z;
    v.nearM = nearM;
    v.farM = farM + pad_z;
    v.perspective = false;
    v.extent = hi - lo;
    v.clipFromWorld = glm::orthoRH_ZO(lo.x, hi.x, lo.y, hi.y, v.nearM, v.farM) * v.viewFromWorld;
  } else {
    v.viewFromWorld = lightViewMatrix(light.position, light.direction);
    const Aabb recv = visibleReceiversInLightSpace(v.viewFromWorld, camera, aspect, scene);
    float halfAngle = light.coneAngleRad;
    float farM = 1.0f;
    if (!recv.empty()) {
      bool behind = false;
      float widest = 0.0f;
      for (const glm::vec3& c : recv.corners()) {
        if (c.z >= -kMinNearM) { behind = true; continue; }
        widest = std::max(widest, std::atan(std::max(std::abs(c.x), std::abs(c.y)) / -c.z));
        farM = std::max(farM, -c.z);
      }
      if (!behind) halfAngle = std::min(halfAngle, widest);
      if (behind) farM = std::max(farM, -recv.lo.z);
    }
    // Margin in angle: marginTexels of the map's width.
    constexpr float kMaxHalfAngleRad = 1.5f;  // ~86 degrees: beyond, the map's texels degenerate
    halfAngle = std::min(halfAngle * (1.0f + 2.0f * marginFraction), kMaxHalfAngleRad);
    const float tanHalf = std::tan(halfAngle);
    // The nearest point of any caster's box inside the light's pyramid up to the receivers.
    float nearM = nearestCasterDistance(scene, v.viewFromWorld, farM,
                                        lightPyramidHalfSpaces(v.viewFromWorld, tanHalf, kMinNearM, farM));
    nearM = std::max({nearM * (1.0f - kDepthPaddingFraction), kMinNearM, farM * kMinNearFractionOfFar});
    v.nearM = nearM;
    v.farM = farM * (1.0f + kDepthPaddingFraction);
    v.perspective = true;
    v.extent = glm::vec2(2.0f * tanHalf);
    v.clipFromWorld = glm::perspectiveRH_ZO(2.0f * halfAngle, 1.0f, v.nearM, v.farM) * v.viewFromWorld;
  }
  v.depthPlane = linearDepthPlane(v.viewFromWorld, v.nearM, v.farM);
  LightFrusta f;
  f.views.push_back(v);
  return f;
}

}  // namespace penumbra
