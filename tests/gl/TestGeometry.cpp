#include "TestGeometry.h"

#include <glm/gtc/constants.hpp>

#include <cmath>
#include <random>

namespace penumbra::test {

CasterTriangles::CasterTriangles(const Scene& scene) {
  for (const Object& o : scene.objects) {
    if (!o.castsShadow) continue;
    const Mesh& m = scene.meshes[o.mesh];
    for (uint32_t i : m.indices) mV.push_back(glm::vec3(o.worldFromObject * glm::vec4(m.positions[i], 1.0f)));
  }
}

float rayTriangle(const glm::vec3& o, const glm::vec3& d, const glm::vec3& a, const glm::vec3& b, const glm::vec3& c) {
  const glm::vec3 e1 = b - a, e2 = c - a;
  const glm::vec3 p = glm::cross(d, e2);
  const float det = glm::dot(e1, p);
  if (std::abs(det) < 1e-12f) return -1.0f;
  const float inv = 1.0f / det;
  const glm::vec3 s = o - a;
  const float u = glm::dot(s, p) * inv;
  if (u < 0.0f || u > 1.0f) return -1.0f;
  const glm::vec3 q = glm::cross(s, e1);
  const float v = glm::dot(d, q) * inv;
  if (v < 0.0f || u + v > 1.0f) return -1.0f;
  return glm::dot(e2, q) * inv;
}

float CasterTriangles::nearestHit(const glm::vec3& o, const glm::vec3& d, float tMin, float tMax) const {
  float nearest = tMax;
  for (size_t i = 0; i + 2 < mV.size(); i += 3) {
    const float t = rayTriangle(o, d, mV[i], mV[i + 1], mV[i + 2]);
    if (t > tMin && t < nearest) nearest = t;
  }
  return nearest;
}

float CasterTriangles::robustOcclusion(const Scene& scene, const glm::vec3& origin, const glm::vec3& normal,
                                       float jitterM, const glm::vec3& onlyAlong) const {
  const Light& l = scene.light();
  const glm::vec3 t1 = glm::normalize(glm::cross(normal, std::abs(normal.y) < 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0)));
  const glm::vec3 t2 = glm::cross(normal, t1);
  std::vector<glm::vec3> offsets = {glm::vec3(0), t1 * jitterM, -t1 * jitterM, t2 * jitterM, -t2 * jitterM};
  if (glm::length(onlyAlong) > 0.0f) offsets = {glm::vec3(0), onlyAlong * jitterM, -onlyAlong * jitterM};
  int hits = 0;
  constexpr float kStartM = 1e-3f;  // leave the surface the point lies on
  for (const glm::vec3& off : offsets) {
    const glm::vec3 p = origin + off + normal * kStartM;
    glm::vec3 dir;
    float tMax = 1e30f;
    if (l.type == LightType::Spot) {
      dir = l.position - p;
      tMax = glm::length(dir);
      dir /= tMax;
    } else {
      dir = -l.direction;
    }
    hits += blocked(p, dir, 0.0f, tMax) ? 1 : 0;
  }
  return hits == static_cast<int>(offsets.size()) ? 1.0f : hits == 0 ? 0.0f : 0.5f;
}

bool onFloor(const glm::vec4& p) {
  constexpr float kFloorEpsM = 1e-3f;
  return p.w > 0.5f && std::abs(p.y) < kFloorEpsM;
}

FloorProbes floorProbes(const Scene& scene, const GBufferData& g, size_t perKind, float jitterM, uint32_t seed,
                        int maxTries) {
  CasterTriangles tris(scene);
  FloorProbes out;
  std::mt19937 rng(seed);
  std::uniform_int_distribution<size_t> pick(0, g.position.size() - 1);
  for (int tries = 0; tries < maxTries && (out.shadowed.size() < perKind || out.lit.size() < perKind); ++tries) {
    const size_t i = pick(rng);
    if (!onFloor(g.position[i])) continue;
    const float occ = tris.robustOcclusion(scene, glm::vec3(g.position[i]), {0, 1, 0}, jitterM);
    if (occ == 1.0f && out.shadowed.size() < perKind) out.shadowed.push_back(i);
    else if (occ == 0.0f && out.lit.size() < perKind) out.lit.push_back(i);
  }
  return out;
}

std::vector<uint8_t> floorNearCasters(const Scene& scene, const GBufferData& g, std::span<const uint8_t> mask,
                                      float bandM) {
  constexpr float kRayHeightM = 0.02f;  // above the floor, below any caster's lowest edge
  constexpr int kDirections = 8;
  const CasterTriangles casters(scene);
  std::vector<uint8_t> band(mask.size(), 0);
  for (size_t i = 0; i < band.size(); ++i) {
    if (!mask[i] || !onFloor(g.position[i])) continue;
    const glm::vec3 origin = glm::vec3(g.position[i]) + glm::vec3(0.0f, kRayHeightM, 0.0f);
    for (int d = 0; d < kDirections && !band[i]; ++d) {
      const float a = glm::two_pi<float>() * static_cast<float>(d) / kDirections;
      band[i] = casters.blocked(origin, glm::vec3(std::cos(a), 0.0f, std::sin(a)), 0.0f, bandM) ? 1 : 0;
    }
  }
  return band;
}

double contactGapTexels(const Scene& scene, const RenderResult& r, int mapSize) {
  const ShadowView& view = r.frusta.views.at(0);
  const float texelM = std::max(view.extent.x, view.extent.y) / static_cast<float>(mapSize);
  const glm::vec3 toSun = -scene.light().direction;
  const float tanElevation = toSun.y / glm::length(glm::vec2(toSun.x, toSun.z));
  CasterTriangles tris(scene);
  // Jitter across the light's direction only: keeps the aliased lateral shadow edges out but
  // keeps the points right behind the contact, where peter-panning shows.
  constexpr float kJitterM = 0.04f;
  const glm::vec3 across = glm::normalize(glm::cross(glm::vec3(0, 1, 0), toSun));
  constexpr float kStartM = 1e-3f;
  double gap = 0.0;
  size_t shadowed = 0;
  for (size_t i = 0; i < r.visibility.size(); ++i) {
    const glm::vec3 p(r.gbuffer.position[i]);
    if (!onFloor(r.gbuffer.position[i])) continue;
    if (tris.robustOcclusion(scene, p, {0, 1, 0}, kJitterM, across) != 1.0f) continue;
    ++shadowed;
    if (r.visibility[i] < 0.5f) continue;
    const float t = tris.nearestHit(p + glm::vec3(0, kStartM, 0), toSun, 0.0f, 1e30f);
    gap = std::max(gap, static_cast<double>(t * tanElevation / texelM));
  }
  EXPECT_GT(shadowed, 500u) << "the camera must see the box's shadow";
  return gap;
}

double acneFraction(const Scene& scene, const RenderResult& r) {
  CasterTriangles tris(scene);
  size_t floor = 0, acne = 0;
  for (size_t i = 0; i < r.visibility.size(); i += 3) {  // every third pixel keeps the CPU test fast
    if (!onFloor(r.gbuffer.position[i])) continue;
    if (tris.robustOcclusion(scene, glm::vec3(r.gbuffer.position[i]), {0, 1, 0}, 0.05f) != 0.0f) continue;
    ++floor;
    if (r.visibility[i] < 0.5f) ++acne;
  }
  EXPECT_GT(floor, 1000u);
  return static_cast<double>(acne) / static_cast<double>(std::max<size_t>(floor, 1));
}

}  // namespace penumbra::test
