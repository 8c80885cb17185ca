#pragma once
// The ground truth: visibility and shading ray traced on the CPU with Embree, pixel-aligned with
// the renderer's G-buffer. Every technique is measured against this (docs/reference.md).
//
// For each G-buffer pixel that faces the light, shadow rays start at the pixel's position (not
// lifted off it: they skip the receiver's own triangle and ignore hits within its float error of
// its plane) and go toward the light: one ray for a light of size 0, N stratified samples,
// uniform in solid angle, over the cone the light subtends for a spherical spot light or the
// sun's disk. Results are deterministic (per-pixel seeds) and cached on disk.
#include <penumbra/Image.h>
#include <penumbra/Scene.h>

#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <vector>

namespace penumbra {

/// Version of the reference's maths; part of every cache key. Bump it whenever a change to the
/// code changes the numbers it produces, so that stale cache files are never read.
inline constexpr uint32_t kReferenceCodeVersion = 5;

/// How far a G-buffer position may lie off its triangle's plane, in float32 spacings of the
/// largest magnitude it was computed from (its coordinates, its triangle's world vertices and the
/// transform's terms): the rasteriser's rounding. Shadow rays ignore hits lower than this above
/// the receiver's plane, t < tolerance / (N·ω), and skip the receiver's own triangle; the rays
/// start on the surface, so no shadow cast from higher up moves. GL test
/// ReferenceScale.GBufferPositionsLieWithinTheToleranceOfTheirTriangle measures the rasteriser.
inline constexpr float kPositionToleranceUlps = 16.0f;

struct ReferenceOptions {
  /// Light samples per pixel for a light of size > 0, in [1, kMaxReferenceSamples]; default 256.
  /// Laid out as a jittered nx × ny grid with nx·ny = samples (nx = the largest divisor ≤ √N,
  /// so squares and powers of two stratify well). Lights of size 0 always use one ray.
  int samples = 256;
  uint32_t seed = 0;           ///< the same seed gives bit-identical results
  bool progress = true;        ///< progress bar on stderr; drawn only when stderr is a terminal
  bool useCache = true;        ///< read and write the on-disk cache
  /// Cap of the cache folder in bytes, kept after this result is stored by evicting the least
  /// recently used entries (penumbra/Files.h); unset = defaultCacheMaxBytes()
  /// ($PENUMBRA_CACHE_MAX_MB, else kDefaultCacheMaxMiB).
  std::optional<std::uintmax_t> cacheMaxBytes;
  /// Where cache files go; empty = defaultCacheDir() (penumbra/Files.h).
  std::filesystem::path cacheDir;
};

inline constexpr int kMaxReferenceSamples = 1 << 16;

/// Per-pixel arrays are width × height, row 0 = bottom (the G-buffer's GL order).
struct ReferenceResult {
  int width = 0, height = 0;
  int samplesPerPixel = 0;  ///< 1 for a light of size 0, else ReferenceOptions::samples

  /// 1 where the pixel is covered, faces the light (geometric N·L > 0 toward the light's centre)
  /// and, for a spot light, lies inside its cone. Metrics are taken over these pixels only.
  std::vector<uint8_t> litMask;
  /// V_ref in [0, 1]: the fraction of the light's solid angle (above the surface's horizon)
  /// that is unoccluded. Outside litMask: 1 for background; on geometry 0 where no part of the
  /// light is above the horizon, else the fraction of that part (see horizonPixels).
  std::vector<float> visibility;
  /// Cosine-weighted visibility ∫cos·V dω / ∫cos dω = shadingExact / unshadowed shading. Its
  /// difference to `visibility` is the split approximation's error in units of V.
  std::vector<float> visibilityCosWeighted;
  /// Outgoing radiance (linear RGB) of a Lambertian surface with the G-buffer albedo:
  /// ∫ L_e · (albedo/π) · cos · V dω over the light (exact) …
  std::vector<glm::vec3> shadingExact;
  /// … and the split approximation every shadow map makes: V_ref · ∫ L_e · (albedo/π) · cos dω.
  /// Both use the same light samples, so their difference is the split alone, not noise.
  std::vector<glm::vec3> shadingSplit;
  /// shadingSplit − shadingExact: > 0 where the split model is too bright.
  std::vector<glm::vec3> approximationError;
  /// Where the scene has translucent casters (Material::translucent), V_ref per colour: the mean
  /// over the light's samples of each ray's RGB light, the product of the transmittances of the
  /// translucent casters it crosses (0 where an opaque one stops it), and its cos-weighted twin.
  /// `visibility` and `visibilityCosWeighted` are then their channels' mean. Empty in a scene
  /// without translucent casters, whose V_ref is one channel.
  std::vector<glm::vec3> visibilityRgb, visibilityCosWeightedRgb;

