#include "techniques/projections/LightSpace.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace penumbra {

glm::mat4 lightViewMatrix(const glm::vec3& eye, const glm::vec3& forward) {
  const glm::vec3 f = glm::normalize(forward);
  const glm::vec3 up = std::abs(f.y) > 0.99f ? glm::vec3(0, 0, 1) : glm::vec3(0, 1, 0);
  return glm::lookAt(eye, eye + f, up);
}

std::array<glm::vec3, 8> frustumCorners(const Camera& camera, float aspect, float nearM, float farM) {
  const glm::mat4 worldFromView = glm::inverse(camera.viewFromWorld());
  std::array<glm::vec3, 8> c;
  int i = 0;
  if (camera.orthographic()) {  // a box: the same half extents at every depth
    const float hy = camera.orthoHalfHeightM, hx = hy * aspect;
    for (float d : {nearM, farM})
      for (float sy : {-1.0f, 1.0f})
        for (float sx : {-1.0f, 1.0f}) c[static_cast<size_t>(i++)] = glm::vec3(worldFromView * glm::vec4(sx * hx, sy * hy, -d, 1.0f));
    return c;
  }
  const float ty = std::tan(0.5f * camera.fovYRad), tx = ty * aspect;
  for (float d : {nearM, farM})
    for (float sy : {-1.0f, 1.0f})
      for (float sx : {-1.0f, 1.0f}) c[static_cast<size_t>(i++)] = glm::vec3(worldFromView * glm::vec4(sx * tx * d, sy * ty * d, -d, 1.0f));
  return c;
}

float shadowFarDistance(const Camera& camera, const SceneExtent& scene) {
  const glm::mat4 view = camera.viewFromWorld();
  float farthest = camera.nearM * 2.0f;
  for (const glm::vec3& c : scene.bounds().corners()) farthest = std::max(farthest, -(view * glm::vec4(c, 1.0f)).z);
  return std::min(camera.farM, farthest);
}

glm::vec2 cameraDepthRange(std::span<const glm::vec3> points, const Camera& camera) {
  const glm::vec3 fwd = camera.forward();
  glm::vec2 range(std::numeric_limits<float>::infinity(), -std::numeric_limits<float>::infinity());
  for (const glm::vec3& p : points) {
    const float d = glm::dot(p - camera.position, fwd);
    range = {std::min(range.x, d), std::max(range.y, d)};
  }
  return range;
}

glm::vec4 linearDepthPlane(const glm::mat4& viewFromWorld, float nearM, float farM) {
  const glm::vec4 row2(viewFromWorld[0][2], viewFromWorld[1][2], viewFromWorld[2][2], viewFromWorld[3][2]);
  glm::vec4 plane = -row2 / (farM - nearM);
  plane.w -= nearM / (farM - nearM);
  return plane;
}

// ---- Convex bodies -------------------------------------------------------------------------

namespace {

// Half-spaces given in a view space (p_view = viewFromWorld · p_world), moved to world space.
std::vector<HalfSpace> toWorld(const std::vector<HalfSpace>& inView, const glm::mat4& viewFromWorld) {
  const glm::dmat4 m(viewFromWorld);
  const glm::dmat3 r(m);
  const glm::dvec3 t(m[3]);
  std::vector<HalfSpace> out;
  for (const HalfSpace& h : inView) out.push_back({glm::transpose(r) * h.n, glm::dot(h.n, t) + h.d});
  return out;
}

// A pyramid with apex at the view origin looking down -Z: |x| <= tx·depth, |y| <= ty·depth,
// nearM <= depth <= farM (depth = -z).
std::vector<HalfSpace> pyramidInView(double tx, double ty, double nearM, double farM) {
  return {{{0, 0, -1}, -nearM}, {{0, 0, 1}, farM}, {{1, 0, -tx}, 0}, {{-1, 0, -tx}, 0}, {{0, 1, -ty}, 0}, {{0, -1, -ty}, 0}};
}

}  // namespace

Aabb visibleReceiversInLightSpace(const glm::mat4& lightFromWorld, const Camera& camera, float aspect,
                                  const SceneExtent& scene) {
  // Each object's box clipped to the camera frustum itself (not to the frustum's bounding box,
  // which for a camera looking down on a large ground covers most of the ground).
  const std::vector<HalfSpace> frustum = frustumHalfSpaces(camera, aspect, camera.nearM, shadowFarDistance(camera, scene));
  Aabb out;
  for (const SceneExtent::Body& body : scene.bodies)
    for (const glm::vec3& p : clipBoxToConvex(body.bounds, frustum)) out.extend(glm::vec3(lightFromWorld * glm::vec4(p, 1.0f)));
  return out;
}

