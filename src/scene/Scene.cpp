#include <penumbra/Error.h>
#include <penumbra/Scene.h>

#include <fmt/format.h>
#include <glm/gtc/matrix_transform.hpp>

#include <cmath>

namespace penumbra {

glm::mat4 Camera::viewFromWorld() const { return glm::lookAt(position, target, up); }

glm::mat4 Camera::clipFromView(float aspect) const {
  // Reversed-Z with [0,1] depth: z_clip/w_clip = near / z_dist → 1 at the near plane, 0 at
  // infinity. The far plane is not needed for precision; an infinite far keeps it simple.
  const float f = 1.0f / std::tan(0.5f * fovYRad);
  glm::mat4 m(0.0f);
  m[0][0] = f / aspect;
  m[1][1] = f;
  m[2][3] = -1.0f;
  m[3][2] = nearM;
  return m;
}

const Light& Scene::light() const {
  PN_CHECK(!lights.empty(), fmt::format("scene '{}' has no light", name));
  return lights.front();
}

Aabb Scene::bounds() const {
  Aabb b;
  for (const Object& o : objects) b.extend(meshes[o.mesh].bounds().transformed(o.worldFromObject));
  return b;
}

Aabb Scene::casterBounds() const {
  Aabb b;
  for (const Object& o : objects)
    if (o.castsShadow) b.extend(meshes[o.mesh].bounds().transformed(o.worldFromObject));
  return b;
}

SceneExtent Scene::extent() const {
  SceneExtent e;
  e.bodies.reserve(objects.size());
  for (const Object& o : objects) e.bodies.push_back({meshes[o.mesh].bounds().transformed(o.worldFromObject), o.castsShadow});
  return e;
}

Aabb SceneExtent::bounds() const {
  Aabb b;
  for (const Body& body : bodies) b.extend(body.bounds);
  return b;
}

Aabb SceneExtent::casterBounds() const {
  Aabb b;
  for (const Body& body : bodies)
    if (body.castsShadow) b.extend(body.bounds);
  return b;
}

size_t Scene::triangleCount() const {
  size_t n = 0;
  for (const Object& o : objects) n += meshes[o.mesh].triangleCount();
  return n;
}

void Scene::validate() const {
  const std::string where = sourceFile.empty() ? name : sourceFile.string();
  PN_CHECK(!objects.empty(), fmt::format("{}: the scene has no objects", where));
  PN_CHECK(!lights.empty(), fmt::format("{}: the scene has no light", where));
  for (const Mesh& m : meshes) {
    PN_CHECK(m.indices.size() % 3 == 0, fmt::format("{}: mesh '{}': index count {} is not a multiple of 3", where, m.name, m.indices.size()));
    for (uint32_t i : m.indices)
      PN_CHECK(i < m.vertices.size(), fmt::format("{}: mesh '{}': index {} out of range ({} vertices)", where, m.name, i, m.vertices.size()));
    for (const Vertex& v : m.vertices)
      PN_CHECK(std::isfinite(v.position.x) && std::isfinite(v.position.y) && std::isfinite(v.position.z),
               fmt::format("{}: mesh '{}': a vertex position is not finite", where, m.name));
  }
  for (const Object& o : objects) {
    PN_CHECK(o.mesh < meshes.size(), fmt::format("{}: object '{}': mesh index out of range", where, o.name));
    PN_CHECK(o.material < materials.size(), fmt::format("{}: object '{}': material index out of range", where, o.name));
  }
  for (const Material& m : materials)
    PN_CHECK(m.baseColorTexture < static_cast<int>(images.size()),
             fmt::format("{}: material '{}': texture index out of range", where, m.name));
  PN_CHECK(triangleCount() > 0, fmt::format("{}: the scene has zero triangles", where));
  for (const Light& l : lights) {
    PN_CHECK(glm::length(l.direction) > 0.0f, fmt::format("{}: a light has a zero direction", where));
    PN_CHECK(l.size >= 0.0f, fmt::format("{}: a light has a negative size", where));
  }
}

}  // namespace penumbra
