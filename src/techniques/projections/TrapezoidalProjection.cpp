#include "techniques/projections/TrapezoidalProjection.h"

#include "techniques/projections/LightSpace.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

namespace penumbra {
namespace {

constexpr ParamDesc kParams[] = {
    {"tsm.focusDistanceM", "Focus distance", "depth (m) past the nearest visible receiver up to which the focus region reaches; mapped to focusMapFraction of the map", "m",
     20.0f, 0.1f, 10000.0f, 0.0f},
    {"tsm.focusMapFraction", "Focus share", "share of the map's height the focus region is mapped to (the paper's 80% rule)", "of the map",
     0.8f, 0.05f, 0.95f, 0.0f},
    {"tsm.marginTexels", "Margin", "border added around the trapezoid, in texels", "texels", 2.0f, 0.0f, 64.0f, 1.0f},
};

// The centre line must span at least this much of the unwarped map (NDC units, the map is 2
// wide) for a trapezoid to make sense; shorter means the receivers lie all around the camera's
// point in the light's image plane (the camera looks along the light).
constexpr float kMinCentreLineNdc = 0.05f;
// Twice a hull's area (NDC²) below which it counts as a point or a line: the points' mean is used.
constexpr double kMinHullArea2 = 1e-12;
// The centroid line replaces the view axis' when its focus point gets this many times the texels.
constexpr float kCentroidGain = 2.0f;
// The apex is kept between these multiples of the trapezoid's height behind its top edge: closer
// would put a singularity at the camera, farther is a uniform map with rounding noise.
constexpr float kMinApexOverHeight = 1e-3f;
constexpr float kMaxApexOverHeight = 1e4f;

glm::vec2 toNdc(const glm::mat4& clip, const glm::vec3& p, bool& valid) {
  const glm::vec4 c = clip * glm::vec4(p, 1.0f);
  valid = valid && c.w > 0.0f;
  return glm::vec2(c) / c.w;
}

struct TrapezoidFit {
  glm::mat4 warp{1.0f};
  float focusTexelDensity = 0.0f;  ///< warped area per unwarped area at the focus point (|det J|)
};

// The trapezoid around the receivers' image `hull` along the unit centre line u from the camera's
// point `top`, with the 80% rule placing `focus`; empty when the region has no extent along u.
std::optional<TrapezoidFit> fitTrapezoid(const std::vector<glm::vec2>& hull, const glm::vec2& top,
                                         const glm::vec2& focus, const glm::vec2& u, float mapFraction,
                                         float marginFraction) {
  const glm::vec2 extent = extentAlong(hull, top, u);
  const float lambda = extent.y - extent.x;
  if (lambda <= 0.0f) return std::nullopt;
  const float delta = std::clamp(glm::dot(focus - top, u) - extent.x, 0.0f, lambda);
  const float eta = std::clamp(trapezoidApexDistance(lambda, delta, mapFraction), kMinApexOverHeight * lambda,
                               kMaxApexOverHeight * lambda);
  TrapezoidFit fit;
  fit.warp = trapezoidAround(hull, top, u, eta, marginFraction);
  // A plane homography H (rows x, y, w over (x, y, 1)) scales areas by det(H) / w³.
  const glm::dmat3 h(glm::dvec3(fit.warp[0][0], fit.warp[0][1], fit.warp[0][3]),
                     glm::dvec3(fit.warp[1][0], fit.warp[1][1], fit.warp[1][3]),
                     glm::dvec3(fit.warp[3][0], fit.warp[3][1], fit.warp[3][3]));
  const double w = fit.warp[0][3] * focus.x + fit.warp[1][3] * focus.y + fit.warp[3][3];
  fit.focusTexelDensity = static_cast<float>(std::abs(glm::determinant(h) / (w * w * w)));
  return fit;
}

}  // namespace

glm::vec2 hullAreaCentroid(std::vector<glm::vec2> points) {
  glm::vec2 mean(0.0f);
  for (const glm::vec2& p : points) mean += p / static_cast<float>(points.size());
  if (points.size() < 3) return mean;
  std::sort(points.begin(), points.end(), [](const glm::vec2& a, const glm::vec2& b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
  const auto cross = [](const glm::vec2& o, const glm::vec2& a, const glm::vec2& b) {
    return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
  };
  std::vector<glm::vec2> hull(2 * points.size());
  size_t k = 0;
  for (size_t i = 0; i < points.size(); ++i) {  // lower chain
    while (k >= 2 && cross(hull[k - 2], hull[k - 1], points[i]) <= 0.0f) --k;
    hull[k++] = points[i];
  }
  for (size_t i = points.size() - 1, lower = k + 1; i-- > 0;) {  // upper chain
    while (k >= lower && cross(hull[k - 2], hull[k - 1], points[i]) <= 0.0f) --k;
    hull[k++] = points[i];
  }
  hull.resize(k > 0 ? k - 1 : 0);  // the last point repeats the first
  // Shoelace sums about the mean (small numbers, less cancellation).
  double area2 = 0.0, cx = 0.0, cy = 0.0;
  for (size_t i = 0; i < hull.size(); ++i) {
    const glm::dvec2 a(hull[i] - mean), b(hull[(i + 1) % hull.size()] - mean);
    const double c = a.x * b.y - b.x * a.y;
    area2 += c;
    cx += (a.x + b.x) * c;
    cy += (a.y + b.y) * c;
  }
  if (std::abs(area2) < kMinHullArea2) return mean;
  return mean + glm::vec2(static_cast<float>(cx / (3.0 * area2)), static_cast<float>(cy / (3.0 * area2)));
}

float trapezoidApexDistance(float lambda, float delta, float mapFraction) {
  const float denominator = mapFraction * lambda - delta;
  if (denominator <= 0.0f) return std::numeric_limits<float>::infinity();
  return (1.0f - mapFraction) * lambda * delta / denominator;
}

glm::mat4 trapezoidWarp(const glm::vec2& q, const glm::vec2& u, float eta, float lambda, float tMin, float tMax) {
  // Frame at the apex: a = distance along u (the homogeneous w), b = offset across it.
  // x = (b/a − tMid)/tHalf spans the sides; y = A − B/a maps a = η → −1 and a = η + λ → +1
  // with A = 1 + 2η/λ, B = 2η(η + λ)/λ (a 1-D perspective along the centre line).
  const glm::vec2 v(-u.y, u.x);
  const float tMid = 0.5f * (tMax + tMin), tHalf = 0.5f * (tMax - tMin);
  const float A = 1.0f + 2.0f * eta / lambda, B = 2.0f * eta * (eta + lambda) / lambda;
  const float qu = glm::dot(q, u), qv = glm::dot(q, v);
  glm::mat4 m(0.0f);  // m[column][row], acting on (x, y, z, w) of the unwarped clip space
  const glm::vec3 rowX = glm::vec3(v.x - tMid * u.x, v.y - tMid * u.y, -qv + tMid * qu) / tHalf;
  const glm::vec3 rowY(A * u.x, A * u.y, -A * qu - B);
  const glm::vec3 rowW(u.x, u.y, -qu);
  const glm::vec3 rows[4] = {rowX, rowY, 0.5f * rowW, rowW};
  for (int r = 0; r < 4; ++r) {
    m[0][r] = rows[r].x;
    m[1][r] = rows[r].y;
    m[3][r] = rows[r].z;
  }
  return m;
}

glm::vec2 extentAlong(std::span<const glm::vec2> hull, const glm::vec2& top, const glm::vec2& u) {
  glm::vec2 range(std::numeric_limits<float>::max(), -std::numeric_limits<float>::max());
  for (const glm::vec2& h : hull) {
    const float s = glm::dot(h - top, u);
    range = {std::min(range.x, s), std::max(range.y, s)};
  }
  return range;
}

glm::mat4 trapezoidAround(std::span<const glm::vec2> hull, const glm::vec2& top, const glm::vec2& u, float eta,
                          float marginFraction) {
  const glm::vec2 v(-u.y, u.x);
  // Top and base edges: perpendicular to u, touching the region.
  const glm::vec2 extent = extentAlong(hull, top, u);
  const float lambda = extent.y - extent.x;
  const glm::vec2 q = top + u * (extent.x - eta);
  // Sides: the widest tangents from the apex to the region.
  float tMin = std::numeric_limits<float>::max(), tMax = -tMin;
  for (const glm::vec2& h : hull) {
    const float t = glm::dot(h - q, v) / glm::dot(h - q, u);
    tMin = std::min(tMin, t);
    tMax = std::max(tMax, t);
  }
  const float widen = (tMax - tMin) * marginFraction + 1e-6f;
  tMin -= widen;
  tMax += widen;
  // The margin along u: the top edge moves toward the apex, the base away from it, each by
  // marginFraction of the map measured in warped y = A − B/a (dy/da = B/a², B = 2η(η+λ)/λ):
  // Δ = 2·marginFraction / (dy/da) at a = η and at a = η + λ. Both tend to marginFraction·λ as the
  // apex recedes (no warp); a margin proportional to η instead grew with it (at the apex clamp of
  // 1e4·λ the base edge landed 40λ away and the scene filled a sliver of the map).
  const float topMargin = marginFraction * lambda * eta / (eta + lambda);
  const float baseMargin = marginFraction * lambda * (eta + lambda) / eta;
  return trapezoidWarp(q, u, eta - topMargin, lambda + topMargin + baseMargin, tMin, tMax);
}

TrapezoidalProjection::TrapezoidalProjection() : Projection(kParams) {}

LightFrusta TrapezoidalProjection::computeFrusta(const Camera& camera, float aspect, const Light& light,
                                                 const SceneExtent& scene, int mapSize) const {
  const float marginFraction = param("tsm.marginTexels") / static_cast<float>(mapSize);
  const ViewRegion region = wholeViewRegion(camera, aspect, light, scene);
  const std::vector<glm::vec3>& body = region.body;
  const float nearM = region.nearM, farM = region.farM;
  LightFrusta f;
  ShadowView base = fitLightView(scene, light, body, region.casters, 0.0f);
  f.views.push_back(base);
  if (body.empty()) return f;

  // The centre line starts at the camera's point in the light's image plane; the focus point is the
  // view axis tsm.focusDistanceM past the nearest receiver.
  const glm::vec3 fwd = camera.forward();
  const glm::vec2 depths = cameraDepthRange(body, camera);
  const float depthLo = std::max(std::min(depths.x, farM), nearM), depthHi = std::max(depths.y, nearM);
  bool valid = true;
  const glm::vec2 top = toNdc(base.clipFromWorld, camera.position + fwd * depthLo, valid);
  // The focus region starts at the nearest receiver (the paper's near plane, were it tight): from
  // 120 m above a city, a focus at 20 m from the camera lay in empty air, the 80% rule then put
  // the apex on the top edge, and the map's median went to 7.1 screen px per texel (1.4 now).
  const float focusDepth = std::min(depthLo + param("tsm.focusDistanceM"), depthHi);
  const glm::vec2 focus = toNdc(base.clipFromWorld, camera.position + fwd * focusDepth, valid);
  std::vector<glm::vec2> hull;
  for (const glm::vec3& p : body) hull.push_back(toNdc(base.clipFromWorld, p, valid));
  if (!valid) return f;
  // The centre line runs from the camera's point along the image of the view axis (the paper's),
  // or toward the area centroid of the receivers' region when that gives the focus point more
  // than kCentroidGain times the texels. A camera that looks down at the ground has its axis leave
  // the receivers a few metres ahead, and the axis' image can then point away from where they
  // spread: the sides open nearly flat and the map keeps uniform's density (city from its bench,
  // looking away from the sun: 498 screen px per texel near the camera; along the centroid 0.17,
  // ×298 the focus texels). From the built-in scenes' cameras the two lines are within ×0.92–×1.20
  // of each other and the axis stays.
  const auto fitAlong = [&](const glm::vec2& end, bool ok) -> std::optional<TrapezoidFit> {
    if (!ok || glm::length(end - top) < kMinCentreLineNdc) return std::nullopt;  // looking along the light
    return fitTrapezoid(hull, top, focus, glm::normalize(end - top), param("tsm.focusMapFraction"), marginFraction);
  };
  bool axisValid = true;  // a spot light may see the axis' far end from behind
  const glm::vec2 axisEnd = toNdc(base.clipFromWorld, camera.position + fwd * depthHi, axisValid);
  std::optional<TrapezoidFit> best = fitAlong(axisEnd, axisValid);
  const std::optional<TrapezoidFit> centred = fitAlong(hullAreaCentroid(hull), true);
  if (centred && (!best || centred->focusTexelDensity > kCentroidGain * best->focusTexelDensity)) best = centred;
  if (!best) return f;

  ShadowView& w = f.views.front();
  w.clipFromWorld = best->warp * base.clipFromWorld;
  w.warped = true;
  return f;
}

}  // namespace penumbra