std::vector<glm::vec3> clipBoxToConvex(const Aabb& box, std::span<const HalfSpace> convex) {
  if (box.empty()) return {};
  // A flat box (a plane) has no volume for convexVertices: give it a millimetre of thickness.
  constexpr float kFlatPadM = 1e-3f;
  Aabb padded = box;
  padded.lo -= glm::vec3(kFlatPadM);
  padded.hi += glm::vec3(kFlatPadM);
  std::vector<HalfSpace> hs(convex.begin(), convex.end());
  const std::vector<HalfSpace> sides = boxHalfSpaces(padded);
  hs.insert(hs.end(), sides.begin(), sides.end());
  return convexVertices(hs);
}

std::vector<HalfSpace> lightRectHalfSpaces(const glm::mat4& lightFromWorld, const glm::vec2& lo, const glm::vec2& hi) {
  return toWorld({{{1, 0, 0}, -lo.x}, {{-1, 0, 0}, hi.x}, {{0, 1, 0}, -lo.y}, {{0, -1, 0}, hi.y}}, lightFromWorld);
}

std::vector<HalfSpace> lightPyramidHalfSpaces(const glm::mat4& lightFromWorld, float tanHalf, float nearM, float farM) {
  return toWorld(pyramidInView(tanHalf, tanHalf, nearM, farM), lightFromWorld);
}

std::vector<HalfSpace> frustumHalfSpaces(const Camera& camera, float aspect, float nearM, float farM) {
  if (camera.orthographic()) {  // a box: |x| <= hx, |y| <= hy, nearM <= depth <= farM
    const double hy = camera.orthoHalfHeightM, hx = hy * static_cast<double>(aspect);
    const std::vector<HalfSpace> box = {{{0, 0, -1}, -static_cast<double>(nearM)}, {{0, 0, 1}, static_cast<double>(farM)},
                                        {{1, 0, 0}, hx}, {{-1, 0, 0}, hx}, {{0, 1, 0}, hy}, {{0, -1, 0}, hy}};
    return toWorld(box, camera.viewFromWorld());
  }
  const double ty = std::tan(0.5 * static_cast<double>(camera.fovYRad)), tx = ty * static_cast<double>(aspect);
  return toWorld(pyramidInView(tx, ty, nearM, farM), camera.viewFromWorld());
}

std::vector<HalfSpace> boxHalfSpaces(const Aabb& box) {
  std::vector<HalfSpace> out;
  for (int a = 0; a < 3; ++a) {
    glm::dvec3 n(0.0);
    n[a] = 1.0;
    out.push_back({n, -static_cast<double>(box.lo[a])});
    out.push_back({-n, static_cast<double>(box.hi[a])});
  }
  return out;
}

std::vector<HalfSpace> spotHalfSpaces(const Light& light, float nearM) {
  const double t = std::tan(static_cast<double>(light.coneAngleRad));
  std::vector<HalfSpace> inView = pyramidInView(t, t, nearM, 0.0);
  inView.erase(inView.begin() + 1);  // no far plane: the scene's box bounds the body
  return toWorld(inView, lightViewMatrix(light.position, light.direction));
}

std::vector<glm::vec3> convexVertices(std::span<const HalfSpace> hs) {
  // Scale for tolerances: the largest plane offset (metres); points this far off a plane, in
  // relative terms, still count as on it.
  double scale = 1.0;
  for (const HalfSpace& h : hs) scale = std::max(scale, std::abs(h.d) / std::max(glm::length(h.n), 1e-300));
  const double insideEps = 1e-7 * scale, mergeEps = 1e-6 * scale;
  std::vector<glm::dvec3> found;
  const size_t n = hs.size();
  for (size_t i = 0; i < n; ++i)
    for (size_t j = i + 1; j < n; ++j)
      for (size_t k = j + 1; k < n; ++k) {
        const glm::dvec3 a = hs[i].n, b = hs[j].n, c = hs[k].n;
        const glm::dvec3 bc = glm::cross(b, c);
        const double det = glm::dot(a, bc);
        if (std::abs(det) < 1e-12 * glm::length(a) * glm::length(b) * glm::length(c)) continue;
        // Solve a·p = -da, b·p = -db, c·p = -dc (Cramer's rule in vector form).
        const glm::dvec3 p = (-hs[i].d * bc - hs[j].d * glm::cross(c, a) - hs[k].d * glm::cross(a, b)) / det;
        bool inside = true;
        for (const HalfSpace& h : hs)
          if (h.eval(p) < -insideEps * glm::length(h.n)) { inside = false; break; }
        if (!inside) continue;
        bool dup = false;
        for (const glm::dvec3& q : found)
          if (glm::length(q - p) < mergeEps) { dup = true; break; }
        if (!dup) found.push_back(p);
      }
  std::vector<glm::vec3> out;
  if (found.size() < 4) return out;  // empty, or flat: no volume to fit
  for (const glm::dvec3& p : found) out.emplace_back(p);
  return out;
}

