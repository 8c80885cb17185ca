// Procedural shapes with outward normals and counter-clockwise front faces.
#include <penumbra/Error.h>
#include <penumbra/Scene.h>

#include <glm/gtc/constants.hpp>

#include <algorithm>

namespace penumbra {
namespace {

void addQuad(Mesh& m, glm::vec3 origin, glm::vec3 du, glm::vec3 dv, glm::vec2 uvScale = {1, 1}) {
  const glm::vec3 n = glm::normalize(glm::cross(du, dv));
  const uint32_t base = m.addVertex(origin, n, {0, 0});
  m.addVertex(origin + du, n, {uvScale.x, 0});
  m.addVertex(origin + du + dv, n, uvScale);
  m.addVertex(origin + dv, n, {0, uvScale.y});
  for (uint32_t i : {0u, 1u, 2u, 0u, 2u, 3u}) m.indices.push_back(base + i);
}

// A surface of revolution around +Y from a profile of (radius, y, normal r, normal y) rings.
void addLathe(Mesh& m, const std::vector<glm::vec4>& ringsPos, const std::vector<glm::vec2>& ringsNormal, int slices) {
  const auto base = static_cast<uint32_t>(m.vertexCount());
  const int rings = static_cast<int>(ringsPos.size());
  for (int r = 0; r < rings; ++r) {
    for (int s = 0; s <= slices; ++s) {
      const float a = glm::two_pi<float>() * static_cast<float>(s) / static_cast<float>(slices);
      const glm::vec2 dir{std::cos(a), -std::sin(a)};
      const glm::vec3 p{ringsPos[r].x * dir.x, ringsPos[r].y, ringsPos[r].x * dir.y};
      glm::vec3 n{ringsNormal[r].x * dir.x, ringsNormal[r].y, ringsNormal[r].x * dir.y};
      m.addVertex(p, glm::normalize(n), {static_cast<float>(s) / static_cast<float>(slices), ringsPos[r].z});
    }
  }
  const auto stride = static_cast<uint32_t>(slices + 1);
  for (int r = 0; r + 1 < rings; ++r) {
    for (uint32_t s = 0; s < static_cast<uint32_t>(slices); ++s) {
      const uint32_t a = base + static_cast<uint32_t>(r) * stride + s, b = a + 1, c = a + stride, d = c + 1;
      if (ringsPos[r].x > 0.0f || ringsPos[r + 1].x > 0.0f) {
        for (uint32_t i : {a, b, d, a, d, c}) m.indices.push_back(i);
      }
    }
  }
}

// A flat disk at height y facing up (+1) or down (-1).
void addDisk(Mesh& m, float radius, float y, float facing, int slices) {
  const glm::vec3 n{0, facing, 0};
  const uint32_t centre = m.addVertex({0, y, 0}, n, {0.5f, 0.5f});
  for (int s = 0; s <= slices; ++s) {
    const float a = glm::two_pi<float>() * static_cast<float>(s) / static_cast<float>(slices);
    m.addVertex({radius * std::cos(a), y, -radius * std::sin(a)}, n, {0.5f + 0.5f * std::cos(a), 0.5f + 0.5f * std::sin(a)});
  }
  for (uint32_t s = 0; s < static_cast<uint32_t>(slices); ++s) {
    const uint32_t a = centre + 1 + s, b = a + 1;
    if (facing > 0) { m.indices.insert(m.indices.end(), {centre, a, b}); }
    else { m.indices.insert(m.indices.end(), {centre, b, a}); }
  }
}

}  // namespace

uint32_t Mesh::addVertex(const glm::vec3& position, const glm::vec3& normal, const glm::vec2& uv) {
  positions.push_back(position);
  normals.push_back(normal);
  uvs.push_back(uv);
  return static_cast<uint32_t>(positions.size() - 1);
}

size_t Mesh::byteSize() const {
  return positions.size() * sizeof(glm::vec3) + normals.size() * sizeof(glm::vec3) + uvs.size() * sizeof(glm::vec2) +
         indices.size() * sizeof(uint32_t);
}

Aabb Mesh::bounds() const {
  Aabb b;
  for (const glm::vec3& p : positions) b.extend(p);
  return b;
}

bool Mesh::hasArea() const {
  const size_t n = positions.size();
  for (size_t t = 0; t + 2 < indices.size(); t += 3) {
    if (indices[t] >= n || indices[t + 1] >= n || indices[t + 2] >= n) continue;
    const glm::vec3 a = positions[indices[t]], b = positions[indices[t + 1]], c = positions[indices[t + 2]];
    if (glm::length(glm::cross(b - a, c - a)) > 0.0f) return true;
  }
  return false;
}

Mesh makePlane(float sizeX, float sizeZ) {
  Mesh m;
  m.name = "plane";
  addQuad(m, {-0.5f * sizeX, 0, 0.5f * sizeZ}, {sizeX, 0, 0}, {0, 0, -sizeZ}, {sizeX, sizeZ});
  return m;
}

Mesh makeGrid(float sizeX, float sizeZ, int cells) {
  PN_CHECK(cells >= 1, "makeGrid: at least one cell");
  Mesh m;
  m.name = "grid";
  const float n = static_cast<float>(cells);
  // makePlane's layout: uv (0, 0) at (−x, +z), u along +x, v along −z.
  for (int j = 0; j <= cells; ++j)
    for (int i = 0; i <= cells; ++i) {
      const glm::vec2 uv{static_cast<float>(i) / n, static_cast<float>(j) / n};
      m.addVertex({(uv.x - 0.5f) * sizeX, 0.0f, (0.5f - uv.y) * sizeZ}, {0, 1, 0}, uv);
    }
  const auto at = [cells](int i, int j) { return static_cast<uint32_t>(j * (cells + 1) + i); };
  for (int j = 0; j < cells; ++j)
    for (int i = 0; i < cells; ++i)
      m.indices.insert(m.indices.end(), {at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j), at(i + 1, j + 1), at(i, j + 1)});
  return m;
}

