// The distance field's data and geometry (SdfVolume.h): what the sdf filter needs on the GPU side
// and what any baker shares. The Embree bake itself is in src/bake/.
#include "techniques/sdf/SdfVolume.h"

#include "frame/CasterSet.h"

#include "base/Hash.h"

#include <penumbra/Error.h>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace penumbra::sdf {
namespace {

constexpr float kInfinity = std::numeric_limits<float>::infinity();

/// A triangle whose squared sine between its edges is below this is treated as a segment: the
/// barycentric solve of the face region would divide by ~0.
constexpr float kDegenerateSin2 = 1e-10f;

glm::vec3 closestPointOnSegment(const glm::vec3& p, const glm::vec3& a, const glm::vec3& b) {
  const glm::vec3 ab = b - a;
  const float len2 = glm::dot(ab, ab);
  if (len2 <= 0.0f) return a;
  return a + std::clamp(glm::dot(p - a, ab) / len2, 0.0f, 1.0f) * ab;
}

/// True when every vertex of the triangles lies in one plane (within kSheetFlatness of their size).
bool isFlat(const std::vector<glm::vec3>& triangles) {
  Aabb bounds;
  glm::vec3 normal(0.0f);
  for (size_t t = 0; t + 2 < triangles.size(); t += 3) {
    bounds.extend(triangles[t]);
    const glm::vec3 n = glm::cross(triangles[t + 1] - triangles[t], triangles[t + 2] - triangles[t]);
    if (glm::dot(n, n) > glm::dot(normal, normal)) normal = n;  // the largest triangle's plane
  }
  if (glm::dot(normal, normal) <= 0.0f) return false;
  normal = glm::normalize(normal);
  const float tolerance = kSheetFlatness * glm::length(bounds.size()) + std::numeric_limits<float>::min();
  for (const glm::vec3& p : triangles)
    if (std::abs(glm::dot(p - triangles[0], normal)) > tolerance) return false;
  return true;
}

Baker& installedBaker() {
  static Baker baker;
  return baker;
}

}  // namespace

SdfVolume gridForTriangles(const CasterTriangles& casters, int resolution) {
  PN_CHECK(resolution >= kMinResolution && resolution <= kMaxResolution,
           fmt::format("sdf: resolution {} is outside {}..{}", resolution, kMinResolution, kMaxResolution));
  SdfVolume v;
  v.sheets = casters.sheets;
  const std::vector<glm::vec3>& sized = casters.volume.empty() ? casters.sheets : casters.volume;
  if (sized.empty()) return v;
  Aabb bounds;
  for (const glm::vec3& p : sized) bounds.extend(p);
  const glm::vec3 extent = bounds.size();
  const float longest = std::max({extent.x, extent.y, extent.z});
  PN_CHECK(longest > 0.0f, "sdf: the shadow casters have zero extent");
  v.voxelM = longest / static_cast<float>(resolution - 2 * kPadVoxels);
  if (casters.volume.empty()) return v;
  for (int a = 0; a < 3; ++a) {
    // ceil with a little tolerance, so the longest axis gets exactly `resolution` voxels.
    const int inner = std::max(1, static_cast<int>(std::ceil(extent[a] / v.voxelM - 1e-3f)));
    v.dims[a] = inner + 2 * kPadVoxels;
  }
  v.lo = bounds.center() - 0.5f * glm::vec3(v.dims) * v.voxelM;
  return v;
}

glm::vec3 closestPointOnTriangle(const glm::vec3& p, const glm::vec3& a, const glm::vec3& b, const glm::vec3& c) {
  // Voronoi regions of the vertices, then the edges, then the face (Ericson, Real-Time
  // Collision Detection, 5.1.5), with a segment fallback for degenerate triangles.
  const glm::vec3 ab = b - a, ac = c - a;
  const glm::vec3 n = glm::cross(ab, ac);
  if (glm::dot(n, n) <= kDegenerateSin2 * glm::dot(ab, ab) * glm::dot(ac, ac)) {
    const glm::vec3 candidates[3] = {closestPointOnSegment(p, a, b), closestPointOnSegment(p, b, c),
                                     closestPointOnSegment(p, c, a)};
    glm::vec3 best = candidates[0];
    for (const glm::vec3& q : candidates)
      if (glm::dot(p - q, p - q) < glm::dot(p - best, p - best)) best = q;
    return best;
  }
  const glm::vec3 ap = p - a;
  const float d1 = glm::dot(ab, ap), d2 = glm::dot(ac, ap);
  if (d1 <= 0.0f && d2 <= 0.0f) return a;
  const glm::vec3 bp = p - b;
  const float d3 = glm::dot(ab, bp), d4 = glm::dot(ac, bp);
  if (d3 >= 0.0f && d4 <= d3) return b;
  const float vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0f && d1 >= 0.0f && d3 <= 0.0f) return a + (d1 / (d1 - d3)) * ab;
  const glm::vec3 cp = p - c;
  const float d5 = glm::dot(ab, cp), d6 = glm::dot(ac, cp);
  if (d6 >= 0.0f && d5 <= d6) return c;
  const float vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0f && d2 >= 0.0f && d6 <= 0.0f) return a + (d2 / (d2 - d6)) * ac;
  const float va = d3 * d6 - d5 * d4;
  if (va <= 0.0f && d4 - d3 >= 0.0f && d5 - d6 >= 0.0f) return b + ((d4 - d3) / ((d4 - d3) + (d5 - d6))) * (c - b);
  const float inv = 1.0f / (va + vb + vc);
  return a + ab * (vb * inv) + ac * (vc * inv);
}