std::vector<glm::vec3> receiverBody(const Camera& camera, float aspect, float nearM, float farM, const SceneExtent& scene,
                                    const Light& light) {
  std::vector<HalfSpace> hs = frustumHalfSpaces(camera, aspect, nearM, farM);
  const std::vector<HalfSpace> box = boxHalfSpaces(scene.bounds());
  hs.insert(hs.end(), box.begin(), box.end());
  if (light.type == LightType::Spot) {
    constexpr float kSpotBodyNearM = 0.01f;  // receivers at the light's centre get no shadow
    const std::vector<HalfSpace> spot = spotHalfSpaces(light, kSpotBodyNearM);
    hs.insert(hs.end(), spot.begin(), spot.end());
  }
  return convexVertices(hs);
}

std::vector<glm::vec3> casterExtrusion(std::span<const glm::vec3> body, const Light& light, const Aabb& casters) {
  std::vector<glm::vec3> out;
  if (body.empty() || casters.empty()) return out;
  if (light.type == LightType::Directional) {
    const glm::vec3 toLight = -glm::normalize(light.direction);
    // Per slab: distance to its exit plane along toLight is affine in the point, so moving each
    // vertex by it moves every point of the body by at least its true exit distance.
    float bestWorst = std::numeric_limits<float>::max();
    int bestAxis = -1;
    for (int a = 0; a < 3; ++a) {
      if (std::abs(toLight[a]) < 1e-6f) continue;
      const float plane = toLight[a] > 0.0f ? casters.hi[a] : casters.lo[a];
      float worst = 0.0f;
      for (const glm::vec3& p : body) worst = std::max(worst, (plane - p[a]) / toLight[a]);
      if (worst < bestWorst) { bestWorst = worst; bestAxis = a; }
    }
    const float plane = toLight[bestAxis] > 0.0f ? casters.hi[bestAxis] : casters.lo[bestAxis];
    for (const glm::vec3& p : body) out.push_back(p + toLight * std::max(0.0f, (plane - p[bestAxis]) / toLight[bestAxis]));
  } else {
    // Toward the light's centre: p + (L − p)·s. The exit fraction through one slab is monotonic
    // in the point's coordinate, so its largest value over the vertices bounds the whole body.
    const glm::vec3 L = light.position;
    float best = 1.0f;
    for (int a = 0; a < 3; ++a) {
      float worst = 0.0f;
      for (const glm::vec3& p : body) {
        const float toward = L[a] - p[a];
        if (std::abs(toward) < 1e-6f) { worst = 1.0f; break; }
        const float plane = toward > 0.0f ? casters.hi[a] : casters.lo[a];
        worst = std::max(worst, std::clamp((plane - p[a]) / toward, 0.0f, 1.0f));
      }
      best = std::min(best, worst);
    }
    for (const glm::vec3& p : body) out.push_back(p + (L - p) * best);
  }
  return out;
}

ViewRegion wholeViewRegion(const Camera& camera, float aspect, const Light& light, const SceneExtent& scene) {
  ViewRegion r;
  r.nearM = camera.nearM;
  r.farM = std::max(shadowFarDistance(camera, scene), 2.0f * r.nearM);
  r.body = receiverBody(camera, aspect, r.nearM, r.farM, scene, light);
  r.casters = casterExtrusion(r.body, light, scene.casterBounds());
  return r;
}

glm::mat4 sunViewMatrix(const SceneExtent& scene, const Light& light) {
  const Aabb bounds = scene.bounds();
  const float radius = std::max(bounds.radius(), 1e-3f);
  return lightViewMatrix(bounds.center() - glm::normalize(light.direction) * (2.0f * radius), light.direction);
}

Aabb boundsOf(std::span<const glm::vec3> points, const glm::mat4& m) {
  Aabb b;
  for (const glm::vec3& p : points) b.extend(glm::vec3(m * glm::vec4(p, 1.0f)));
  return b;
}

