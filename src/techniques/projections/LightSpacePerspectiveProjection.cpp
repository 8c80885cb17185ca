#include "techniques/projections/LightSpacePerspectiveProjection.h"

#include "techniques/projections/LightSpace.h"
#include "techniques/projections/TrapezoidalProjection.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace penumbra {
namespace {

constexpr ParamDesc kParams[] = {
    {"lispsm.nScale", "n scale", "multiplies Wimmer et al.'s optimal distance n_opt of the warp's centre of projection; 1 = the optimum, larger = weaker warp (toward uniform), smaller = more texels near the camera", "×n_opt",
     1.0f, 0.05f, 100.0f, 0.0f},
    {"lispsm.marginTexels", "Margin", "border added around the warped region, in texels", "texels", 2.0f, 0.0f, 64.0f, 1.0f},
};

// Beyond this many region depths between P's centre and its near plane the warp changes texel
// sizes by less than 0.02 % over the region ((1 + 1/r)² − 1): a uniform map with rounding noise,
// so the unwarped fit is taken (the paper's limit n_opt → ∞).
constexpr float kMaxNearOverDepth = 1e4f;
// The image of the view axis must span at least this share of the region's size in the light's
// image plane to give P a direction (less: the camera looks along the light).
constexpr float kMinAxisImageFraction = 1e-4f;

// The light's image plane as homogeneous 2-D coordinates (x, y, ·, w) of a world point: the sun's
// light view in metres (w = 1); a spot's view divided by its depth (its post-perspective plane,
// where its rays are parallel).
glm::mat4 planeFromWorld(const ShadowView& base, const Light& light) {
  if (light.type == LightType::Directional) return base.viewFromWorld;
  const glm::mat4& v = base.viewFromWorld;
  glm::mat4 m(0.0f);
  for (int c = 0; c < 4; ++c) {
    m[c][0] = v[c][0];
    m[c][1] = v[c][1];
    m[c][3] = -v[c][2];
  }
  return m;
}

glm::vec2 toPlane(const glm::mat4& plane, const glm::vec3& p, bool& valid) {
  const glm::vec4 c = plane * glm::vec4(p, 1.0f);
  valid = valid && c.w > 0.0f;
  return glm::vec2(c) / c.w;
}

}  // namespace

float lispsmOptimalNear(float z0M, float depthM, float sinGamma) {
  if (!(sinGamma > 0.0f)) return std::numeric_limits<float>::infinity();
  const float z1M = z0M + depthM * sinGamma;  // the camera depth P's far plane reaches
  return (z0M + std::sqrt(z0M * z1M)) / sinGamma;
}

LispsmWarp computeLispsmWarp(const Camera& camera, const Light& light, std::span<const glm::vec3> body,
                             const ShadowView& base, float nScale, float marginFraction) {
  LispsmWarp out;
  out.degenerate = true;
  if (body.empty()) return out;
  const glm::vec3 fwd = camera.forward();
  // The light's direction at the receivers: the sun's, or a spot's ray to their centre.
  glm::vec3 centre(0.0f);
  for (const glm::vec3& p : body) centre += p / static_cast<float>(body.size());
  const glm::vec3 l = light.type == LightType::Directional ? glm::normalize(light.direction)
                                                            : glm::normalize(centre - light.position);
  out.sinGamma = glm::length(glm::cross(fwd, l));
  const glm::vec2 depths = cameraDepthRange(body, camera);
  out.nearM = std::max(depths.x, camera.nearM);
  const float farM = std::max(depths.y, out.nearM);

  const glm::mat4 plane = planeFromWorld(base, light);
  bool valid = true;
  std::vector<glm::vec2> hull;
  for (const glm::vec3& p : body) hull.push_back(toPlane(plane, p, valid));
  const glm::vec2 top = toPlane(plane, camera.position + fwd * out.nearM, valid);
  // P's axis: the view direction as the light's image plane sees it (the sun: the view direction
  // projected onto the plane perpendicular to the light).
  const glm::vec2 end = toPlane(plane, camera.position + fwd * farM, valid);
  if (!valid) return out;
  glm::vec2 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
  for (const glm::vec2& h : hull) lo = glm::min(lo, h), hi = glm::max(hi, h);
  glm::vec2 axis = light.type == LightType::Directional ? glm::vec2(glm::mat3(base.viewFromWorld) * fwd) : end - top;
  if (light.type != LightType::Directional && glm::length(axis) < kMinAxisImageFraction * glm::length(hi - lo)) return out;
  if (!(glm::length(axis) > 0.0f) || !(out.sinGamma > 0.0f)) return out;
  const glm::vec2 u = glm::normalize(axis);
  const glm::vec2 extent = extentAlong(hull, top, u);
  const float lambda = extent.y - extent.x;  // the region's depth along P's axis, in plane units
  if (!(lambda > 0.0f)) return out;
  // d in metres: the sun's plane is in metres; a spot's is in tangents, so its region is measured
  // along the world direction perpendicular to the ray that the plane's axis stands for.
  if (light.type == LightType::Directional) {
    out.depthM = lambda;
  } else {
    const glm::vec3 across = glm::normalize(fwd - glm::dot(fwd, l) * l);
    float a = std::numeric_limits<float>::max(), b = -a;
    for (const glm::vec3& p : body) a = std::min(a, glm::dot(p, across)), b = std::max(b, glm::dot(p, across));
    out.depthM = b - a;
  }
  out.nOptM = nScale * lispsmOptimalNear(out.nearM, out.depthM, out.sinGamma);
  const float eta = out.nOptM * lambda / std::max(out.depthM, 1e-6f);
  if (!std::isfinite(eta) || eta > kMaxNearOverDepth * lambda) return out;
  out.clipFromWorld = trapezoidAround(hull, top, u, eta, marginFraction) * plane;
  // Every point of the region must keep w > 0 (the GPU clips w <= 0 away).
  for (const glm::vec3& p : body)
    if (!((out.clipFromWorld * glm::vec4(p, 1.0f)).w > 0.0f)) return out;
  out.degenerate = false;
  return out;
}

LightSpacePerspectiveProjection::LightSpacePerspectiveProjection() : Projection(kParams) {}

LightFrusta LightSpacePerspectiveProjection::computeFrusta(const Camera& camera, float aspect, const Light& light,
                                                           const SceneExtent& scene, int mapSize) const {
  const float marginFraction = param("lispsm.marginTexels") / static_cast<float>(mapSize);
  const ViewRegion region = wholeViewRegion(camera, aspect, light, scene);
  LightFrusta f;
  f.views.push_back(fitLightView(scene, light, region.body, region.casters, marginFraction));
  // The casters lie on the receivers' rays toward the light: the same image in the light's plane,
  // so the warp is fitted to the receivers alone.
  const LispsmWarp warp =
      computeLispsmWarp(camera, light, region.body, f.views.front(), param("lispsm.nScale"), marginFraction);
  if (warp.degenerate) return f;  // the unwarped fit: what the warp tends to as n_opt grows
  f.views.front().clipFromWorld = warp.clipFromWorld;
  f.views.front().warped = true;
  return f;
}

}  // namespace penumbra
