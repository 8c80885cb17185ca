#include "techniques/projections/PerspectiveProjection.h"

#include "techniques/projections/LightSpace.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace penumbra {
namespace {

constexpr ParamDesc kParams[] = {
    {"psm.slideBack", "Slide-back", "virtual camera distance behind the camera, in units of √(near·far) of the visible receivers; larger = weaker warp", "×√(near·far)",
     1.0f, 0.0f, 16.0f, 0.0f},
    {"psm.marginTexels", "Margin", "border added around the fitted region, in texels", "texels", 2.0f, 0.0f, 64.0f, 1.0f},
};

// |w| / |xyz| of the light's PPS image below which it is treated as a direction (orthographic).
constexpr double kDirectionalEps = 1e-4;
// A map wider than this from the PPS light wastes most texels and loses precision: slide back.
constexpr double kMaxHalfAngleTan = 4.0;  // ~76 degrees
constexpr int kMaxSlideAttempts = 12;     // doubling each time: 4096× the first slide
// The virtual near plane is never closer than this fraction of the virtual far plane (f/n ≤ 10⁴).
constexpr double kMinNearOverFar = 1e-4;
// Sun and spot lights lie this close to the camera's side plane: "perpendicular".
constexpr float kPerpendicularCos = 1e-4f;

using dvec3 = glm::dvec3;
using dvec4 = glm::dvec4;
using dmat4 = glm::dmat4;

// The light as a homogeneous world point: the sun is at infinity opposite its direction.
dvec4 lightPoint(const Light& light) {
  return light.type == LightType::Directional ? dvec4(-glm::normalize(dvec3(light.direction)), 0.0)
                                              : dvec4(dvec3(light.position), 1.0);
}

// Off-centre projection (OpenGL, z in [0,1]) from the origin looking down −Z, fitted to points
// given in that view space: all must lie in front (checked by the caller).
dmat4 fitPerspective(std::span<const dvec3> pts, double marginFraction, double& maxTan) {
  double nearM = std::numeric_limits<double>::max(), farM = 0.0;
  glm::dvec2 lo(std::numeric_limits<double>::max()), hi(-std::numeric_limits<double>::max());
  for (const dvec3& p : pts) {
    const double depth = -p.z;
    nearM = std::min(nearM, depth);
    farM = std::max(farM, depth);
    lo = glm::min(lo, glm::dvec2(p) / depth);
    hi = glm::max(hi, glm::dvec2(p) / depth);
  }
  const glm::dvec2 pad = (hi - lo) * marginFraction;
  lo -= pad;
  hi += pad;
  maxTan = std::max({-lo.x, -lo.y, hi.x, hi.y});
  nearM *= 1.0 - 1e-3;
  farM *= 1.0 + 1e-3;
  return glm::frustumRH_ZO(lo.x * nearM, hi.x * nearM, lo.y * nearM, hi.y * nearM, nearM, farM);
}

dmat4 lookFrom(const dvec3& eye, const dvec3& forward) {
  const dvec3 f = glm::normalize(forward);
  const dvec3 up = std::abs(f.y) > 0.99 ? dvec3(0, 0, 1) : dvec3(0, 1, 0);
  return glm::lookAtRH(eye, eye + f, up);
}

}  // namespace

PsmLightCase psmLightCase(const Camera& camera, const Light& light) {
  const glm::vec3 fwd = camera.forward();
  const float along = light.type == LightType::Directional ? glm::dot(-glm::normalize(light.direction), fwd)
                                                           : glm::dot(glm::normalize(light.position - camera.position), fwd);
  if (std::abs(along) < kPerpendicularCos) return PsmLightCase::Perpendicular;
  return along > 0.0f ? PsmLightCase::InFront : PsmLightCase::Behind;
}

