// Reference visibility and shading per G-buffer pixel (docs/reference.md).
//
// Estimator: the light is the cone of directions it subtends (a sphere's cap for a spot light,
// the sun's disk), sampled uniformly in solid angle on a jittered nx × ny grid mapped through
// the concentric disk. Samples below the surface's horizon are dropped from every sum: the
// receiver's own surface is not a shadow caster, and their cosine weight is zero anyway. A pixel
// whose horizon cuts the light is traced over the part above it, its centre above the horizon or
// not (only the former are in litMask). From
// the same samples: V = mean visibility, ∫cos·V and ∫cos, so exact and split shading differ by
// the split alone (their difference is −Ω·L·Cov(cos, V) over the light).
#include <penumbra/Error.h>
#include <penumbra/Files.h>
#include <penumbra/Reference.h>

#include "reference/PixelTracer.h"
#include "base/Hash.h"
#include "reference/LightSampling.h"
#include "base/ProgressBar.h"
#include "reference/ReferenceCache.h"

#include <fmt/format.h>
#include <glm/gtc/constants.hpp>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <span>

namespace penumbra {
namespace {

using namespace reference;

void checkGBuffer(const GBufferData& g) {
  PN_CHECK(g.width > 0 && g.height > 0, fmt::format("reference: G-buffer size {}x{} is empty", g.width, g.height));
  const size_t pixels = static_cast<size_t>(g.width) * static_cast<size_t>(g.height);
  PN_CHECK(g.position.size() == pixels && g.geoNormal.size() == pixels && g.albedo.size() == pixels,
           fmt::format("reference: G-buffer {}x{} needs {} positions, geometric normals and albedos; has {}, {}, {}",
                       g.width, g.height, pixels, g.position.size(), g.geoNormal.size(), g.albedo.size()));
  PN_CHECK(g.triangle.empty() || g.triangle.size() == pixels,
           fmt::format("reference: G-buffer {}x{} has {} triangle ids (none, or one per pixel)", g.width, g.height,
                       g.triangle.size()));
}

int samplesFor(const Light& light, const ReferenceOptions& options) {
  return light.size > 0.0f ? options.samples : 1;
}

}  // namespace

struct ReferenceTracer::Impl {
  Impl(const Scene& scene, MeshStorage storage) : embree(scene, storage), triangles(receiverTriangles(scene)) {}

  std::vector<Receiver> receivers(const GBufferData& g) const { return receiversOf(g, triangles); }

  uint64_t key(const GBufferData& g, std::span<const Receiver> receivers, const Light& light,
               const ReferenceOptions& options) const;

  EmbreeScene embree;
  std::vector<std::vector<ReceiverTriangle>> triangles;  // receiverTriangles(scene)
};

ReferenceTracer::ReferenceTracer(const Scene& scene, MeshStorage storage) : mImpl(std::make_unique<Impl>(scene, storage)) {}
ReferenceTracer::~ReferenceTracer() = default;
uint64_t ReferenceTracer::bvhBytes() const { return mImpl->embree.memory().bytes; }
uint64_t ReferenceTracer::bvhPeakBytes() const { return mImpl->embree.memory().peakBytes; }
double ReferenceTracer::bvhBuildSeconds() const { return mImpl->embree.buildSeconds(); }

uint64_t ReferenceTracer::cacheKey(const GBufferData& g, const Light& light, const ReferenceOptions& options) const {
  checkGBuffer(g);
  return mImpl->key(g, mImpl->receivers(g), light, options);
}

uint64_t ReferenceTracer::Impl::key(const GBufferData& g, std::span<const Receiver> receivers, const Light& light,
                                    const ReferenceOptions& options) const {
  Hasher hash;
  hash.text("penumbra.reference");
  hash.value(kReferenceCodeVersion);
  hash.value(embree.geometryHash());
  // What each pixel skips and ignores (the G-buffer's triangle ids, the receivers' planes and
  // magnitudes: non-casters are not in the geometry hash).
  for (const Receiver& r : receivers) {
    hash.value(r.triangle.object);
    hash.value(r.triangle.triangle);
    hash.value(r.errorM);
    hash.value(r.planeNormal);
  }
  hash.value(static_cast<int>(light.type));
  hash.value(light.position);
  hash.value(light.direction);
  hash.value(light.color);
  hash.value(light.intensity);
  hash.value(light.coneAngleRad);
  hash.value(light.innerConeAngleRad);
  hash.value(light.rangeM);
  hash.value(light.size);
  const bool soft = light.size > 0.0f;  // a hard light's result depends on neither
  hash.value(samplesFor(light, options));
  hash.value(soft ? options.seed : 0u);
  hash.value(g.width);
  hash.value(g.height);
  hash.array(std::span<const glm::vec4>(g.position));
  hash.array(std::span<const glm::vec4>(g.geoNormal));
  hash.array(std::span<const glm::vec4>(g.albedo));
  return hash.digest();
}

ReferenceResult ReferenceTracer::trace(const GBufferData& g, const Light& light, const ReferenceOptions& options) const {
  const auto start = std::chrono::steady_clock::now();
  const auto secondsSince = [](std::chrono::steady_clock::time_point t) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
  };
  checkGBuffer(g);
  PN_CHECK(options.samples >= 1 && options.samples <= kMaxReferenceSamples,
           fmt::format("reference: samples {} out of range [1, {}]", options.samples, kMaxReferenceSamples));
  const LightSetup setup = setupLight(light);

