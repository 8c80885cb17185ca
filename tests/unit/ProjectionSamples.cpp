#include "ProjectionSamples.h"

#include "techniques/projections/LightSpace.h"

#include <algorithm>
#include <random>

namespace penumbra::test {

std::vector<glm::vec3> visibleSurfaceSamples(const Scene& scene, float aspect, int count, uint32_t seed) {
  struct Tri { glm::vec3 a, b, c; };
  std::vector<Tri> tris;
  std::vector<float> cumulative;
  float total = 0.0f;
  const glm::mat4 clip = scene.camera.clipFromView(aspect) * scene.camera.viewFromWorld();
  const float farM = shadowFarDistance(scene.camera, scene.extent());
  for (const Object& o : scene.objects) {
    const Mesh& m = scene.meshes[o.mesh];
    for (size_t i = 0; i + 2 < m.indices.size(); i += 3) {
      Tri t{glm::vec3(o.worldFromObject * glm::vec4(m.positions[m.indices[i]], 1.0f)),
            glm::vec3(o.worldFromObject * glm::vec4(m.positions[m.indices[i + 1]], 1.0f)),
            glm::vec3(o.worldFromObject * glm::vec4(m.positions[m.indices[i + 2]], 1.0f))};
      total += 0.5f * glm::length(glm::cross(t.b - t.a, t.c - t.a));
      tris.push_back(t);
      cumulative.push_back(total);
    }
  }
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::vector<glm::vec3> out;
  for (int tries = 0; tries < count * 400 && static_cast<int>(out.size()) < count; ++tries) {
    const size_t k = static_cast<size_t>(std::lower_bound(cumulative.begin(), cumulative.end(), u(rng) * total) - cumulative.begin());
    const Tri& t = tris[std::min(k, tris.size() - 1)];
    float r1 = u(rng), r2 = u(rng);
    if (r1 + r2 > 1.0f) { r1 = 1.0f - r1; r2 = 1.0f - r2; }
    const glm::vec3 p = t.a + r1 * (t.b - t.a) + r2 * (t.c - t.a);
    const glm::vec4 c = clip * glm::vec4(p, 1.0f);
    const float depth = -(scene.camera.viewFromWorld() * glm::vec4(p, 1.0f)).z;
    if (c.w <= 0.0f || depth > farM || depth < scene.camera.nearM) continue;
    if (std::abs(c.x / c.w) > 1.0f || std::abs(c.y / c.w) > 1.0f) continue;
    out.push_back(p);
  }
  return out;
}

}  // namespace penumbra::test