PsmWarp computePsmWarp(const Camera& camera, const Light& light, std::span<const glm::vec3> receivers,
                       std::span<const glm::vec3> casters, const Aabb& scene, float slideBackM, float marginFraction) {
  PsmWarp out;
  out.lightCase = psmLightCase(camera, light);
  std::vector<dvec3> all;
  for (const glm::vec3& p : receivers) all.emplace_back(p);
  for (const glm::vec3& p : casters) all.emplace_back(p);
  const dvec3 fwd(camera.forward()), eye(camera.position);
  double farthest = 0.0, nearest = std::numeric_limits<double>::max();
  for (const dvec3& p : all) {
    farthest = std::max(farthest, glm::dot(p - eye, fwd));
    nearest = std::min(nearest, glm::dot(p - eye, fwd));
  }
  // Slide back at least far enough that every point is in front of the virtual near plane, and
  // the whole scene in front of the virtual eye: a triangle reaching behind it would have w < 0
  // in PPS, and the light's projection can flip that sign back, drawing it across the map.
  double sceneNearest = nearest;
  for (const glm::vec3& c : scene.corners()) sceneNearest = std::min(sceneNearest, glm::dot(dvec3(c) - eye, fwd));
  double slide = std::max({static_cast<double>(slideBackM), kMinNearOverFar * farthest - nearest,
                           kMinNearOverFar * farthest - sceneNearest});
  const dmat4 cameraRotation(glm::lookAtRH(dvec3(0.0), fwd, dvec3(camera.up)));
  for (int attempt = 0; attempt < kMaxSlideAttempts; ++attempt, slide = slide * 2.0 + 1e-3 * farthest) {
    const dvec3 virtualEye = eye - fwd * slide;
    const dmat4 viewV = cameraRotation * glm::translate(dmat4(1.0), -virtualEye);
    std::vector<dvec3> inView;
    for (const dvec3& p : all) inView.emplace_back(viewV * dvec4(p, 1.0));
    double ignored = 0.0;
    const dmat4 ppsFromWorld = fitPerspective(inView, 0.0, ignored) * viewV;
    std::vector<dvec3> pps;
    dvec3 centroid(0.0);
    for (const dvec3& p : all) {
      const dvec4 c = ppsFromWorld * dvec4(p, 1.0);
      pps.emplace_back(dvec3(c) / c.w);
      centroid += pps.back() / static_cast<double>(all.size());
    }
    const dvec4 L = ppsFromWorld * lightPoint(light);
    dmat4 lightFromPps;
    if (std::abs(L.w) <= kDirectionalEps * glm::length(dvec3(L))) {
      // A direction in PPS: orthographic along it (the sign of a point at infinity is arbitrary;
      // the depth order is not used).
      const dvec3 dir = -glm::normalize(dvec3(L));
      const dmat4 view = lookFrom(centroid - dir * 4.0, dir);  // PPS points lie in [-1,1]³
      Aabb b;
      for (const dvec3& p : pps) b.extend(glm::vec3(view * dvec4(p, 1.0)));
      const glm::dvec2 pad = glm::dvec2(b.size()) * static_cast<double>(marginFraction);
      lightFromPps = glm::orthoRH_ZO(b.lo.x - pad.x, b.hi.x + pad.x, b.lo.y - pad.y, b.hi.y + pad.y,
                                     -static_cast<double>(b.hi.z) - 1e-3, -static_cast<double>(b.lo.z) + 1e-3) * view;
    } else {
      const dvec3 lp = dvec3(L) / L.w;
      const dvec3 axis = centroid - lp;
      if (glm::length(axis) < 1e-9) continue;
      const dmat4 view = lookFrom(lp, axis);
      std::vector<dvec3> local;
      bool inFront = true;
      for (const dvec3& p : pps) {
        local.emplace_back(view * dvec4(p, 1.0));
        inFront = inFront && -local.back().z > 1e-6;
      }
      if (!inFront) continue;  // the PPS light sits inside the body: slide further back
      double maxTan = 0.0;
      const dmat4 proj = fitPerspective(local, marginFraction, maxTan);
      if (maxTan > kMaxHalfAngleTan) continue;
      lightFromPps = proj * view;
    }
    out.clipFromWorld = glm::mat4(lightFromPps * ppsFromWorld);
    out.slideBackM = static_cast<float>(slide);
    // The composed matrix must keep w > 0 at every point (the GPU clips w ≤ 0 away).
    bool positive = true;
    for (const dvec3& p : all) positive = positive && (glm::dvec4(out.clipFromWorld * glm::vec4(glm::vec3(p), 1.0f))).w > 0.0;
    if (positive) return out;
  }
  out.degenerate = true;
  return out;
}

PerspectiveProjection::PerspectiveProjection() : Projection(kParams) {}

LightFrusta PerspectiveProjection::computeFrusta(const Camera& camera, float aspect, const Light& light,
                                                 const SceneExtent& scene, int mapSize) const {
  const float marginFraction = param("psm.marginTexels") / static_cast<float>(mapSize);
  const ViewRegion region = wholeViewRegion(camera, aspect, light, scene);
  const std::vector<glm::vec3>& body = region.body;
  const std::vector<glm::vec3>& casters = region.casters;
  const float nearM = region.nearM;
  LightFrusta f;
  f.views.push_back(fitLightView(scene, light, body, casters, marginFraction));
  if (body.empty()) return f;
  // Slide-back in units of √(n·f) of the visible receivers: LiSPSM's optimal near distance for a
  // light perpendicular to the view, n + √(n·f), is where the warp spreads error evenly.
  const glm::vec2 depths = cameraDepthRange(body, camera);
  const float recvNear = depths.x, recvFar = std::max(depths.y, 0.0f);
  const float slide = param("psm.slideBack") * std::sqrt(std::max(recvNear, nearM) * recvFar);
  const PsmWarp warp = computePsmWarp(camera, light, body, casters, scene.bounds(), slide, marginFraction);
  if (warp.degenerate) return f;  // the unwarped fit
  f.views.front().clipFromWorld = warp.clipFromWorld;
  f.views.front().warped = true;
  return f;
}

}  // namespace penumbra
