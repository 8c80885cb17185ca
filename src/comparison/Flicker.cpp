// Flicker between consecutive frames (Flicker.h).
#include "comparison/Flicker.h"

#include <penumbra/Error.h>

#include <fmt/format.h>
#include <glm/gtc/matrix_inverse.hpp>

#include <cmath>

namespace penumbra {

FlickerFrame makeFlickerFrame(const GBufferData& g, const Camera& camera, std::vector<float> v, std::vector<float> vRef,
                              std::vector<uint8_t> mask, std::vector<glm::mat4> worldFromObject) {
  const size_t n = static_cast<size_t>(g.width) * static_cast<size_t>(g.height);
  PN_CHECK(v.size() == n && vRef.size() == n && mask.size() == n && g.position.size() == n && g.geoNormal.size() == n,
           fmt::format("makeFlickerFrame: arrays of {}, {}, {} and {} values for a {}x{} frame", v.size(), vRef.size(), mask.size(),
                       g.position.size(), g.width, g.height));
  FlickerFrame f;
  f.width = g.width;
  f.height = g.height;
  f.clipFromWorld = camera.clipFromView(static_cast<float>(g.width) / static_cast<float>(g.height)) * camera.viewFromWorld();
  f.cameraPosition = camera.position;
  f.pixelAngleRad = 2.0f * std::tan(0.5f * camera.fovYRad) / static_cast<float>(g.height);
  f.position.resize(n);
  f.geoNormal.resize(n);
  f.object.assign(n, 0);
  for (size_t i = 0; i < n; ++i) {
    f.position[i] = glm::vec3(g.position[i]);
    f.geoNormal[i] = glm::vec3(g.geoNormal[i]);
    if (g.covered(i) && i < g.triangle.size()) f.object[i] = g.triangle[i].x;
  }
  f.v = std::move(v);
  f.vRef = std::move(vRef);
  f.mask = std::move(mask);
  f.worldFromObject = std::move(worldFromObject);
  return f;
}

std::vector<FollowedPoint> followPoints(const FlickerFrame& a, const FlickerFrame& b, const FlickerOptions& o) {
  PN_CHECK(a.width == b.width && a.height == b.height && a.worldFromObject.size() == b.worldFromObject.size(),
           "followPoints: the frames differ in size or in objects");
  // Frame a's world → frame b's world, per object.
  std::vector<glm::mat4> move(a.worldFromObject.size());
  std::vector<glm::mat3> moveNormal(move.size());
  for (size_t k = 0; k < move.size(); ++k) {
    move[k] = b.worldFromObject[k] * glm::inverse(a.worldFromObject[k]);
    moveNormal[k] = glm::inverseTranspose(glm::mat3(move[k]));
  }
  std::vector<FollowedPoint> out;
  const size_t n = static_cast<size_t>(a.width) * static_cast<size_t>(a.height);
  for (size_t i = 0; i < n; ++i) {
    const uint32_t object = a.object[i];
    if (!a.mask[i] || object == 0 || object > move.size()) continue;
    const size_t k = object - 1;
    const glm::vec3 p = glm::vec3(move[k] * glm::vec4(a.position[i], 1.0f));
    const glm::vec4 clip = b.clipFromWorld * glm::vec4(p, 1.0f);
    if (clip.w <= 0.0f) continue;
    const glm::vec2 ndc = glm::vec2(clip) / clip.w;
    const float fx = (0.5f * ndc.x + 0.5f) * static_cast<float>(b.width), fy = (0.5f * ndc.y + 0.5f) * static_cast<float>(b.height);
    if (!(fx >= 0.0f && fy >= 0.0f && fx < static_cast<float>(b.width) && fy < static_cast<float>(b.height))) continue;
    const glm::ivec2 pixel(static_cast<int>(fx), static_cast<int>(fy));
    const size_t j = static_cast<size_t>(pixel.y) * static_cast<size_t>(b.width) + static_cast<size_t>(pixel.x);
    if (!b.mask[j] || b.object[j] != object) continue;
    const float footprintM = glm::length(p - b.cameraPosition) * b.pixelAngleRad;
    if (glm::length(b.position[j] - p) > o.followTolerancePx * footprintM) continue;
    out.push_back({i, j, {p, glm::normalize(moveNormal[k] * a.geoNormal[i]), pixel}});
  }
  return out;
}

FlickerCounts countFlicker(const FlickerFrame& a, const FlickerFrame& b, std::span<const FollowedPoint> points,
                           std::span<const float> vAt, const FlickerOptions& o) {
  PN_CHECK(points.size() == vAt.size(), fmt::format("countFlicker: {} values for {} points", vAt.size(), points.size()));
  FlickerCounts c;
  c.followed = points.size();
  for (size_t k = 0; k < points.size(); ++k) {
    const FollowedPoint& p = points[k];
    if (std::abs(vAt[k] - a.v[p.from]) > o.changeThresholdV && std::abs(b.vRef[p.to] - a.vRef[p.from]) < o.referenceStillV) ++c.flickering;
  }
  return c;
}

}  // namespace penumbra
