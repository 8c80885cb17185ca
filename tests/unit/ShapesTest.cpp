// Procedural shapes: every vertex normal is unit length and points out of the solid, and every
// triangle winds counter-clockwise seen from outside (its cross-product normal agrees with its
// vertex normals and points away from the shape's centre). Bias modes, back-face culling and the
// lit pass all depend on these.
#include <penumbra/Error.h>
#include <penumbra/Scene.h>

#include <gtest/gtest.h>
#include <glm/glm.hpp>
#include <glm/gtc/constants.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <tuple>

using namespace penumbra;

namespace {

constexpr float kUnitTol = 1e-5f;        // |n| - 1, float normalisation error
constexpr float kFlatCosTol = 1e-5f;     // flat faces: face and vertex normals equal to this
constexpr float kDegenerateArea = 1e-9f; // m²: pole/apex slivers of zero area carry no winding
// A lathe triangle spans one slice (and one stack): its face normal and its vertices' smooth
// normals differ by less than the larger of those two angles.
float smoothMinCos(int slices, int stacks = 1) {
  return std::cos(std::max(glm::two_pi<float>() / static_cast<float>(slices), glm::pi<float>() / static_cast<float>(stacks)));
}

// What checkShape found: counts of each kind of defect and the first one, described.
struct ShapeReport {
  size_t triangles = 0, degenerate = 0;
  size_t nonUnit = 0, inward = 0, clockwise = 0, disagreeing = 0, badIndex = 0;
  std::string first;
  size_t defects() const { return nonUnit + inward + clockwise + disagreeing + badIndex; }
  void note(size_t& counter, const std::string& what) {
    if (defects() == 0) first = what;
    ++counter;
  }
};

std::string str(const glm::vec3& v) {
  return "(" + std::to_string(v.x) + ", " + std::to_string(v.y) + ", " + std::to_string(v.z) + ")";
}

// Checks every vertex (unit normal, `outward(p, n)`: the normal n at p points out of the solid)
// and every triangle (counter-clockwise from outside: its cross-product normal points away from
// `centre` and agrees with its vertex normals to at least minFaceVertexCos).
template <class Outward>
ShapeReport checkShape(const Mesh& m, const glm::vec3& centre, float minFaceVertexCos, Outward outward) {
  ShapeReport r;
  if (m.normals.size() != m.positions.size() || m.uvs.size() != m.positions.size())
    r.note(r.badIndex, "a shape has one normal and one uv per position");
  for (size_t i = 0; i < m.normals.size(); ++i) {
    const glm::vec3 &p = m.positions[i], &n = m.normals[i];
    if (std::abs(glm::length(n) - 1.0f) > kUnitTol)
      r.note(r.nonUnit, "vertex " + std::to_string(i) + " normal length " + std::to_string(glm::length(n)));
    if (!outward(p, n)) r.note(r.inward, "vertex " + std::to_string(i) + " at " + str(p) + " has normal " + str(n));
  }
  for (size_t t = 0; t + 2 < m.indices.size(); t += 3) {
    ++r.triangles;
    const uint32_t ia = m.indices[t], ib = m.indices[t + 1], ic = m.indices[t + 2];
    if (std::max({ia, ib, ic}) >= m.normals.size()) {
      r.note(r.badIndex, "triangle " + std::to_string(t / 3) + " indexes past the vertices");
      continue;
    }
    const glm::vec3 &a = m.positions[ia], &b = m.positions[ib], &c = m.positions[ic];
    const glm::vec3 cross = glm::cross(b - a, c - a);
    if (0.5f * glm::length(cross) < kDegenerateArea) {
      ++r.degenerate;
      continue;
    }
    const glm::vec3 face = glm::normalize(cross);
    const glm::vec3 centroid = (a + b + c) / 3.0f;
    if (glm::dot(face, centroid - centre) <= 0.0f)
      r.note(r.clockwise, "triangle " + std::to_string(t / 3) + " winds clockwise from outside, face normal " + str(face));
    for (uint32_t v : {ia, ib, ic})
      if (glm::dot(face, m.normals[v]) <= minFaceVertexCos)
        r.note(r.disagreeing, "triangle " + std::to_string(t / 3) + " face normal " + str(face) + " vs vertex normal " + str(m.normals[v]));
  }
  return r;
}

void expectClean(const Mesh& m, const ShapeReport& r) {
  EXPECT_FALSE(m.positions.empty()) << m.name;
  EXPECT_EQ(m.indices.size() % 3, 0u) << m.name;
  EXPECT_GT(r.triangles, r.degenerate) << m.name;
  EXPECT_EQ(r.defects(), 0u) << m.name << ": " << r.nonUnit << " non-unit, " << r.inward << " inward normals, "
                             << r.clockwise << " clockwise, " << r.disagreeing << " face/vertex disagreements, "
                             << r.badIndex << " bad indices; first: " << r.first;
}

bool near(float a, float b, float tol = 1e-5f) { return std::abs(a - b) <= tol; }

}  // namespace