ShadowView fitLightView(const SceneExtent& scene, const Light& light, std::span<const glm::vec3> receivers,
                        std::span<const glm::vec3> casters, float marginFraction) {
  constexpr float kDepthPaddingFraction = 1e-3f;  // keeps receivers strictly inside [0,1]
  constexpr float kMinNearM = 0.01f;              // a spot map's nearest near plane
  constexpr float kMinNearFractionOfFar = 1e-3f;  // bounds the perspective depth ratio
  ShadowView v;
  if (light.type == LightType::Directional) {
    v.viewFromWorld = sunViewMatrix(scene, light);
    Aabb recv = boundsOf(receivers, v.viewFromWorld);
    if (recv.empty()) recv = scene.bounds().transformed(v.viewFromWorld);
    Aabb all = recv;
    all.extend(boundsOf(casters, v.viewFromWorld));
    const glm::vec2 pad = glm::vec2(recv.size()) * marginFraction;
    const glm::vec2 lo = glm::vec2(recv.lo) - pad, hi = glm::vec2(recv.hi) + pad;
    const float farM = -recv.lo.z, nearM = -all.hi.z;
    const float padZ = (farM - nearM) * kDepthPaddingFraction + 1e-4f;
    v.nearM = nearM - padZ;
    v.farM = farM + padZ;
    v.perspective = false;
    v.extent = hi - lo;
    v.clipFromWorld = glm::orthoRH_ZO(lo.x, hi.x, lo.y, hi.y, v.nearM, v.farM) * v.viewFromWorld;
  } else {
    v.viewFromWorld = lightViewMatrix(light.position, light.direction);
    const float tanCone = std::tan(light.coneAngleRad);
    glm::vec2 lo(tanCone), hi(-tanCone);
    float farM = kMinNearM * 2.0f, nearM = std::numeric_limits<float>::max();
    for (const glm::vec3& p : receivers) {
      const glm::vec3 l(v.viewFromWorld * glm::vec4(p, 1.0f));
      const float depth = std::max(-l.z, kMinNearM);
      lo = glm::min(lo, glm::vec2(l) / depth);
      hi = glm::max(hi, glm::vec2(l) / depth);
      farM = std::max(farM, depth);
      nearM = std::min(nearM, depth);
    }
    if (receivers.empty()) { lo = glm::vec2(-tanCone); hi = glm::vec2(tanCone); nearM = kMinNearM; }
    for (const glm::vec3& p : casters) nearM = std::min(nearM, -(v.viewFromWorld * glm::vec4(p, 1.0f)).z);
    lo = glm::max(lo, glm::vec2(-tanCone));
    hi = glm::min(hi, glm::vec2(tanCone));
    const glm::vec2 pad = (hi - lo) * marginFraction;
    lo -= pad;
    hi += pad;
    v.nearM = std::max({nearM * (1.0f - kDepthPaddingFraction), kMinNearM, farM * kMinNearFractionOfFar});
    v.farM = farM * (1.0f + kDepthPaddingFraction);
    v.perspective = true;
    v.extent = hi - lo;
    v.clipFromWorld = glm::frustumRH_ZO(lo.x * v.nearM, hi.x * v.nearM, lo.y * v.nearM, hi.y * v.nearM, v.nearM, v.farM) *
                      v.viewFromWorld;
  }
  v.depthPlane = linearDepthPlane(v.viewFromWorld, v.nearM, v.farM);
  return v;
}

LightFrusta cubeFaceViews(const Light& light, const SceneExtent& scene, int mapSize, float guardTexels) {
  constexpr glm::vec3 kAxes[kCubeFaces] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  constexpr glm::vec3 kUps[kCubeFaces] = {{0, 1, 0}, {0, 1, 0}, {0, 0, -1}, {0, 0, 1}, {0, 1, 0}, {0, 1, 0}};
  constexpr float kDepthPaddingFraction = 1e-3f;  // keeps receivers strictly inside [0,1]
  constexpr float kMinNearM = 0.01f;              // a face's nearest near plane
  constexpr float kMinNearFractionOfFar = 1e-3f;  // bounds the perspective depth ratio
  const Aabb bounds = scene.bounds();
  float farM = 1e-3f;
  for (const glm::vec3& c : bounds.corners()) farM = std::max(farM, glm::length(c - light.position));
  if (light.rangeM > 0.0f) farM = std::min(farM, light.rangeM);
  // tan of the half angle: 1 at the face's edge, plus the guard band's texels of a map whose
  // inner (2·mapSize − 2·guard)/2 texels span the face: t = S / (S − 2g).
  const float size = static_cast<float>(mapSize);
  const float guard = std::min(guardTexels, 0.25f * size);
  const float tanHalf = size / (size - 2.0f * guard);
  const float nearM = std::max({light.size, kMinNearM, farM * kMinNearFractionOfFar});
  LightFrusta f;
  for (int face = 0; face < kCubeFaces; ++face) {
    ShadowView v;
    v.viewFromWorld = glm::lookAt(light.position, light.position + kAxes[face], kUps[face]);
    v.nearM = nearM;
    v.farM = std::max(farM * (1.0f + kDepthPaddingFraction), 2.0f * nearM);
    v.perspective = true;
    v.extent = glm::vec2(2.0f * tanHalf);
    v.clipFromWorld = glm::perspectiveRH_ZO(2.0f * std::atan(tanHalf), 1.0f, v.nearM, v.farM) * v.viewFromWorld;
    v.depthPlane = linearDepthPlane(v.viewFromWorld, v.nearM, v.farM);
    f.views.push_back(v);
  }
  return f;
}

}  // namespace penumbra
