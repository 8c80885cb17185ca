#pragma once
// The engine of gl.Engine.* (EngineTest.cpp), the part that is not GL: its scene (a Z-up world of
// 24-byte vertices: a ground, a box turned about two axes, a floating sphere) and the truth its
// shadows are checked against, an exact CPU ray cast of the same triangles from each pixel's
// centre, with the comparison that leaves out a band around edges and silhouettes.
#include <penumbra/Light.h>

#include <glm/glm.hpp>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace penumbra::test::engine {

constexpr int kW = 160, kH = 120;
// A pixel is compared when nothing changes within this many pixels of it: the shadow edge and
// the silhouettes are where a map's texels and a pixel's centre may fairly disagree.
constexpr int kEdgeBandPx = 2;

struct EngineVertex {
  glm::vec3 position, normal;
};
static_assert(sizeof(EngineVertex) == 24, "the engine's 24-byte vertex");

struct EngineMesh {
  std::vector<EngineVertex> vertices;
  std::vector<uint32_t> indices;
  glm::mat4 worldFromObject{1.0f};
  bool caster = true;
};

/// The engine's scene: a ground (not a caster), a box turned about two axes standing above it, a
/// floating sphere.
std::vector<EngineMesh> engineScene();

/// The ray cast's truth for each pixel (row 0 = bottom) and each light: the object seen (−1:
/// background) and V (1 = the light reaches the surface's point, 0 = it does not or it faces away).
struct Truth {
  std::vector<int> object;
  std::vector<std::vector<float>> v;  ///< per light
};
/// Rays through each pixel's centre between clip depths ndcDepths.x and .y of clipFromWorld.
Truth rayCast(const std::vector<EngineMesh>& meshes, const glm::mat4& clipFromWorld, glm::vec2 ndcDepths,
              const std::vector<Light>& lights);

struct Agreement {
  size_t compared = 0, differing = 0, shadowed = 0;
  double differingPct() const { return compared ? 100.0 * static_cast<double>(differing) / static_cast<double>(compared) : 100.0; }
};
/// Pixels of surfaces whose object and reference V are the same within kEdgeBandPx, compared.
Agreement compare(const std::vector<float>& v, const Truth& truth, size_t light);

}  // namespace penumbra::test::engine