TEST(Shapes, PlaneFacesUpAndWindsCounterClockwise) {
  const Mesh m = makePlane(4.0f, 2.0f);
  ASSERT_EQ(m.triangleCount(), 2u);
  // Seen from above (the outside of a plane), centre one metre below it.
  expectClean(m, checkShape(m, {0, -1, 0}, 1.0f - kFlatCosTol, [](const glm::vec3& p, const glm::vec3& n) {
    return near(p.y, 0.0f) && near(n.y, 1.0f);
  }));
  const Aabb b = m.bounds();
  EXPECT_NEAR(b.size().x, 4.0f, 1e-6f);
  EXPECT_NEAR(b.size().z, 2.0f, 1e-6f);
}

TEST(Shapes, GridIsThePlaneCutIntoCellsThatShareTheirEdges) {
  const Mesh m = makeGrid(4.0f, 2.0f, 3);
  ASSERT_EQ(m.triangleCount(), 2u * 3u * 3u);
  EXPECT_EQ(m.vertexCount(), 4u * 4u) << "one vertex per grid point: neighbours share edges exactly";
  expectClean(m, checkShape(m, {0, -1, 0}, 1.0f - kFlatCosTol, [](const glm::vec3& p, const glm::vec3& n) {
    return near(p.y, 0.0f) && near(n.y, 1.0f);
  }));
  const Aabb b = m.bounds();
  EXPECT_NEAR(b.size().x, 4.0f, 1e-6f);
  EXPECT_NEAR(b.size().z, 2.0f, 1e-6f);
  // The uv of makePlane: (0, 0) at (−x, +z).
  const Mesh plane = makePlane(4.0f, 2.0f);
  EXPECT_EQ(m.positions.front(), plane.positions.front());
  EXPECT_EQ(m.uvs.front(), plane.uvs.front());
  EXPECT_THROW(makeGrid(1.0f, 1.0f, 0), Error);
}

TEST(Shapes, BoxNormalsAreItsFaceAxesPointingOut) {
  const glm::vec3 size{1.0f, 2.0f, 0.5f};
  const Mesh m = makeBox(size);
  ASSERT_EQ(m.triangleCount(), 12u);
  const glm::vec3 h = 0.5f * size;
  const ShapeReport r = checkShape(m, {0, 0, 0}, 1.0f - kFlatCosTol, [&](const glm::vec3& p, const glm::vec3& n) {
    // The normal is one axis, and the vertex lies on that axis' face on the side it points to.
    for (int k = 0; k < 3; ++k) {
      if (near(std::abs(n[k]), 1.0f)) return near(p[k], n[k] * h[k]) && glm::dot(n, p) > 0.0f;
    }
    return false;
  });
  expectClean(m, r);
  // Every face axis appears: 4 vertices each of ±X, ±Y, ±Z.
  int perAxis[6] = {};
  for (const glm::vec3& n : m.normals)
    for (int k = 0; k < 3; ++k)
      if (near(std::abs(n[k]), 1.0f)) ++perAxis[2 * k + (n[k] > 0.0f ? 0 : 1)];
  for (int count : perAxis) EXPECT_EQ(count, 4);
}

