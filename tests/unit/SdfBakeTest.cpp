// The SDF bake against analytic signed distances, its sign rule on open and overlapping meshes,
// and its disk cache. Small grids (32 voxels on the long axis) keep each test well under a second.
#include "bake/SdfBake.h"

#include <penumbra/Error.h>
#include <penumbra/Scene.h>

#include <gtest/gtest.h>
#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <random>
#include <unistd.h>

namespace penumbra::sdf {
namespace {

constexpr int kTestResolution = 32;
constexpr int kRandomPoints = 2000;

/// A private cache directory per test, removed afterwards.
struct TempDir {
  std::filesystem::path path;
  TempDir() {
    path = std::filesystem::temp_directory_path() /
           ("penumbra-sdf-test-" + std::to_string(getpid()) + "-" + ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::remove_all(path);
    std::filesystem::create_directories(path);
  }
  ~TempDir() {
    std::error_code ignored;
    std::filesystem::remove_all(path, ignored);
  }
};

BakeOptions quiet(int resolution = kTestResolution) {
  BakeOptions o;
  o.resolution = resolution;
  o.progress = false;
  o.useCache = false;
  return o;
}

struct Errors {
  float maxAtVoxels = 0.0f;   // |baked − analytic| at voxel centres
  float maxSampled = 0.0f;    // |trilinear sample − analytic| at random points
  int wrongSigns = 0;         // voxels whose sign differs where |analytic| > the tessellation error
};

Errors compare(const SdfVolume& v, const std::function<float(glm::vec3)>& analytic, float signMargin) {
  Errors e;
  for (int k = 0; k < v.dims.z; ++k)
    for (int j = 0; j < v.dims.y; ++j)
      for (int i = 0; i < v.dims.x; ++i) {
        const float exact = analytic(v.voxelCenter(i, j, k));
        const float baked = v.at(i, j, k);
        e.maxAtVoxels = std::max(e.maxAtVoxels, std::abs(baked - exact));
        if (std::abs(exact) > signMargin && (baked < 0.0f) != (exact < 0.0f)) ++e.wrongSigns;
      }
  std::mt19937 rng(12345);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  for (int n = 0; n < kRandomPoints; ++n) {
    const glm::vec3 p = v.lo + glm::vec3(unit(rng), unit(rng), unit(rng)) * v.size();
    e.maxSampled = std::max(e.maxSampled, std::abs(v.sample(p) - analytic(p)));
  }
  return e;
}

float halfVoxelDiagonal(const SdfVolume& v) { return 0.5f * std::sqrt(3.0f) * v.voxelM; }

TEST(SdfBake, SphereMatchesAnalyticDistance) {
  const glm::vec3 centre{0.1f, 0.2f, -0.3f};
  constexpr float kRadiusM = 0.5f;
  constexpr int kSlices = 96, kStacks = 48;
  Scene scene;
  addObject(scene, "sphere", makeSphere(kRadiusM, kSlices, kStacks), glm::vec3(1.0f), glm::translate(glm::mat4(1.0f), centre));
  const SdfVolume v = bake(scene, quiet());
  ASSERT_FALSE(v.empty());
  EXPECT_EQ(std::max({v.dims.x, v.dims.y, v.dims.z}), kTestResolution);
  // The mesh is inscribed in the sphere: its faces lie inside by at most R(1 − cos(π/slices)·cos(π/stacks)).
  const float tessellationM = kRadiusM * (1.0f - std::cos(glm::pi<float>() / kSlices) * std::cos(glm::pi<float>() / kStacks));
  const Errors e = compare(v, [&](glm::vec3 p) { return glm::length(p - centre) - kRadiusM; }, tessellationM);
  EXPECT_LE(e.maxAtVoxels, 2.0f * tessellationM + 1e-5f);  // ±t between a facet and the sphere (see the cylinder)
  EXPECT_EQ(e.wrongSigns, 0);
  EXPECT_LE(e.maxSampled, halfVoxelDiagonal(v));
  std::printf("sphere: voxel %.4f m, max error at voxels %.5f m (tessellation %.5f m), at %d random points %.5f m "
              "(half voxel diagonal %.5f m)\n",
              v.voxelM, e.maxAtVoxels, tessellationM, kRandomPoints, e.maxSampled, halfVoxelDiagonal(v));
}

TEST(SdfBake, RotatedBoxMatchesAnalyticDistance) {
  const glm::vec3 halfSize{0.4f, 0.25f, 0.15f};
  const glm::mat4 worldFromBox = glm::rotate(glm::translate(glm::mat4(1.0f), {0.3f, -0.1f, 0.2f}), 0.6f, glm::normalize(glm::vec3(1, 2, 0.5f)));
  const glm::mat4 boxFromWorld = glm::inverse(worldFromBox);
  Scene scene;
  addObject(scene, "box", makeBox(2.0f * halfSize), glm::vec3(1.0f), worldFromBox);
  const SdfVolume v = bake(scene, quiet());
  auto boxSdf = [&](glm::vec3 p) {
    const glm::vec3 q = glm::abs(glm::vec3(boxFromWorld * glm::vec4(p, 1.0f))) - halfSize;
    return glm::length(glm::max(q, 0.0f)) + std::min(std::max({q.x, q.y, q.z}), 0.0f);
  };
  constexpr float kFloatToleranceM = 2e-5f;  // a box mesh is exact; what is left is float rounding
  const Errors e = compare(v, boxSdf, kFloatToleranceM);
  EXPECT_LE(e.maxAtVoxels, kFloatToleranceM);
  EXPECT_EQ(e.wrongSigns, 0);
  EXPECT_LE(e.maxSampled, halfVoxelDiagonal(v));
  std::printf("box: voxel %.4f m, max error at voxels %.6f m, at %d random points %.5f m (half voxel diagonal %.5f m)\n",
              v.voxelM, e.maxAtVoxels, kRandomPoints, e.maxSampled, halfVoxelDiagonal(v));
}

TEST(SdfBake, ThinTiltedCylinderHasRightSigns) {
  // The pen scene's pencil: a cylinder only a few voxels across, leaning across the grid axes.
  constexpr float kRadiusM = 0.04f, kLengthM = 1.5f, kLeanRad = 0.45f;
  constexpr int kSlices = 24;
  const glm::vec3 axis{-std::cos(kLeanRad), std::sin(kLeanRad), 0.0f};
  const glm::mat4 worldFromCylinder = glm::rotate(glm::mat4(1.0f), glm::half_pi<float>() - kLeanRad, {0, 0, 1});
  Scene scene;
  addObject(scene, "pencil", makeCylinder(kRadiusM, kLengthM, kSlices), glm::vec3(1.0f), worldFromCylinder);
  const SdfVolume v = bake(scene, quiet(kDefaultResolution));
  auto cylinderSdf = [&](glm::vec3 p) {
    const float along = glm::dot(p, axis);
    const glm::vec2 q{glm::length(p - along * axis) - kRadiusM, std::abs(along - 0.5f * kLengthM) - 0.5f * kLengthM};
    return std::min(std::max(q.x, q.y), 0.0f) + glm::length(glm::max(q, 0.0f));
  };
  const float tessellationM = kRadiusM * (1.0f - std::cos(glm::pi<float>() / kSlices));
  const Errors e = compare(v, cylinderSdf, tessellationM + 1e-5f);
  EXPECT_EQ(e.wrongSigns, 0);
  // A voxel between a flat facet and the true surface is outside one and inside the other:
  // −t versus +t, so twice the tessellation error is the bound there.
  EXPECT_LE(e.maxAtVoxels, 2.0f * tessellationM + 1e-5f);
  EXPECT_LE(e.maxSampled, halfVoxelDiagonal(v));
}

TEST(SdfBake, FlatSheetIsExactAndPositiveOnBothSides) {
  Scene scene;
  addObject(scene, "floor", makePlane(2.0f, 1.0f), glm::vec3(1.0f));
  const SdfVolume v = bake(scene, quiet());
  ASSERT_FALSE(v.empty());
  EXPECT_FALSE(v.hasGrid());  // an open flat mesh is measured analytically
  EXPECT_EQ(v.sheets.size(), 6u);
  EXPECT_GT(v.voxelM, 0.0f);  // epsilons in voxels keep a scale
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> coordinate(-2.0f, 2.0f);
  float maxError = 0.0f, minValue = 1e9f;
  for (int n = 0; n < kRandomPoints; ++n) {
    const glm::vec3 p{coordinate(rng), coordinate(rng), coordinate(rng)};
    const glm::vec3 q = glm::max(glm::abs(glm::vec3(p.x, 0.0f, p.z)) - glm::vec3(1.0f, 0.0f, 0.5f), 0.0f);
    const float exact = std::sqrt(q.x * q.x + p.y * p.y + q.z * q.z);
    maxError = std::max(maxError, std::abs(v.distance(p) - exact));
    minValue = std::min(minValue, v.distance(p));
  }
  EXPECT_LE(maxError, 1e-5f);
  EXPECT_GE(minValue, 0.0f);
}

TEST(SdfBake, FloorDoesNotStretchTheGrid) {
  // A 24 m floor under a 1 m box: the grid spans the box only, the floor is a sheet.
  Scene scene;
  addObject(scene, "floor", makePlane(24.0f, 24.0f), glm::vec3(1.0f));
  addObject(scene, "box", makeBox(glm::vec3(1.0f)), glm::vec3(1.0f), glm::translate(glm::mat4(1.0f), {0.0f, 0.5f, 0.0f}));
  const SdfVolume v = bake(scene, quiet());
  ASSERT_TRUE(v.hasGrid());
  EXPECT_EQ(v.sheets.size(), 6u);
  EXPECT_NEAR(v.voxelM, 1.0f / (kTestResolution - 2 * kPadVoxels), 1e-6f);
  EXPECT_NEAR(v.distance({5.0f, 0.3f, -7.0f}), 0.3f, 1e-5f);       // far from the box: the floor
  EXPECT_NEAR(v.distance({0.0f, 1.25f, 0.0f}), 0.25f, 1e-3f);      // above the box: the grid
  EXPECT_LT(v.distance({0.0f, 0.5f, 0.0f}), -0.45f);                // inside the box
  const Aabb all = v.casterBounds();
  EXPECT_NEAR(all.lo.x, -12.0f, 1e-5f);
  EXPECT_NEAR(all.hi.y, 1.0f, 1e-5f);
}

TEST(SdfBake, TooManySheetTrianglesGoToTheGrid) {
  Scene scene;
  for (int i = 0; i < kMaxSheetTriangles / 2 + 1; ++i)  // two triangles per plane: one plane too many
    addObject(scene, "tile", makePlane(1.0f, 1.0f), glm::vec3(1.0f), glm::translate(glm::mat4(1.0f), {1.1f * static_cast<float>(i), 0.2f * static_cast<float>(i), 0.0f}));
  const SdfVolume v = bake(scene, quiet());
  EXPECT_EQ(v.sheets.size(), 3u * kMaxSheetTriangles);
  EXPECT_TRUE(v.hasGrid());
}

TEST(SdfBake, OverlappingSpheresAreInsideWhereTheyOverlap) {
  // Ray parity would call the overlap "outside" (two surfaces crossed); winding numbers do not.
  constexpr float kRadiusM = 0.5f;
  Scene scene;
  addObject(scene, "a", makeSphere(kRadiusM, 48, 24), glm::vec3(1.0f), glm::translate(glm::mat4(1.0f), {-0.25f, 0, 0}));
  addObject(scene, "b", makeSphere(kRadiusM, 48, 24), glm::vec3(1.0f), glm::translate(glm::mat4(1.0f), {0.25f, 0, 0}));
  const SdfVolume v = bake(scene, quiet());
  auto unionSdf = [&](glm::vec3 p) {
    return std::min(glm::length(p - glm::vec3(-0.25f, 0, 0)), glm::length(p - glm::vec3(0.25f, 0, 0))) - kRadiusM;
  };
  constexpr float kSignMarginM = 0.01f;  // beyond the 48×24 tessellation error (≈ 3 mm)
  const Errors e = compare(v, unionSdf, kSignMarginM);
  EXPECT_EQ(e.wrongSigns, 0);
  EXPECT_LT(v.sample({0.0f, 0.0f, 0.0f}), -0.2f);  // the overlap's centre lies ≈ 0.43 m deep (the sphere surfaces)
}

TEST(SdfBake, ClosestPointOnDegenerateTriangleIsFinite) {
  const glm::vec3 p{0.3f, 1.0f, -0.2f};
  const glm::vec3 collinear = closestPointOnTriangle(p, {0, 0, 0}, {1, 0, 0}, {2, 0, 0});
  EXPECT_NEAR(glm::length(collinear - glm::vec3(0.3f, 0, 0)), 0.0f, 1e-6f);
  const glm::vec3 point = closestPointOnTriangle(p, {1, 1, 1}, {1, 1, 1}, {1, 1, 1});
  EXPECT_EQ(point, glm::vec3(1, 1, 1));
  const glm::vec3 face = closestPointOnTriangle({0.2f, 0.5f, 0.2f}, {0, 0, 0}, {1, 0, 0}, {0, 0, 1});
  EXPECT_NEAR(glm::length(face - glm::vec3(0.2f, 0, 0.2f)), 0.0f, 1e-6f);
}

TEST(SdfBake, CacheStoresReloadsAndIgnoresCorruptFiles) {
  const TempDir dir;
  Scene scene;
  addObject(scene, "box", makeBox({0.5f, 0.3f, 0.2f}), glm::vec3(1.0f));
  BakeOptions o = quiet(16);
  o.useCache = true;
  o.cacheDir = dir.path;
  const SdfVolume first = loadOrBake(scene, o);
  EXPECT_FALSE(first.stats.fromCache);
  const std::filesystem::path file = cacheFilePath(dir.path, cacheKey(scene, 16));
  ASSERT_TRUE(std::filesystem::exists(file));
  const SdfVolume second = loadOrBake(scene, o);
  EXPECT_TRUE(second.stats.fromCache);
  EXPECT_EQ(second.dims, first.dims);
  EXPECT_EQ(second.lo, first.lo);
  EXPECT_EQ(second.distances, first.distances);

  // Flip one payload byte: the hash no longer matches, the file is ignored and baked over.
  {
    std::fstream f(file, std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(static_cast<std::streamoff>(std::filesystem::file_size(file) - 3));
    f.put('\x5a');
  }
  const SdfVolume third = loadOrBake(scene, o);
  EXPECT_FALSE(third.stats.fromCache);
  EXPECT_EQ(third.distances, first.distances);
  // Truncated: ignored too.
  std::filesystem::resize_file(file, 40);
  EXPECT_FALSE(loadOrBake(scene, o).stats.fromCache);
  EXPECT_TRUE(loadOrBake(scene, o).stats.fromCache);
  // No temporaries left behind.
  int files = 0;
  for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator(dir.path)) ++files;
  EXPECT_EQ(files, 1);
}

TEST(SdfBake, CacheKeyFollowsGeometryAndResolution) {
  Scene a;
  addObject(a, "box", makeBox({0.5f, 0.3f, 0.2f}), glm::vec3(1.0f));
  Scene moved = a;
  moved.objects[0].worldFromObject = glm::translate(glm::mat4(1.0f), {0.0f, 1e-3f, 0.0f});
  Scene notCasting = a;
  addObject(notCasting, "floor", makePlane(4, 4), glm::vec3(1.0f), glm::mat4(1.0f), false);
  EXPECT_NE(cacheKey(a, 32), cacheKey(a, 64));
  EXPECT_NE(cacheKey(a, 32), cacheKey(moved, 32));
  EXPECT_EQ(cacheKey(a, 32), cacheKey(notCasting, 32));  // receivers do not enter the field
}

TEST(SdfBake, RejectsBadResolution) {
  Scene scene;
  addObject(scene, "box", makeBox(glm::vec3(1.0f)), glm::vec3(1.0f));
  EXPECT_THROW(bake(scene, quiet(kMinResolution - 1)), Error);
  EXPECT_THROW(bake(scene, quiet(kMaxResolution + 1)), Error);
}

// Benchmark, not a test (run with --gtest_also_run_disabled_tests): ~100k triangles of spheres
// at the default 128³; the budget is 60 s on 2 cores.
TEST(SdfBakeBench, DISABLED_HundredThousandTriangles) {
  Scene scene;
  constexpr int kSide = 5;  // 5³ = 125 spheres of 32 × 13 quads = 800 triangles each
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> jitter(-0.3f, 0.3f), radius(0.25f, 0.6f);
  for (int x = 0; x < kSide; ++x)
    for (int y = 0; y < kSide; ++y)
      for (int z = 0; z < kSide; ++z)
        addObject(scene, "s", makeSphere(radius(rng), 32, 13), glm::vec3(1.0f),
                  glm::translate(glm::mat4(1.0f), glm::vec3(x, y, z) + glm::vec3(jitter(rng), jitter(rng), jitter(rng))));
  BakeOptions o = quiet(kDefaultResolution);
  o.verbose = true;
  const SdfVolume v = bake(scene, o);
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  std::printf("bench: %zu triangles, %dx%dx%d voxels, %.2f s on %ld hardware threads, grid %.1f MiB, transient %.1f MiB, "
              "process peak RSS %.1f MiB\n",
              v.stats.triangles, v.dims.x, v.dims.y, v.dims.z, v.stats.seconds, sysconf(_SC_NPROCESSORS_ONLN),
              static_cast<double>(v.stats.gridBytes) / (1 << 20), static_cast<double>(v.stats.scratchBytes) / (1 << 20),
              static_cast<double>(usage.ru_maxrss) / 1024.0);
  // The filter hashes the casters every frame to notice a new scene: what that costs here.
  const auto hashStart = std::chrono::steady_clock::now();
  const uint64_t key = cacheKey(scene, kDefaultResolution);
  const double hashMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - hashStart).count();
  std::printf("bench: per-frame scene check (cacheKey) %.2f ms (key %016llx)\n", hashMs, static_cast<unsigned long long>(key));
  EXPECT_GE(v.stats.triangles, 100000u);
  EXPECT_LT(v.stats.seconds, 60.0);
}

}  // namespace
}  // namespace penumbra::sdf
