#pragma once
// CPU ray casting against a scene's triangles, for tests that need a geometric truth without
// the Embree reference: is the segment from a point toward the light blocked by a caster? And
// the floor pixels that are robustly in or out of a hard shadow, picked with it.
#include "GlFixture.h"

#include <penumbra/Renderer.h>
#include <penumbra/Scene.h>

#include <cstdint>
#include <span>
#include <vector>

namespace penumbra::test {

/// Where a ray from `o` along `d` meets triangle (a, b, c) (Möller–Trumbore): the distance in
/// units of |d|, or -1 when it misses (or runs parallel to the triangle's plane).
float rayTriangle(const glm::vec3& o, const glm::vec3& d, const glm::vec3& a, const glm::vec3& b, const glm::vec3& c);

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

/// A G-buffer position on the floor plane y = 0 (within 1 mm) of the built-in scenes.
bool onFloor(const glm::vec4& position);

struct FloorProbes {
  std::vector<size_t> shadowed, lit;  ///< pixel indices
};
/// Up to perKind floor pixels of each kind, picked at random (seeded) in at most maxTries picks,
/// whose centre and 4 points jitterM around it are all occluded / all unoccluded from the light's
/// centre: far enough from any shadow edge to be dark / lit for a small light.
FloorProbes floorProbes(const Scene& scene, const GBufferData& g, size_t perKind, float jitterM, uint32_t seed,
                        int maxTries);

/// A mask (1 = in) of the pixels of `mask` that lie on the floor within bandM, horizontally, of
/// a caster: where casters stand on the floor (contacts). Found by horizontal rays in 8
/// directions from a little above the floor.
std::vector<uint8_t> floorNearCasters(const Scene& scene, const GBufferData& g, std::span<const uint8_t> mask,
                                      float bandM);

/// Peter-panning: a bias moves receivers toward the light, so floor points just behind a
/// caster's contact read lit. A truly shadowed floor point whose occluder is t metres away along
/// the sun's ray is lit only if the bias exceeds t; seen in the map's plane that detachment spans
/// t · tan(elevation). The largest such span among wrongly lit (V >= 0.5) floor pixels of `r`
/// (a sun scene, one uniform view of mapSize texels) is the gap, in texels.
double contactGapTexels(const Scene& scene, const RenderResult& r, int mapSize);

/// Acne: the fraction of unoccluded floor pixels of `r` that the filter darkens (V < 0.5), read
/// on every third pixel.
double acneFraction(const Scene& scene, const RenderResult& r);

}  // namespace penumbra::test
