#pragma once
// Embree 3 BVH of a Scene's shadow casters in world space: the same triangles, with the same
// transforms, that the renderer rasterises. Answers occlusion queries only. Each caster's geometry
// ID is its index in Scene::objects and its primitive IDs are its mesh's triangle indices, the
// numbering the G-buffer records (GBufferData::triangle), so a ray can skip its receiver's own
// triangle.
#include <penumbra/Reference.h>
#include <penumbra/Scene.h>

#include <glm/glm.hpp>

#include <atomic>
#include <cstdint>
#include <limits>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include <embree3/rtcore_ray.h>

typedef struct RTCDeviceTy* RTCDevice;
typedef struct RTCSceneTy* RTCScene;

namespace penumbra::reference {

/// A triangle: object index in Scene::objects, triangle index in its mesh.
struct TriangleId {
  static constexpr uint32_t kNoObject = ~0u;  ///< no triangle
  uint32_t object = kNoObject, triangle = 0;
};

/// What the occlusion filter of one geometry needs: for an alpha mask, uvs by triangle and the
/// texture; for a translucent caster, its transmittance.
struct FilteredGeometry {
  std::vector<glm::vec2> uvs;      ///< three per triangle, in triangle order (alpha mask only)
  const Image* image = nullptr;    ///< RGBA8, row 0 = top; owned by EmbreeScene; null = no alpha mask
  float alphaCutoff = 0.5f;
  uint32_t object = 0;             ///< its geometry ID
  bool translucent = false;
  glm::vec3 transmittance{0.0f};   ///< Material::transmittance, when translucent
};

/// The most distinct translucent triangles one ray counts; a ray that crosses more is blocked
/// (docs/reference.md, "Translucent casters").
inline constexpr uint32_t kMaxTranslucentCrossings = 32;

/// One ray's light through the translucent casters it has crossed so far: the product of their
/// transmittances, and which triangles they were (Embree may report a triangle twice when the BVH
/// split it: each counts once).
struct RayTransmittance {
  glm::vec3 product{1.0f};
  uint32_t crossings = 0;
  TriangleId crossed[kMaxTranslucentCrossings];
};

/// The last error Embree reported through its callback.
struct EmbreeErrorLog {
  std::mutex mutex;
  std::string last;
};

/// What Embree allocates (its memory-monitor callback): bytes held now and the most held at once.
struct EmbreeMemory {
  std::atomic<int64_t> current{0};
  std::atomic<int64_t> peak{0};
};


class EmbreeScene {
public:
  /// Throws penumbra::Error if Embree fails (the message is Embree's). With MeshStorage::Borrowed
  /// Embree reads `scene`'s index arrays (and the positions of objects placed at the identity) in
  /// place: `scene` must outlive this, unchanged.
  explicit EmbreeScene(const Scene& scene, MeshStorage storage = MeshStorage::Copied);
  EmbreeScene(const EmbreeScene&) = delete;
  EmbreeScene& operator=(const EmbreeScene&) = delete;

  /// True when a caster lies on the segment origin + t·direction, t in [tNear, tFar], other
  /// than the triangle `skip` (none when skip.object = TriangleId::kNoObject).
  bool occluded(const glm::vec3& origin, const glm::vec3& direction, float tNear, float tFar,
                TriangleId skip = {}) const;

  /// A bundle of rays from one origin (one pixel's light samples): directions and segments in,
  /// one flag per ray out. Reused from pixel to pixel, so tracing allocates nothing per ray.
  struct Bundle {
    std::vector<RTCRay> rays;  // Embree's layout: origin, tnear, direction, time, tfar, mask, id, flags
    // Inline: add() and blocked() run once per ray, in the tracer's and the benchmark's loops.
    void clear() { rays.clear(); }
    void add(const glm::vec3& origin, const glm::vec3& direction, float tNear, float tFar) {
      RTCRay& ray = rays.emplace_back();
      ray.org_x = origin.x; ray.org_y = origin.y; ray.org_z = origin.z;
      ray.dir_x = direction.x; ray.dir_y = direction.y; ray.dir_z = direction.z;
      ray.tnear = tNear;
      ray.tfar = tFar;
      ray.time = 0.0f;
      ray.mask = std::numeric_limits<unsigned int>::max();
      ray.id = 0;
      ray.flags = 0;
    }
    size_t size() const { return rays.size(); }
    /// After occluded(bundle): whether ray i was blocked (Embree sets a blocked ray's tfar to −inf).
    bool blocked(size_t i) const { return rays[i].tfar == -std::numeric_limits<float>::infinity(); }
  };
  /// occluded() for every ray of `bundle` at once, as one coherent stream (Embree groups the rays
  /// into packets of its SIMD width): the same answer as one occluded() call per ray, faster when
  /// the rays leave one point toward one light.
  void occluded(Bundle& bundle, TriangleId skip = {}) const;

  /// Whether any caster is translucent (Material::translucent): only then do the reference's
  /// rays carry colour.
  bool hasTranslucentCasters() const { return mTranslucent; }
  /// occluded(bundle) that also multiplies each ray's light by the transmittance of every
  /// translucent caster it crosses (in any order: a product), an opaque hit stopping it.
  /// transmittance[i] is ray i's product, 0 where it is blocked; a ray that crosses no
  /// translucent caster gets exactly (1, 1, 1).
  void transmittance(Bundle& bundle, std::vector<glm::vec3>& transmittance, TriangleId skip = {}) const;
  /// The same for one segment.
  glm::vec3 transmittance(const glm::vec3& origin, const glm::vec3& direction, float tNear, float tFar,
                          TriangleId skip = {}) const;

  /// Hash of the world-space caster triangles and alpha masks (part of the cache key).
  uint64_t geometryHash() const { return mGeometryHash; }
  size_t casterTriangles() const { return mCasterTriangles; }
  struct Memory {
    uint64_t bytes = 0, peakBytes = 0;
  };
  /// Embree's own allocations once built (BVH, and the triangles it copied), and their peak
  /// during the build.
  Memory memory() const { return mMemoryAfterBuild; }
  double buildSeconds() const { return mBuildSeconds; }

private:
  EmbreeErrorLog mErrors;  // declared first: the device's callbacks write here and below until it is gone
  EmbreeMemory mMemory;
  struct ReleaseDevice { void operator()(RTCDevice device) const; };
  struct ReleaseScene { void operator()(RTCScene scene) const; };
  std::unique_ptr<RTCDeviceTy, ReleaseDevice> mDevice;
  std::unique_ptr<RTCSceneTy, ReleaseScene> mScene;  // after mDevice: released first
  std::vector<Image> mImages;  // copies: the filter reads them after the Scene is gone
  std::vector<std::unique_ptr<FilteredGeometry>> mFiltered;  // stable addresses for Embree
  bool mTranslucent = false;
  uint64_t mGeometryHash = 0;
  size_t mCasterTriangles = 0;
  Memory mMemoryAfterBuild;
  double mBuildSeconds = 0.0;
};

}  // namespace penumbra::reference