Mesh makeBox(const glm::vec3& size) {
  Mesh m;
  m.name = "box";
  const glm::vec3 h = 0.5f * size;
  const glm::vec3 X{size.x, 0, 0}, Y{0, size.y, 0}, Z{0, 0, size.z};
  addQuad(m, {-h.x, -h.y, h.z}, X, Y);     // +Z
  addQuad(m, {h.x, -h.y, -h.z}, -X, Y);    // -Z
  addQuad(m, {h.x, -h.y, h.z}, -Z, Y);     // +X
  addQuad(m, {-h.x, -h.y, -h.z}, Z, Y);    // -X
  addQuad(m, {-h.x, h.y, h.z}, X, -Z);     // +Y
  addQuad(m, {-h.x, -h.y, -h.z}, X, Z);    // -Y
  return m;
}

Mesh makeSphere(float radius, int slices, int stacks) {
  Mesh m;
  m.name = "sphere";
  std::vector<glm::vec4> pos;
  std::vector<glm::vec2> nrm;
  for (int i = 0; i <= stacks; ++i) {
    const float phi = glm::pi<float>() * (1.0f - static_cast<float>(i) / static_cast<float>(stacks));  // from the bottom
    // sin(pi) is -8.7e-8 in float: clamped, the bottom pole is one point instead of a tiny
    // mirrored ring whose sliver triangles wind clockwise.
    const float r = std::max(0.0f, std::sin(phi)), y = std::cos(phi);
    pos.push_back({radius * r, radius * y, static_cast<float>(i) / static_cast<float>(stacks), 0});
    nrm.push_back({r, y});
  }
  addLathe(m, pos, nrm, slices);
  return m;
}

Mesh makeCylinder(float radius, float height, int slices) {
  Mesh m;
  m.name = "cylinder";
  addLathe(m, {{radius, 0, 0, 0}, {radius, height, 1, 0}}, {{1, 0}, {1, 0}}, slices);
  addDisk(m, radius, height, 1.0f, slices);
  addDisk(m, radius, 0.0f, -1.0f, slices);
  return m;
}

Mesh makeCone(float radius, float height, int slices) {
  Mesh m;
  m.name = "cone";
  const glm::vec2 n = glm::normalize(glm::vec2(height, radius));
  // The apex ring has radius 0; a tiny radius keeps its normals defined.
  addLathe(m, {{radius, 0, 0, 0}, {0.0f, height, 1, 0}}, {n, n}, slices);
  addDisk(m, radius, 0.0f, -1.0f, slices);
  return m;
}

uint32_t addObject(Scene& scene, std::string name, Mesh mesh, const glm::vec3& color,
                   const glm::mat4& worldFromObject, bool castsShadow) {
  Material material;
  material.name = name;
  material.baseColor = color;
  scene.meshes.push_back(std::move(mesh));
  scene.materials.push_back(material);
  Object o;
  o.name = std::move(name);
  o.mesh = static_cast<uint32_t>(scene.meshes.size() - 1);
  o.material = static_cast<uint32_t>(scene.materials.size() - 1);
  o.worldFromObject = worldFromObject;
  o.castsShadow = castsShadow;
  scene.objects.push_back(o);
  return static_cast<uint32_t>(scene.objects.size() - 1);
}

}  // namespace penumbra
