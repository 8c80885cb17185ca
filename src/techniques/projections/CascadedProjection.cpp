#include "techniques/projections/CascadedProjection.h"

#include "techniques/projections/LightSpace.h"
#include "shared/Bindings.h"

#include <penumbra/Error.h>

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>

namespace penumbra {
namespace {

constexpr std::string_view kOnOff[] = {"off", "on"};

constexpr ParamDesc kParams[] = {
    {"csm.cascades", "Cascades", "number of cascades (one shadow map each, same resolution)", "maps", 4.0f, 1.0f,
     static_cast<float>(PN_MAX_CASCADES), 1.0f},
    {"csm.lambda", "Split λ", "practical split blend: 0 = uniform slices, 1 = logarithmic slices", "fraction", 0.9f, 0.0f, 1.0f, 0.0f},
    {"csm.stabilize", "Stabilise", "sun: bounding-sphere cascades snapped to whole texels so edges do not shimmer", "",
     1.0f, 0.0f, 1.0f, 1.0f, kOnOff, {}, kSunLightBit},
    {"csm.blendBandM", "Blend band", "camera depth (m) before each split where two cascades are mixed; at most half the shortest cascade", "m",
     2.0f, 0.0f, 100.0f, 0.0f},
    {"csm.marginTexels", "Margin", "border added around each cascade, in texels", "texels", 2.0f, 0.0f, 64.0f, 1.0f},
};

constexpr float kStepsPerOctave = 4.0f;  // stableFarDistance: ≤ 19% more depth than needed
constexpr float kSpotMinNearM = 0.01f;
// Stabilised cascades keep near/far of the whole scene: a range that moved with the camera
// would change the stored depths (and the constant bias in metres) from frame to frame.
constexpr float kDepthPaddingFraction = 1e-3f;

// The smallest sphere holding the symmetric frustum slice between depths a and b (metres,
// along the view axis); k2 = tan²(half fov x) + tan²(half fov y). Returns (centre depth, radius).
glm::vec2 sliceBoundingSphere(float a, float b, float k2) {
  // Equidistant from a near corner (a, a·√k2) and a far corner (b, b·√k2) on the axis.
  float c = 0.5f * (a + b) * (1.0f + k2);
  if (c >= b) return {b, b * std::sqrt(k2)};  // the far rectangle's circle already holds the near one
  return {c, std::sqrt((b - c) * (b - c) + b * b * k2)};
}

ShadowView stabilizedSunCascade(const Camera& camera, float aspect, const Light& light, const SceneExtent& scene,
                                float a, float b, int mapSize, float marginTexels) {
  glm::vec2 sphere;
  if (camera.orthographic()) {  // a box slice: its centre, and the half diagonal
    const float hy = camera.orthoHalfHeightM, hx = hy * aspect, hz = 0.5f * (b - a);
    sphere = {0.5f * (a + b), std::sqrt(hx * hx + hy * hy + hz * hz)};
  } else {
    const float ty = std::tan(0.5f * camera.fovYRad), tx = ty * aspect;
    sphere = sliceBoundingSphere(a, b, tx * tx + ty * ty);
  }
  // Half-size of the square: the sphere's radius plus the margin in texels of this map.
  const float half = sphere.y / (1.0f - 2.0f * marginTexels / static_cast<float>(mapSize));
  const glm::mat4 viewFromWorld = sunViewMatrix(scene, light);  // fixed basis: independent of the camera
  const glm::vec3 centre = camera.position + camera.forward() * sphere.x;
  return snappedSunView(scene, viewFromWorld, glm::vec2(viewFromWorld * glm::vec4(centre, 1.0f)), glm::vec2(half), mapSize);
}

}  // namespace

ShadowView snappedSunView(const SceneExtent& scene, const glm::mat4& viewFromWorld, const glm::vec2& centre,
                          const glm::vec2& half, int mapSize) {
  ShadowView v;
  v.viewFromWorld = viewFromWorld;
  // Snap the centre to the texel grid: the map moves only by whole texels.
  const glm::vec2 texelM = 2.0f * half / static_cast<float>(mapSize);
  const glm::vec2 snapped = glm::round(centre / texelM) * texelM;
  const Aabb sceneLs = scene.bounds().transformed(v.viewFromWorld);
  const float pad = (sceneLs.hi.z - sceneLs.lo.z) * kDepthPaddingFraction + 1e-4f;
  v.nearM = -sceneLs.hi.z - pad;
  v.farM = -sceneLs.lo.z + pad;
  v.perspective = false;
  v.extent = 2.0f * half;
  // The orthographic matrix written out rather than from its bounds (glm::ortho's r − l would
  // round differently for every snapped centre): scale 1/half is the same bits every frame and
  // the translation is −snapped/half = a whole number of texels (2/mapSize in NDC each).
  glm::mat4 ortho(1.0f);
  ortho[0][0] = 1.0f / half.x;
  ortho[1][1] = 1.0f / half.y;
  ortho[2][2] = -1.0f / (v.farM - v.nearM);
  ortho[3] = glm::vec4(-snapped / half, -v.nearM / (v.farM - v.nearM), 1.0f);
  v.clipFromWorld = ortho * v.viewFromWorld;
  v.depthPlane = linearDepthPlane(v.viewFromWorld, v.nearM, v.farM);
  return v;
}

ShadowView fittedCascade(const Camera& camera, float aspect, const Light& light, const SceneExtent& scene, float a, float b,
                         float marginFraction) {
  std::vector<glm::vec3> body = receiverBody(camera, aspect, a, b, scene, light);
  if (body.empty()) {  // the slice sees no part of the scene: fit its frustum so the map is valid
    const auto corners = frustumCorners(camera, aspect, a, b);
    body.assign(corners.begin(), corners.end());
  }
  const std::vector<glm::vec3> casters = casterExtrusion(body, light, scene.casterBounds());
  return fitLightView(scene, light, body, casters, marginFraction);
}

std::vector<float> practicalSplits(float nearM, float farM, int cascades, float lambda) {
  PN_CHECK(nearM > 0.0f && farM > nearM && cascades >= 1, "practicalSplits: need 0 < near < far and ≥ 1 cascade");
  std::vector<float> z(static_cast<size_t>(cascades) + 1);
  for (int i = 0; i <= cascades; ++i) {
    const float t = static_cast<float>(i) / static_cast<float>(cascades);
    const float logSplit = nearM * std::pow(farM / nearM, t);
    const float uniformSplit = nearM + (farM - nearM) * t;
    z[static_cast<size_t>(i)] = lambda * logSplit + (1.0f - lambda) * uniformSplit;
  }
  z.front() = nearM;  // exact ends (pow rounding)
  z.back() = farM;
  return z;
}

float stableFarDistance(float farM) {
  return std::exp2(std::ceil(std::log2(farM) * kStepsPerOctave) / kStepsPerOctave);
}

float stableNearDistance(float nearM, float cameraNearM) {
  return std::max(cameraNearM, std::exp2(std::floor(std::log2(nearM) * kStepsPerOctave) / kStepsPerOctave));
}

CascadedProjection::CascadedProjection() : Projection(kParams) {}

LightFrusta CascadedProjection::computeFrusta(const Camera& camera, float aspect, const Light& light,
                                              const SceneExtent& scene, int mapSize) const {
  const int count = paramInt("csm.cascades");
  const bool stabilize = paramInt("csm.stabilize") != 0 && light.type == LightType::Directional;
  float farM = shadowFarDistance(camera, scene);
  if (stabilize) farM = std::min(stableFarDistance(farM), std::max(camera.farM, farM));
  // The splits start at the nearest receiver the camera can see, not at its near plane: from above
  // a city (an aerial camera 120 m up) every cascade but the last covered empty air and the last
  // one spread over the whole view, 30x coarser than one uniform map. Stabilised cascades take
  // that depth in quarter-octave steps, as the far end, so it changes rarely as the camera moves.
  float nearM = camera.nearM;
  const std::vector<glm::vec3> visible = receiverBody(camera, aspect, camera.nearM, farM, scene, light);
  if (!visible.empty()) {
    const float nearest = std::max(std::min(cameraDepthRange(visible, camera).x, farM), camera.nearM);
    nearM = stabilize ? stableNearDistance(nearest, camera.nearM) : nearest;
  }
  farM = std::max(farM, nearM * 2.0f);
  const std::vector<float> z = practicalSplits(nearM, farM, count, param("csm.lambda"));
  float shortest = farM;
  for (int i = 0; i + 1 < count; ++i) shortest = std::min(shortest, z[static_cast<size_t>(i) + 1] - z[static_cast<size_t>(i)]);
  LightFrusta f;
  f.blendBandM = count > 1 ? std::min(param("csm.blendBandM"), 0.5f * shortest) : 0.0f;
  const float marginFraction = param("csm.marginTexels") / static_cast<float>(mapSize);
  for (int i = 0; i < count; ++i) {
    // Each cascade also covers the blend band before its own slice, where it is mixed in.
    const float a = i == 0 ? nearM : z[static_cast<size_t>(i)] - f.blendBandM;
    const float b = z[static_cast<size_t>(i) + 1];
    ShadowView v = stabilize ? stabilizedSunCascade(camera, aspect, light, scene, a, b, mapSize, param("csm.marginTexels"))
                             : fittedCascade(camera, aspect, light, scene, std::max(a, kSpotMinNearM), b, marginFraction);
    v.splitFarM = b;
    f.views.push_back(v);
  }
  return f;
}

}  // namespace penumbra