CasterTriangles casterTriangles(std::span<const CasterGeometry> casters) {
  CasterTriangles out;
  size_t triangles = 0;
  for (const CasterGeometry& g : casters) triangles += g.triangleCount();
  out.volume.reserve(3 * triangles);
  std::vector<glm::vec3> object;
  for (const CasterGeometry& g : casters) {
    object.clear();
    for (size_t t = 0; t < g.triangleCount(); ++t)
      for (int c = 0; c < 3; ++c) object.push_back(glm::vec3(g.worldFromObject * glm::vec4(g.corner(t, c), 1.0f)));
    const bool sheet = !object.empty() && out.sheets.size() + object.size() <= 3 * static_cast<size_t>(kMaxSheetTriangles) && isFlat(object);
    std::vector<glm::vec3>& into = sheet ? out.sheets : out.volume;
    into.insert(into.end(), object.begin(), object.end());
  }
  return out;
}

SdfVolume gridFor(std::span<const CasterGeometry> casters, int resolution) {
  return gridForTriangles(casterTriangles(casters), resolution);
}

CasterTriangles casterTriangles(const Scene& scene) { return casterTriangles(casterGeometry(scene)); }
SdfVolume gridFor(const Scene& scene, int resolution) { return gridFor(casterGeometry(scene), resolution); }
uint64_t cacheKey(const Scene& scene, int resolution) { return cacheKey(casterGeometry(scene), resolution); }

Aabb SdfVolume::gridCasterBounds() const {
  Aabb b;
  if (!hasGrid()) return b;
  const glm::vec3 pad(static_cast<float>(kPadVoxels) * voxelM);
  b.extend(lo + pad);
  b.extend(hi() - pad);
  return b;
}

Aabb SdfVolume::casterBounds() const {
  Aabb b = gridCasterBounds();
  for (const glm::vec3& p : sheets) b.extend(p);
  return b;
}

float SdfVolume::sample(const glm::vec3& ws) const {
  PN_ASSERT(hasGrid());
  // Texel space: voxel centres at integers, as GL_LINEAR places them at (i + 0.5) / dims.
  const glm::vec3 u = (ws - lo) / voxelM - 0.5f;
  const glm::vec3 base = glm::floor(u);
  const glm::vec3 f = u - base;
  float result = 0.0f;
  for (int corner = 0; corner < 8; ++corner) {
    const glm::ivec3 offset(corner & 1, (corner >> 1) & 1, (corner >> 2) & 1);
    const glm::ivec3 cell = glm::clamp(glm::ivec3(base) + offset, glm::ivec3(0), dims - 1);
    const glm::vec3 w = glm::mix(1.0f - f, f, glm::vec3(offset));
    result += w.x * w.y * w.z * at(cell.x, cell.y, cell.z);
  }
  return result;
}

float SdfVolume::distance(const glm::vec3& ws) const {
  float d = kInfinity;
  if (hasGrid()) {
    const glm::vec3 q = glm::clamp(ws, lo, hi());
    d = sample(q);
    if (q != ws) {
      // Two lower bounds: the grid's nearest point less the way there (1-Lipschitz), and the
      // distance to the box the grid's casters lie in.
      const Aabb inner = gridCasterBounds();
      d = std::max(d - glm::length(ws - q), glm::length(glm::max(glm::max(inner.lo - ws, ws - inner.hi), 0.0f)));
    }
  }
  for (size_t t = 0; t + 2 < sheets.size(); t += 3) d = std::min(d, triangleDistance(ws, sheets[t], sheets[t + 1], sheets[t + 2]));
  return d;
}

float triangleDistance(const glm::vec3& p, const glm::vec3& a, const glm::vec3& b, const glm::vec3& c) {
  return glm::length(p - closestPointOnTriangle(p, a, b, c));
}

uint64_t cacheKey(std::span<const CasterGeometry> casters, int resolution) {
  Hasher hash;
  hash.text("penumbra sdf");
  hash.value(kSdfCodeVersion);
  hash.value(resolution);
  hash.value(kPadVoxels);
  const CasterTriangles triangles = casterTriangles(casters);
  hash.array(std::span<const glm::vec3>(triangles.volume));
  hash.array(std::span<const glm::vec3>(triangles.sheets));
  return hash.digest();
}

void setBaker(Baker baker) { installedBaker() = std::move(baker); }

const Baker& baker() { return installedBaker(); }

}  // namespace penumbra::sdf
