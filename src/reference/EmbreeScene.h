#pragma once
// Embree 3 BVH of a Scene's shadow casters in world space: the same triangles, with the same
// transforms, that the renderer rasterises. Answers occlusion queries only.
#include <penumbra/Scene.h>

#include <glm/glm.hpp>

#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

typedef struct RTCDeviceTy* RTCDevice;
typedef struct RTCSceneTy* RTCScene;

namespace penumbra::reference {

/// What the alpha-test occlusion filter of one geometry needs: uvs by triangle and the texture.
struct AlphaMaskGeometry {
  std::vector<glm::vec2> uvs;      ///< three per triangle, in triangle order
  const Image* image = nullptr;    ///< RGBA8, row 0 = top; owned by EmbreeScene
  float alphaCutoff = 0.5f;
};

/// The last error Embree reported through its callback.
struct EmbreeErrorLog {
  std::mutex mutex;
  std::string last;
};

class EmbreeScene {
public:
  /// Throws penumbra::Error if Embree fails (the message is Embree's).
  explicit EmbreeScene(const Scene& scene);
  EmbreeScene(const EmbreeScene&) = delete;
  EmbreeScene& operator=(const EmbreeScene&) = delete;

  /// True when a caster lies on the segment origin + t·direction, t in [0, tFar].
  bool occluded(const glm::vec3& origin, const glm::vec3& direction, float tFar) const;

  /// Hash of the world-space caster triangles and alpha masks (part of the cache key).
  uint64_t geometryHash() const { return mGeometryHash; }
  /// Size of the scene (m), from the world bounds of every object: the largest of its bounding
  /// radius and its largest absolute coordinate (float spacing grows with |coordinates|).
  float sceneScaleM() const { return mSceneScaleM; }
  size_t casterTriangles() const { return mCasterTriangles; }

private:
  EmbreeErrorLog mErrors;  // declared first: the device's callback writes here until it is gone
  struct ReleaseDevice { void operator()(RTCDevice device) const; };
  struct ReleaseScene { void operator()(RTCScene scene) const; };
  std::unique_ptr<RTCDeviceTy, ReleaseDevice> mDevice;
  std::unique_ptr<RTCSceneTy, ReleaseScene> mScene;  // after mDevice: released first
  std::vector<Image> mImages;  // copies: the filter reads them after the Scene is gone
  std::vector<std::unique_ptr<AlphaMaskGeometry>> mAlphaMasks;  // stable addresses for Embree
  uint64_t mGeometryHash = 0;
  float mSceneScaleM = 1.0f;
  size_t mCasterTriangles = 0;
};

}  // namespace penumbra::reference
