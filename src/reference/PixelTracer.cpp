#include "reference/PixelTracer.h"

#include <penumbra/Error.h>

#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

namespace penumbra::reference {
namespace {

/// Spacing of float32 values at magnitude x ≥ 0.
float floatSpacing(float x) { return std::nextafter(x, std::numeric_limits<float>::infinity()) - x; }

}  // namespace

LightSetup setupLight(const Light& light) {
  PN_CHECK(light.size >= 0.0f && std::isfinite(light.size),
           fmt::format("reference: light size {} must be finite and >= 0", light.size));
  PN_CHECK(glm::length(light.direction) > 0.0f, "reference: the light has a zero direction");
  LightSetup s;
  s.light = light;
  s.power = light.color * light.intensity;
  s.soft = light.size > 0.0f;
  if (light.type == LightType::Directional) {
    PN_CHECK(light.size < glm::half_pi<float>(),
             fmt::format("reference: sun angular radius {} rad must be below pi/2", light.size));
    s.toLight = -glm::normalize(light.direction);
    s.sunCapHeight = reference::oneMinusCos(light.size);
    // E at normal incidence = ∫_cone L_e cos dω = L_e · π sin²α.
    const float sinAlpha = std::sin(light.size);
    s.sunSinRadius = sinAlpha;
    if (s.soft) s.radiance = s.power / (glm::pi<float>() * sinAlpha * sinAlpha);
  } else {
    PN_CHECK(light.type == LightType::Point || (light.coneAngleRad > 0.0f && light.coneAngleRad < glm::pi<float>()),
             fmt::format("reference: spot cone half angle {} rad must be in (0, pi)", light.coneAngleRad));
    s.directional = false;
    s.centre = light.position;
    s.spotAxis = glm::normalize(light.direction);
    constexpr float kEveryDirection = -2.0f;  // below any cosine: a point light has no cone
    s.cosCone = light.type == LightType::Point ? kEveryDirection : std::cos(light.coneAngleRad);
    s.rangeM = light.rangeM;
    s.radiusM = light.size;
    // A uniform sphere of radiance L_e has intensity L_e · πR² in every direction.
    if (s.soft) s.radiance = s.power / (glm::pi<float>() * light.size * light.size);
  }
  return s;
}

std::vector<std::vector<ReceiverTriangle>> receiverTriangles(const Scene& scene) {
  std::vector<std::vector<ReceiverTriangle>> out(scene.objects.size());
  for (size_t o = 0; o < scene.objects.size(); ++o) {
    const Object& object = scene.objects[o];
    const Mesh& mesh = scene.meshes[object.mesh];
    glm::mat4 absolute;
    for (int c = 0; c < 4; ++c) absolute[c] = glm::abs(object.worldFromObject[c]);
    std::vector<glm::vec3> world(mesh.vertexCount());
    std::vector<float> magnitude(mesh.vertexCount());
    for (size_t i = 0; i < mesh.vertexCount(); ++i) {
      world[i] = glm::vec3(object.worldFromObject * glm::vec4(mesh.positions[i], 1.0f));
      const glm::vec4 terms = absolute * glm::vec4(glm::abs(mesh.positions[i]), 1.0f);
      magnitude[i] = std::max({terms.x, terms.y, terms.z});
    }
    out[o].resize(mesh.triangleCount());
    for (size_t t = 0; t < out[o].size(); ++t) {
      const uint32_t a = mesh.indices[3 * t], b = mesh.indices[3 * t + 1], c = mesh.indices[3 * t + 2];
      const glm::vec3 cross = glm::cross(world[b] - world[a], world[c] - world[a]);
      const float length = glm::length(cross);
      out[o][t].normal = length > 0.0f ? cross / length : glm::vec3(0.0f);
      out[o][t].magnitude = std::max({magnitude[a], magnitude[b], magnitude[c]});
    }
  }
  return out;
}

Receiver receiverOf(const GBufferData& g, size_t i, const std::vector<std::vector<ReceiverTriangle>>& triangles) {
  Receiver out;
  const glm::vec3 p = glm::abs(glm::vec3(g.position[i]));
  float magnitude = std::max({p.x, p.y, p.z});
  if (!g.triangle.empty() && g.triangle[i].x > 0) {
    const uint32_t object = g.triangle[i].x - 1, triangle = g.triangle[i].y;
    PN_CHECK(object < triangles.size() && triangle < triangles[object].size(),
             fmt::format("reference: G-buffer pixel {} shows triangle {} of object {}, which the scene does not have", i,
                         triangle, object));
    const ReceiverTriangle& t = triangles[object][triangle];
    out.triangle = {object, triangle};
    out.planeNormal = glm::dot(t.normal, glm::vec3(g.geoNormal[i])) < 0.0f ? -t.normal : t.normal;
    magnitude = std::max(magnitude, t.magnitude);
  }
  out.errorM = kPositionToleranceUlps * floatSpacing(magnitude);
  return out;
}

std::vector<Receiver> receiversOf(const GBufferData& g, const std::vector<std::vector<ReceiverTriangle>>& triangles) {
  std::vector<Receiver> out(g.position.size());
  tbb::parallel_for(tbb::blocked_range<size_t>(0, out.size()), [&](const tbb::blocked_range<size_t>& range) {
    for (size_t i = range.begin(); i != range.end(); ++i) out[i] = receiverOf(g, i, triangles);
  });
  return out;
}

}  // namespace penumbra::reference
