#pragma once
// Small geometry types shared by the scene, the projections and the reference.
#include <glm/glm.hpp>
#include <array>
#include <limits>

namespace penumbra {

struct Aabb {
  glm::vec3 lo{std::numeric_limits<float>::max()};
  glm::vec3 hi{-std::numeric_limits<float>::max()};

  bool empty() const { return lo.x > hi.x || lo.y > hi.y || lo.z > hi.z; }
  void extend(const glm::vec3& p) { lo = glm::min(lo, p); hi = glm::max(hi, p); }
  void extend(const Aabb& b) { if (!b.empty()) { extend(b.lo); extend(b.hi); } }
  glm::vec3 center() const { return 0.5f * (lo + hi); }
  glm::vec3 size() const { return hi - lo; }
  float radius() const { return 0.5f * glm::length(hi - lo); }
  std::array<glm::vec3, 8> corners() const {
    return {glm::vec3{lo.x, lo.y, lo.z}, {hi.x, lo.y, lo.z}, {lo.x, hi.y, lo.z}, {hi.x, hi.y, lo.z},
            {lo.x, lo.y, hi.z}, {hi.x, lo.y, hi.z}, {lo.x, hi.y, hi.z}, {hi.x, hi.y, hi.z}};
  }
  /// The box around this box's corners after an affine transform.
  Aabb transformed(const glm::mat4& m) const {
    Aabb r;
    if (empty()) return r;
    for (const glm::vec3& c : corners()) r.extend(glm::vec3(m * glm::vec4(c, 1.0f)));
    return r;
  }
  bool contains(const glm::vec3& p, float eps = 0.0f) const {
    return glm::all(glm::greaterThanEqual(p, lo - eps)) && glm::all(glm::lessThanEqual(p, hi + eps));
  }
};

}  // namespace penumbra
