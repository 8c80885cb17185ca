#pragma once
// Known answers for the reference's tests (unit and GL). A square occluder at height h over a
// plane under a spherical light of radius R at height H: the visible fraction of the light from a
// ground point near the middle of an edge is a spherical cap cut by the plane through the point
// and the edge, which has a closed form. A plane that is the only caster: V = 1 wherever it faces
// the light. And G-buffers made of points, without a rasteriser.
#include <penumbra/Reference.h>
#include <penumbra/Scene.h>

#include <glm/glm.hpp>
#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <vector>

namespace penumbra::test {

constexpr float kLightHeightM = 4.0f;     // H: sphere centre above the ground
constexpr float kLightRadiusM = 0.4f;     // R
constexpr float kOccluderHeightM = 1.0f;  // h: the square's height above the ground
constexpr float kOccluderSizeM = 1.0f;    // the square spans x, z in [-0.5, 0.5]
constexpr float kEdgeX = 0.5f * kOccluderSizeM;

inline ReferenceOptions quiet(int samples, uint32_t seed = 0) {
  ReferenceOptions o;
  o.samples = samples;
  o.seed = seed;
  o.progress = false;
  o.useCache = false;
  return o;
}

/// One row of points with a common normal, albedo 1: a G-buffer without a rasteriser.
inline GBufferData pointsGBuffer(const std::vector<glm::vec3>& points, glm::vec3 normal = {0, 1, 0}) {
  GBufferData g;
  g.width = static_cast<int>(points.size());
  g.height = 1;
  for (const glm::vec3& p : points) {
    g.position.emplace_back(p, 1.0f);
    g.geoNormal.emplace_back(normal, 0.0f);
    g.normal.emplace_back(normal, 0.0f);
    g.albedo.emplace_back(1.0f);
  }
  return g;
}

/// The sphere light kLightHeightM above `groundM`, pointing down.
inline Light sphereLight(float radiusM = kLightRadiusM, const glm::vec3& groundM = glm::vec3(0.0f)) {
  Light l;
  l.type = LightType::Spot;
  l.position = groundM + glm::vec3(0.0f, kLightHeightM, 0.0f);
  l.direction = {0.0f, -1.0f, 0.0f};
  l.coneAngleRad = 1.2f;
  l.size = radiusM;
  return l;
}

/// Solid angle of the part of a cap (half angle α) beyond a great circle at angular distance
/// β ∈ [0, α] from the cap's centre: 2[acos(sin β / sin α) − cos α · acos(tan β / tan α)].
inline double capSegment(double alpha, double beta) {
  return 2.0 * (std::acos(std::sin(beta) / std::sin(alpha)) - std::cos(alpha) * std::acos(std::tan(beta) / std::tan(alpha)));
}

/// Exact visible fraction of the sphere light from ground point p, shadowed by the square's
/// edge x = kEdgeX (valid near z = 0, where the light's cone meets no other edge). p is relative
/// to the ground point under the light. A box of height kOccluderHeightM standing on the ground
/// under the square gives the same answer outside its footprint: its top edge is the silhouette.
inline double analyticVisibility(glm::dvec3 p) {
  const glm::dvec3 centre{0.0, kLightHeightM, 0.0};
  const double d = glm::length(centre - p);
  const glm::dvec3 axis = (centre - p) / d;
  const double alpha = std::asin(kLightRadiusM / d);
  glm::dvec3 n = glm::normalize(glm::cross(glm::dvec3(kEdgeX, kOccluderHeightM, 0.0) - p, glm::dvec3(0, 0, 1)));
  if (glm::dot(glm::dvec3(0.0, kOccluderHeightM, 0.0) - p, n) < 0.0) n = -n;  // n points into the occluder
  const double beta = std::asin(glm::dot(axis, n));  // > 0: the cap's centre is hidden
  if (beta >= alpha) return 0.0;
  if (beta <= -alpha) return 1.0;
  const double cap = glm::two_pi<double>() * (1.0 - std::cos(alpha));
  const double hidden = beta < 0.0 ? capSegment(alpha, -beta) : cap - capSegment(alpha, beta);
  return 1.0 - hidden / cap;
}

/// A 40 m plane of 16 × 16 cells (shared edges), tilted, 10 km from the origin (float spacing
/// 1 mm there), the sun 1° above it, seen from 8 m away. It is the only caster: its truth is
/// V = 1 everywhere it faces the sun, and a reference that hits the surface its rays leave
/// (acne) darkens some of it.
inline Scene grazingPlaneFarOut(float sunSizeRad) {
  const glm::vec3 centreM{10000.0f, 35.0f, -10000.0f};
  const glm::mat4 worldFromObject = glm::rotate(glm::rotate(glm::translate(glm::mat4(1.0f), centreM), 0.4f, {1, 0, 0}),
                                                0.3f, {0, 0, 1});
  constexpr int kCells = 16;
  constexpr float kSizeM = 40.0f, kElevationRad = glm::radians(1.0f);
  Scene s;
  s.name = "grazing plane 10 km out";
  addObject(s, "plane", makeGrid(kSizeM, kSizeM, kCells), glm::vec3(0.8f), worldFromObject);
  const glm::vec3 n = glm::normalize(glm::mat3(worldFromObject) * glm::vec3(0, 1, 0));
  const glm::vec3 tangent = glm::normalize(glm::mat3(worldFromObject) * glm::vec3(1, 0, 0.3f));
  Light sun;
  sun.type = LightType::Directional;
  sun.direction = -(std::cos(kElevationRad) * tangent + std::sin(kElevationRad) * n);
  sun.size = sunSizeRad;
  s.lights = {sun};
  s.camera.position = centreM + 5.0f * n - 6.0f * tangent;
  s.camera.target = centreM + 2.0f * tangent;
  s.camera.up = n;
  return s;
}

}  // namespace penumbra::test
