// Shimmer: the fraction of fixed world points near shadow edges whose visibility flips between
// consecutive frames of a small camera motion.
#include "comparison/Shimmer.h"

#include <penumbra/Error.h>

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>

namespace penumbra {
namespace {

constexpr float kEdgeContrastV = 0.5f;                     // a hard edge in frame 0's V
constexpr float kPenumbraLowV = 0.02f, kPenumbraHighV = 0.98f;  // or the point is in a soft edge
constexpr float kTurnRadiusM = 20.0f;  // a turn moves a point this far away by subTexelStep texels

// Shadow-map texel (m) of view 0 at the middle of its depth range.
float firstViewTexelM(const LightFrusta& f, int mapSize) {
  const ShadowView& v = f.views.front();
  const float scale = v.perspective ? 0.5f * (v.nearM + v.farM) : 1.0f;
  return std::max(v.extent.x, v.extent.y) * scale / static_cast<float>(mapSize);
}

bool insideView(const Camera& c, float aspect, const glm::vec3& p, float marginNdc) {
  const glm::vec4 clip = c.clipFromView(aspect) * c.viewFromWorld() * glm::vec4(p, 1.0f);
  if (clip.w <= 0.0f) return false;
  const glm::vec2 ndc = glm::vec2(clip) / clip.w;
  return std::abs(ndc.x) <= 1.0f - marginNdc && std::abs(ndc.y) <= 1.0f - marginNdc;
}

}  // namespace

std::vector<Camera> shimmerCameraPath(const Camera& start, int steps, float texelM, const ShimmerOptions& o) {
  PN_CHECK(steps >= 1 && texelM > 0.0f, "shimmer: need ≥ 1 step and a positive texel size");
  std::vector<Camera> path;
  Camera c = start;
  for (int k = 0; k < steps; ++k) {
    const float sign = (k / 4) % 2 == 0 ? 1.0f : -1.0f;
    const glm::vec3 fwd = c.forward();
    const glm::vec3 right = glm::normalize(glm::cross(fwd, c.up));
    const glm::vec3 up = glm::cross(right, fwd);
    glm::vec3 move(0.0f);
    switch (k % 4) {
      case 0: move = right * (o.subTexelStep * texelM); break;
      case 1: move = fwd * (o.subTexelStep * texelM); break;
      case 2: move = glm::normalize(right + up) * (o.fewTexelStep * texelM); break;
      default: {
        const float angle = o.subTexelStep * texelM / kTurnRadiusM;
        const glm::mat4 turn = glm::rotate(glm::mat4(1.0f), sign * angle, c.up);
        c.target = c.position + glm::vec3(turn * glm::vec4(c.target - c.position, 0.0f));
      }
    }
    c.position += sign * move;
    c.target += sign * move;
    path.push_back(c);
  }
  return path;
}

ShimmerResult measureShimmer(Renderer& renderer, const RenderOptions& render, const ShimmerOptions& o) {
  PN_CHECK(o.steps >= 1 && o.edgeRadiusPx >= 0 && o.changeThresholdV > 0.0f, "shimmer: bad options");
  const Camera start = renderer.scene().camera;
  const std::vector<Light> lights = renderer.scene().lights;
  const float aspect = static_cast<float>(render.width) / static_cast<float>(render.height);
  renderer.render(render);
  const GBufferData g = renderer.readGBuffer();
  const std::vector<float> v0 = renderer.readVisibility();
  ShimmerResult result;
  result.steps = o.steps;
  result.texelM = firstViewTexelM(renderer.frusta(), renderer.technique().mapSize());
  const std::vector<Camera> path = shimmerCameraPath(start, o.steps, result.texelM, o);

  // Frame 0's points near a shadow edge that stay in view along the whole path.
  std::vector<SurfaceSample> points;
  const int w = g.width, h = g.height, r = o.edgeRadiusPx;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const size_t i = static_cast<size_t>(y) * static_cast<size_t>(w) + static_cast<size_t>(x);
      if (!g.covered(i)) continue;
      const glm::vec3 p(g.position[i]), n(g.geoNormal[i]);
      const Light& light = lights.front();
      const glm::vec3 toLight = light.type == LightType::Directional ? -glm::normalize(light.direction)
                                                                     : glm::normalize(light.position - p);
      if (glm::dot(n, toLight) <= 0.0f) continue;
      bool edge = v0[i] > kPenumbraLowV && v0[i] < kPenumbraHighV;
      for (int dy = -r; dy <= r && !edge; ++dy)
        for (int dx = -r; dx <= r && !edge; ++dx) {
          const int qx = x + dx, qy = y + dy;
          if (qx < 0 || qy < 0 || qx >= w || qy >= h) continue;
          const size_t j = static_cast<size_t>(qy) * static_cast<size_t>(w) + static_cast<size_t>(qx);
          edge = g.covered(j) && std::abs(v0[j] - v0[i]) > kEdgeContrastV;
        }
      if (!edge) continue;
      bool stays = true;
      for (const Camera& c : path) stays = stays && insideView(c, aspect, p, o.screenMarginNdc);
      if (stays) points.push_back({p, n, {x, y}});
    }
  result.edgePoints = points.size();
  if (points.empty()) return result;

  std::vector<float> previous = renderer.visibilityAt(points);
  for (const Camera& c : path) {
    renderer.setCameraAndLights(c, lights);
    renderer.render(render);
    const std::vector<float> now = renderer.visibilityAt(points);
    for (size_t i = 0; i < now.size(); ++i)
      if (std::abs(now[i] - previous[i]) > o.changeThresholdV) ++result.changes;
    previous = now;
  }
  renderer.setCameraAndLights(start, lights);
  result.shimmerPct = 100.0 * static_cast<double>(result.changes) /
                      (static_cast<double>(points.size()) * static_cast<double>(o.steps));
  return result;
}

}  // namespace penumbra