  // The key hashes the whole G-buffer on one core (a tenth of a 640x360 trace at 64 samples on
  // two): made only where a cache will read or keep the result.
  uint64_t key = 0;
  std::filesystem::path cacheDir;
  std::uintmax_t cacheMaxBytes = 0;
  if (options.useCache) {
    // No directory can be formed only without HOME; the result is the same, just not kept.
    cacheDir = options.cacheDir.empty() ? defaultCacheDir() : options.cacheDir;
    if (!cacheDir.empty()) {
      key = mImpl->key(g, mImpl->receivers(g), light, options);
      if (auto cached = reference::loadCachedResult(cacheDir, key);
          cached && cached->width == g.width && cached->height == g.height) {
        cached->seconds = secondsSince(start);
        return std::move(*cached);
      }
      cacheMaxBytes = options.cacheMaxBytes.value_or(defaultCacheMaxBytes());  // a bad variable stops us now
    }
  }
  // A folder that cannot hold the result costs the cache, not the result (ReferenceResult::cacheWarning).
  std::string cacheWarning;
  if (!cacheDir.empty()) {
    try {
      reference::prepareCacheDir(cacheDir);
    } catch (const Error& e) {
      cacheWarning = e.what();
      cacheDir.clear();
    }
  }

  ReferenceResult r;
  r.width = g.width;
  r.height = g.height;
  r.samplesPerPixel = samplesFor(light, options);
  r.cacheKey = key;
  // Sized here and written once per pixel in the loop, background included: the loop finds each
  // pixel's receiver too, so nothing but the results is kept per pixel.
  const size_t pixels = static_cast<size_t>(g.width) * static_cast<size_t>(g.height);
  r.litMask.resize(pixels);
  r.visibility.resize(pixels);
  r.visibilityCosWeighted.resize(pixels);
  r.shadingExact.resize(pixels);
  r.shadingSplit.resize(pixels);
  r.approximationError.resize(pixels);
  const bool colour = mImpl->embree.hasTranslucentCasters();
  if (colour) {
    r.visibilityRgb.resize(pixels);
    r.visibilityCosWeightedRgb.resize(pixels);
  }

  const PixelTracer tracer(mImpl->embree, setup, r.samplesPerPixel, options.seed);
  PixelOut background;  // nothing to shadow: V = 1
  background.visibility = background.visibilityCos = 1.0f;
  background.visibilityRgb = background.visibilityCosRgb = glm::vec3(1.0f);
  ProgressBar progress(fmt::format("reference {}x{} @ {} spp", g.width, g.height, r.samplesPerPixel),
                                  pixels, options.progress);
  // Rows, one task each: enough tasks to balance shadowed and empty rows across cores.
  tbb::parallel_for(tbb::blocked_range<int>(0, g.height), [&](const tbb::blocked_range<int>& rows) {
    for (int y = rows.begin(); y != rows.end(); ++y) {
      for (int x = 0; x < g.width; ++x) {
        const size_t i = static_cast<size_t>(y) * static_cast<size_t>(g.width) + static_cast<size_t>(x);
        const PixelOut p = g.covered(i) ? tracer.trace(i, glm::vec3(g.position[i]), glm::vec3(g.geoNormal[i]),
                                                       glm::vec3(g.albedo[i]), receiverOf(g, i, mImpl->triangles))
                                        : background;
        r.litMask[i] = p.lit ? 1 : 0;
        r.visibility[i] = p.visibility;
        r.visibilityCosWeighted[i] = p.visibilityCos;
        r.shadingExact[i] = p.exact;
        r.shadingSplit[i] = p.split;
        r.approximationError[i] = p.split - p.exact;
        if (colour) {
          r.visibilityRgb[i] = p.visibilityRgb;
          r.visibilityCosWeightedRgb[i] = p.visibilityCosRgb;
        }
      }
      progress.advance(static_cast<size_t>(g.width));
    }
  });
  r.horizonPixels = countHorizonPixels(r);
  r.traceSeconds = secondsSince(start);
  r.seconds = r.traceSeconds;
  if (!cacheDir.empty()) {
    try {
      reference::storeCachedResult(cacheDir, r);
    } catch (const Error& e) {
      cacheWarning = fmt::format("reference cache: {}", e.what());
    }
    trimCache(cacheDir, cacheMaxBytes);
  }
  r.cacheWarning = std::move(cacheWarning);
  return r;
}

}  // namespace penumbra
