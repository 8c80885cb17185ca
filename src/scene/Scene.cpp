#include <penumbra/Error.h>
#include <penumbra/Scene.h>

#include <fmt/format.h>
#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>

namespace penumbra {
namespace {
constexpr float kMinViewLengthM = 1e-6f;  // the target closer to the position than this: no view direction
constexpr float kMinSinViewToUp = 1e-4f;  // sine of the angle between view and up: below it, no up in the image

bool finite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }
}  // namespace

std::string Camera::viewProblem() const {
  const glm::vec3 view = target - position;
  if (!finite(view) || !(glm::length(view) >= kMinViewLengthM)) return "the target is the position";
  if (!finite(up) || !(glm::length(up) > 0.0f)) return fmt::format("the up vector ({}, {}, {}) is zero or not finite", up.x, up.y, up.z);
  if (!(glm::length(glm::cross(glm::normalize(view), glm::normalize(up))) >= kMinSinViewToUp))
    return fmt::format("the view is along the up vector ({}, {}, {}): no direction is up in the image", up.x, up.y, up.z);
  return "";
}

glm::mat4 Camera::viewFromWorld() const { return glm::lookAt(position, target, up); }

glm::mat4 Camera::clipFromView(float aspect) const {
  if (orthographic()) {  // reversed-Z over [near, far]: z_clip = (far − z_dist) / (far − near)
    glm::mat4 m(1.0f);
    m[0][0] = 1.0f / (orthoHalfHeightM * aspect);
    m[1][1] = 1.0f / orthoHalfHeightM;
    m[2][2] = 1.0f / (farM - nearM);
    m[3][2] = farM / (farM - nearM);
    return m;
  }
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

unsigned lightKindBit(LightType type) {
  switch (type) {
    case LightType::Directional: return kSunLightBit;
    case LightType::Spot: return kSpotLightBit;
    case LightType::Point: return kPointLightBit;
  }
  return kAnyLightBits;
}

const char* lightTypeName(LightType type) {
  switch (type) {
    case LightType::Directional: return "sun";
    case LightType::Spot: return "spot";
    case LightType::Point: return "point";
  }
  return "unknown";
}

float lightFalloff(const Light& light, const glm::vec3& ws) {
  if (!isPositional(light)) return 1.0f;
  const glm::vec3 d = ws - light.position;
  const float distanceM = glm::length(d);
  float f = 1.0f;
  if (light.rangeM > 0.0f) {
    // KHR_lights_punctual's recommended window: (1 − (d / range)^4)^2, clamped.
    const float x = distanceM / light.rangeM;
    const float w = std::clamp(1.0f - x * x * x * x, 0.0f, 1.0f);
    f *= w * w;
  }
  if (light.type == LightType::Spot && distanceM > 0.0f) {
    const float cosAxis = glm::dot(d / distanceM, glm::normalize(light.direction));
    const float lo = std::cos(light.coneAngleRad), hi = std::cos(light.innerConeAngleRad);
    const float t = hi > lo ? std::clamp((cosAxis - lo) / (hi - lo), 0.0f, 1.0f) : (cosAxis >= lo ? 1.0f : 0.0f);
    f *= t * t * (3.0f - 2.0f * t);  // smoothstep, as the lit pass
  }
  return f;
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
  PN_CHECK(lights.size() <= kMaxLights, fmt::format("{}: {} lights, more than the limit of {}", where, lights.size(), kMaxLights));
  for (const Mesh& m : meshes) {
    PN_CHECK(m.indices.size() % 3 == 0, fmt::format("{}: mesh '{}': index count {} is not a multiple of 3", where, m.name, m.indices.size()));
    for (uint32_t i : m.indices)
      PN_CHECK(i < m.positions.size(), fmt::format("{}: mesh '{}': index {} out of range ({} vertices)", where, m.name, i, m.positions.size()));
    PN_CHECK((m.normals.empty() || m.normals.size() == m.positions.size()) && (m.uvs.empty() || m.uvs.size() == m.positions.size()),
             fmt::format("{}: mesh '{}': {} normals and {} texture coordinates for {} positions (each none or one per position)",
                         where, m.name, m.normals.size(), m.uvs.size(), m.positions.size()));
    for (const glm::vec3& p : m.positions)
      PN_CHECK(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z),
               fmt::format("{}: mesh '{}': a vertex position is not finite", where, m.name));
  }
  for (const Object& o : objects) {
    PN_CHECK(o.mesh < meshes.size(), fmt::format("{}: object '{}': mesh index out of range", where, o.name));
    PN_CHECK(o.material < materials.size(), fmt::format("{}: object '{}': material index out of range", where, o.name));
  }
  for (const Material& m : materials) {
    PN_CHECK(m.baseColorTexture < static_cast<int>(images.size()),
             fmt::format("{}: material '{}': texture index out of range", where, m.name));
    PN_CHECK(glm::all(glm::greaterThanEqual(m.transmittance, glm::vec3(0.0f))) &&
                 glm::all(glm::lessThanEqual(m.transmittance, glm::vec3(1.0f))),
             fmt::format("{}: material '{}': transmittance ({}, {}, {}) must be in [0, 1] per colour", where, m.name,
                         m.transmittance.x, m.transmittance.y, m.transmittance.z));
  }
  PN_CHECK(triangleCount() > 0, fmt::format("{}: the scene has zero triangles", where));
  PN_CHECK(std::any_of(objects.begin(), objects.end(), [&](const Object& o) { return meshes[o.mesh].hasArea(); }),
           fmt::format("{}: every triangle has zero area (its corners lie on one line): nothing would be drawn", where));
  for (const Light& l : lights) {
    PN_CHECK(glm::length(l.direction) > 0.0f, fmt::format("{}: a light has a zero direction", where));
    PN_CHECK(l.size >= 0.0f, fmt::format("{}: a light has a negative size", where));
    PN_CHECK(l.rangeM >= 0.0f && std::isfinite(l.rangeM), fmt::format("{}: a light has a negative range", where));
    if (l.type == LightType::Spot)
      PN_CHECK(l.coneAngleRad > 0.0f && l.coneAngleRad <= kMaxSpotConeRad && l.innerConeAngleRad >= 0.0f &&
                   l.innerConeAngleRad <= l.coneAngleRad,
               fmt::format("{}: a spot light's cone angles (inner {} rad, outer {} rad) are not 0 <= inner <= outer <= {}",
                           where, l.innerConeAngleRad, l.coneAngleRad, kMaxSpotConeRad));
    PN_CHECK(glm::all(glm::greaterThanEqual(l.color, glm::vec3(0.0f))) && glm::all(glm::lessThanEqual(l.color, glm::vec3(kMaxRadiance))),
             fmt::format("{}: a light's colour is outside [0, {}]", where, kMaxRadiance));
  }
  PN_CHECK(glm::all(glm::greaterThanEqual(ambient, glm::vec3(0.0f))) && glm::all(glm::lessThanEqual(ambient, glm::vec3(kMaxRadiance))),
           fmt::format("{}: the ambient radiance is outside [0, {}]", where, kMaxRadiance));
  if (const std::string problem = camera.viewProblem(); !problem.empty()) throw Error(fmt::format("{}: camera: {}", where, problem));
  if (const std::string problem = animation.problem(objects.size(), lights.size()); !problem.empty())
    throw Error(fmt::format("{}: {}", where, problem));
  if (const std::string problem = poseProblem(*this, animation.keyTimes()); !problem.empty())
    throw Error(fmt::format("{}: {}", where, problem));
}

}  // namespace penumbra
