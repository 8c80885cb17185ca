#include "EngineTruth.h"

#include "TestGeometry.h"

#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>

namespace penumbra::test::engine {
namespace {

EngineMesh ground() {
  constexpr float kHalfM = 9.0f;
  EngineMesh m;
  for (const glm::vec2 c : {glm::vec2(-1, -1), glm::vec2(1, -1), glm::vec2(1, 1), glm::vec2(-1, 1)})
    m.vertices.push_back({glm::vec3(c * kHalfM, 0.0f), glm::vec3(0, 0, 1)});
  m.indices = {0, 1, 2, 0, 2, 3};
  m.caster = false;  // the engine leaves its ground out of the casters
  return m;
}

EngineMesh box(const glm::vec3& half, const glm::mat4& model) {
  EngineMesh m;
  m.worldFromObject = model;
  for (int axis = 0; axis < 3; ++axis)
    for (const float side : {-1.0f, 1.0f}) {
      glm::vec3 n(0.0f);
      n[axis] = side;
      const glm::vec3 u = glm::vec3(n.y, n.z, n.x), v = glm::cross(n, u);
      const auto base = static_cast<uint32_t>(m.vertices.size());
      for (const glm::vec2 c : {glm::vec2(-1, -1), glm::vec2(1, -1), glm::vec2(1, 1), glm::vec2(-1, 1)})
        m.vertices.push_back({(n + u * c.x + v * c.y) * half, n});
      for (const uint32_t i : {0u, 1u, 2u, 0u, 2u, 3u}) m.indices.push_back(base + i);
    }
  return m;
}

EngineMesh sphere(float radius, const glm::vec3& centre) {
  constexpr int kSlices = 24, kStacks = 12;
  EngineMesh m;
  m.worldFromObject = glm::translate(glm::mat4(1.0f), centre);
  for (int j = 0; j <= kStacks; ++j)
    for (int i = 0; i <= kSlices; ++i) {
      const float theta = glm::pi<float>() * static_cast<float>(j) / kStacks, phi = glm::two_pi<float>() * static_cast<float>(i) / kSlices;
      const glm::vec3 n(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
      m.vertices.push_back({n * radius, n});
    }
  for (int j = 0; j < kStacks; ++j)
    for (int i = 0; i < kSlices; ++i) {
      const auto a = static_cast<uint32_t>(j * (kSlices + 1) + i), b = a + kSlices + 1;
      for (const uint32_t k : {a, b, a + 1, a + 1, b, b + 1}) m.indices.push_back(k);
    }
  return m;
}

// ---- the CPU ray cast ---------------------------------------------------------------------

struct Triangle {
  glm::vec3 a, b, c;
  int object;
};

struct Hit {
  float t = 1e30f;
  int object = -1;
  glm::vec3 normal{0.0f};
};

Hit castRay(const std::vector<Triangle>& tris, const glm::vec3& o, const glm::vec3& d, float tMax) {
  Hit best;
  best.t = tMax;
  for (const Triangle& tri : tris) {
    const float t = rayTriangle(o, d, tri.a, tri.b, tri.c);
    if (t > 0.0f && t < best.t) best = {t, tri.object, glm::normalize(glm::cross(tri.b - tri.a, tri.c - tri.a))};
  }
  return best;
}

std::vector<Triangle> worldTriangles(const std::vector<EngineMesh>& meshes) {
  std::vector<Triangle> out;
  for (size_t m = 0; m < meshes.size(); ++m)
    for (size_t i = 0; i + 2 < meshes[m].indices.size(); i += 3) {
      const auto at = [&](size_t k) { return glm::vec3(meshes[m].worldFromObject * glm::vec4(meshes[m].vertices[meshes[m].indices[i + k]].position, 1.0f)); };
      out.push_back({at(0), at(1), at(2), static_cast<int>(m)});
    }
  return out;
}

}  // namespace

std::vector<EngineMesh> engineScene() {
  glm::mat4 turned = glm::translate(glm::mat4(1.0f), glm::vec3(-0.5f, 0.3f, 1.1f));
  turned = glm::rotate(turned, 0.5f, glm::vec3(0, 0, 1));
  turned = glm::rotate(turned, 0.3f, glm::vec3(1, 0, 0));
  return {ground(), box(glm::vec3(0.7f, 0.5f, 0.6f), turned), sphere(0.55f, glm::vec3(1.8f, -1.2f, 1.6f))};
}

Truth rayCast(const std::vector<EngineMesh>& meshes, const glm::mat4& clipFromWorld, glm::vec2 ndcDepths,
              const std::vector<Light>& lights) {
  const std::vector<Triangle> tris = worldTriangles(meshes), casters = [&] {
    std::vector<Triangle> c;
    for (const Triangle& t : tris)
      if (meshes[static_cast<size_t>(t.object)].caster) c.push_back(t);
    return c;
  }();
  const glm::mat4 worldFromClip = glm::inverse(clipFromWorld);
  Truth truth;
  truth.object.assign(kW * kH, -1);
  truth.v.assign(lights.size(), std::vector<float>(kW * kH, 1.0f));
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const glm::vec2 ndc((x + 0.5f) / kW * 2.0f - 1.0f, (y + 0.5f) / kH * 2.0f - 1.0f);
      const glm::vec4 p0 = worldFromClip * glm::vec4(ndc, ndcDepths.x, 1.0f), p1 = worldFromClip * glm::vec4(ndc, ndcDepths.y, 1.0f);
      const glm::vec3 o = glm::vec3(p0) / p0.w, d = glm::normalize(glm::vec3(p1) / p1.w - o);
      const Hit hit = castRay(tris, o, d, 1e30f);
      const size_t i = static_cast<size_t>(y) * kW + static_cast<size_t>(x);
      if (hit.object < 0) continue;
      truth.object[i] = hit.object;
      const glm::vec3 n = glm::dot(hit.normal, d) < 0.0f ? hit.normal : -hit.normal;  // facing the camera
      const glm::vec3 p = o + hit.t * d + n * 1e-3f;
      for (size_t l = 0; l < lights.size(); ++l) {
        const Light& light = lights[l];
        glm::vec3 toLight = -glm::normalize(light.direction);
        float tMax = 1e30f;
        if (isPositional(light)) {
          toLight = light.position - p;
          tMax = glm::length(toLight);
          toLight /= tMax;
        }
        const bool lit = glm::dot(n, toLight) > 0.0f && castRay(casters, p, toLight, tMax).object < 0;
        truth.v[l][i] = lit ? 1.0f : 0.0f;
      }
    }
  return truth;
}

Agreement compare(const std::vector<float>& v, const Truth& truth, size_t light) {
  Agreement a;
  const std::vector<float>& ref = truth.v[light];
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const size_t i = static_cast<size_t>(y) * kW + static_cast<size_t>(x);
      if (truth.object[i] < 0) continue;
      bool band = false;
      for (int dy = -kEdgeBandPx; dy <= kEdgeBandPx && !band; ++dy)
        for (int dx = -kEdgeBandPx; dx <= kEdgeBandPx && !band; ++dx) {
          const int qx = std::clamp(x + dx, 0, kW - 1), qy = std::clamp(y + dy, 0, kH - 1);
          const size_t q = static_cast<size_t>(qy) * kW + static_cast<size_t>(qx);
          band = truth.object[q] != truth.object[i] || ref[q] != ref[i];
        }
      if (band) continue;
      ++a.compared;
      a.shadowed += ref[i] < 0.5f ? 1 : 0;
      a.differing += (v[i] >= 0.5f) != (ref[i] >= 0.5f) ? 1 : 0;
    }
  return a;
}

}  // namespace penumbra::test::engine