  /// Pixels outside litMask that the light lights all the same: a soft light whose centre is
  /// below their horizon with part of it above (a box top beside a lamp lower than it, the dark
  /// side of a ball under a large lamp). Their V_ref, cos-weighted V_ref and shading are traced
  /// over that part like any pixel's; the metrics leave them out, since a shadow map's lit pass
  /// takes N·L at the light's centre and gives them no light whatever its V.
  size_t horizonPixels = 0;

  double seconds = 0.0;       ///< wall-clock seconds of this call (a cache hit: the load time)
  double traceSeconds = 0.0;  ///< wall-clock seconds of the trace that produced the data
  bool fromCache = false;
  uint64_t cacheKey = 0;       ///< the key it is cached under; 0 where no cache was used (useCache off, no folder)
  /// Why the result was traced but not kept in the cache folder (it cannot be created or written:
  /// read-only, full, a file in its place), naming the folder or file and the reason; empty when
  /// it was kept or not meant to be. The result itself is whole either way.
  std::string cacheWarning;
};

/// How the reference holds the casters' triangles.
enum class MeshStorage {
  Copied,    ///< copies of the meshes' arrays: the scene may change or go away once the tracer is built
  /// The scene's own index arrays (and the positions of meshes placed at the identity) read in
  /// place, no copy: for scenes of millions of triangles. The scene must outlive the tracer, unchanged.
  Borrowed,
};

/// An Embree BVH of the scene's shadow casters (objects with castsShadow), in world space, and
/// the tracer that computes reference results from G-buffers. Thread-safe for concurrent trace()
/// calls. Materials with alphaMask cut holes: an occlusion filter reads their texture's alpha.
class ReferenceTracer {
public:
  /// Builds the BVH. Throws penumbra::Error if Embree cannot be initialised or the scene is invalid.
  explicit ReferenceTracer(const Scene& scene, MeshStorage storage = MeshStorage::Copied);
  ~ReferenceTracer();
  ReferenceTracer(const ReferenceTracer&) = delete;
  ReferenceTracer& operator=(const ReferenceTracer&) = delete;

  /// Traces every covered pixel of `gbuffer` (position, geoNormal, albedo and, when present,
  /// triangle are read) toward `light`. Throws penumbra::Error on inconsistent inputs (a covered
  /// pixel's triangle id that the scene does not have among them), bad options, or an unusable
  /// cache dir.
  ReferenceResult trace(const GBufferData& gbuffer, const Light& light,
                        const ReferenceOptions& options = {}) const;

  /// The key under which trace() caches its result: a hash of the casters' world-space
  /// triangles (and alpha masks), the light, the G-buffer contents, what each pixel's rays skip,
  /// samples, seed and kReferenceCodeVersion.
  uint64_t cacheKey(const GBufferData& gbuffer, const Light& light,
                    const ReferenceOptions& options) const;

  /// Bytes Embree holds for the BVH (with its copies of triangles, if any) after the build, and
  /// the most it held while building; the build's wall-clock seconds.
  uint64_t bvhBytes() const;
  uint64_t bvhPeakBytes() const;
  double bvhBuildSeconds() const;

private:
  struct Impl;
  std::unique_ptr<Impl> mImpl;
};

}  // namespace penumbra
