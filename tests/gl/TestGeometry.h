#pragma once
// CPU ray casting against a scene's triangles, for tests that need a geometric truth without
// the Embree reference: is the segment from a point toward the light blocked by a caster?
#include <penumbra/Scene.h>

#include <vector>

namespace penumbra::test {

class CasterTriangles {
public:
  explicit CasterTriangles(const Scene& scene);
  /// True if a ray from `origin` along unit `dir` hits a caster triangle within (tMin, tMax).
  bool blocked(const glm::vec3& origin, const glm::vec3& dir, float tMin, float tMax) const {
    return nearestHit(origin, dir, tMin, tMax) < tMax;
  }
  /// Distance to the nearest caster hit in (tMin, tMax), or tMax if none.
  float nearestHit(const glm::vec3& origin, const glm::vec3& dir, float tMin, float tMax) const;
  /// Occlusion of the centre of a hard light, sampled at `origin` and at points `jitterM` away
  /// in the surface plane (4 around it, or 2 along `onlyAlong` when it is non-zero):
  /// 1 = all blocked, 0 = none blocked, 0.5 = mixed (near an edge).
  float robustOcclusion(const Scene& scene, const glm::vec3& origin, const glm::vec3& normal, float jitterM,
                        const glm::vec3& onlyAlong = glm::vec3(0.0f)) const;

private:
  std::vector<glm::vec3> mV;  // three per triangle, world space
};

}  // namespace penumbra::test
