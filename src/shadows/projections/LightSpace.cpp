#include "shadows/projections/LightSpace.h"

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>

namespace penumbra {

glm::mat4 lightViewMatrix(const glm::vec3& eye, const glm::vec3& forward) {
  const glm::vec3 f = glm::normalize(forward);
  const glm::vec3 up = std::abs(f.y) > 0.99f ? glm::vec3(0, 0, 1) : glm::vec3(0, 1, 0);
  return glm::lookAt(eye, eye + f, up);
}

std::array<glm::vec3, 8> frustumCorners(const Camera& camera, float aspect, float nearM, float farM) {
  const glm::mat4 worldFromView = glm::inverse(camera.viewFromWorld());
  const float ty = std::tan(0.5f * camera.fovYRad), tx = ty * aspect;
  std::array<glm::vec3, 8> c;
  int i = 0;
  for (float d : {nearM, farM})
    for (float sy : {-1.0f, 1.0f})
      for (float sx : {-1.0f, 1.0f}) c[static_cast<size_t>(i++)] = glm::vec3(worldFromView * glm::vec4(sx * tx * d, sy * ty * d, -d, 1.0f));
  return c;
}

float shadowFarDistance(const Camera& camera, const Scene& scene) {
  const glm::mat4 view = camera.viewFromWorld();
  float farthest = camera.nearM * 2.0f;
  for (const glm::vec3& c : scene.bounds().corners()) farthest = std::max(farthest, -(view * glm::vec4(c, 1.0f)).z);
  return std::min(camera.farM, farthest);
}

std::vector<Aabb> objectBounds(const Scene& scene) {
  std::vector<Aabb> out;
  out.reserve(scene.objects.size());
  for (const Object& o : scene.objects) out.push_back(scene.meshes[o.mesh].bounds().transformed(o.worldFromObject));
  return out;
}

glm::vec4 linearDepthPlane(const glm::mat4& viewFromWorld, float nearM, float farM) {
  const glm::vec4 row2(viewFromWorld[0][2], viewFromWorld[1][2], viewFromWorld[2][2], viewFromWorld[3][2]);
  glm::vec4 plane = -row2 / (farM - nearM);
  plane.w -= nearM / (farM - nearM);
  return plane;
}

Aabb visibleReceiversInLightSpace(const glm::mat4& lightFromWorld, const Camera& camera, float aspect,
                                  const Scene& scene) {
  Aabb frustumWs;
  for (const glm::vec3& c : frustumCorners(camera, aspect, camera.nearM, shadowFarDistance(camera, scene))) frustumWs.extend(c);
  Aabb out;
  for (const Aabb& b : objectBounds(scene)) {
    Aabb clipped;
    clipped.lo = glm::max(b.lo, frustumWs.lo);
    clipped.hi = glm::min(b.hi, frustumWs.hi);
    if (clipped.empty()) continue;
    out.extend(clipped.transformed(lightFromWorld));
  }
  return out;
}

}  // namespace penumbra