TEST(Shapes, SphereNormalsArePositionsOverRadius) {
  // The default tessellation and a coarse one (whose pole slivers are large enough to count).
  for (const auto& [radius, slices, stacks] : {std::tuple{0.7f, 32, 16}, std::tuple{1.0f, 8, 4}}) {
    const Mesh m = makeSphere(radius, slices, stacks);
    const ShapeReport s = checkShape(m, {0, 0, 0}, smoothMinCos(slices, stacks), [&](const glm::vec3& p, const glm::vec3& n) {
      return near(glm::length(p), radius, 1e-5f) && glm::dot(n, p / radius) > 1.0f - 1e-4f;
    });
    expectClean(m, s);
    // Only the pole triangles (one per slice at each pole) may be slivers.
    EXPECT_LE(s.degenerate, 2u * static_cast<size_t>(slices)) << slices << "x" << stacks;
  }
}

TEST(Shapes, CylinderSidesPointRadiallyAndCapsAlongTheAxis) {
  const float radius = 0.3f, height = 1.5f;
  const Mesh m = makeCylinder(radius, height, 24);
  int side = 0, top = 0, bottom = 0;
  const ShapeReport r = checkShape(m, {0, 0.5f * height, 0}, smoothMinCos(24), [&](const glm::vec3& p, const glm::vec3& n) {
    const glm::vec2 radial{p.x, p.z};
    if (near(n.y, 1.0f)) {
      ++top;
      return near(p.y, height);
    }
    if (near(n.y, -1.0f)) {
      ++bottom;
      return near(p.y, 0.0f);
    }
    ++side;
    return near(n.y, 0.0f) && near(glm::length(radial), radius) &&
           glm::dot(glm::vec2(n.x, n.z), radial / radius) > 1.0f - 1e-4f;
  });
  expectClean(m, r);
  EXPECT_EQ(side, 2 * 25);
  EXPECT_EQ(top, 26);  // centre + 25 rim vertices
  EXPECT_EQ(bottom, 26);
}

TEST(Shapes, ConeSidesArePerpendicularToTheSlantAndTheBaseFacesDown) {
  const float radius = 0.4f, height = 1.2f;
  const Mesh m = makeCone(radius, height, 24);
  const glm::vec3 apex{0, height, 0};
  // The side normal leans up by atan(radius / height) from the horizontal.
  const float expectedNy = radius / std::sqrt(radius * radius + height * height);
  int side = 0, base = 0;
  const ShapeReport r = checkShape(m, {0, 0.5f * height, 0}, smoothMinCos(24), [&](const glm::vec3& p, const glm::vec3& n) {
    if (near(n.y, -1.0f)) {
      ++base;
      return near(p.y, 0.0f);
    }
    ++side;
    if (!near(n.y, expectedNy, 1e-5f)) return false;
    if (glm::length(p - apex) < 1e-6f) return true;  // the apex: any azimuth is right
    // A base-ring vertex: its normal is perpendicular to the slant line to the apex and leans out.
    return near(glm::dot(n, glm::normalize(apex - p)), 0.0f, 1e-5f) && glm::dot(glm::vec2(n.x, n.z), glm::vec2(p.x, p.z)) > 0.0f;
  });
  expectClean(m, r);
  EXPECT_EQ(side, 2 * 25);
  EXPECT_EQ(base, 26);
}

// The checks above can fail: a box with its winding reversed and a sphere with inward normals
// are both caught.
TEST(Shapes, ChecksCatchReversedWindingAndInwardNormals) {
  Mesh flipped = makeBox({1, 1, 1});
  for (size_t t = 0; t + 2 < flipped.indices.size(); t += 3) std::swap(flipped.indices[t + 1], flipped.indices[t + 2]);
  const auto outward = [](const glm::vec3& p, const glm::vec3& n) { return glm::dot(n, p) > 0.0f; };
  const ShapeReport f = checkShape(flipped, {0, 0, 0}, 1.0f - kFlatCosTol, outward);
  EXPECT_EQ(f.clockwise, 12u);
  EXPECT_EQ(f.disagreeing, 36u);
  EXPECT_EQ(f.inward, 0u);
  Mesh inward = makeSphere(1.0f, 8, 4);
  for (glm::vec3& n : inward.normals) n = -n;
  const ShapeReport i = checkShape(inward, {0, 0, 0}, smoothMinCos(8, 4), outward);
  EXPECT_EQ(i.inward, inward.vertexCount());
  EXPECT_EQ(i.clockwise, 0u);
  EXPECT_GT(i.disagreeing, 0u);
}
