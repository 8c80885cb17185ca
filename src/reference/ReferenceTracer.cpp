// Reference visibility and shading per G-buffer pixel (docs/reference.md).
//
// Estimator: the light is the cone of directions it subtends (a sphere's cap for a spot light,
// the sun's disk), sampled uniformly in solid angle on a jittered nx × ny grid mapped through
// the concentric disk. Samples below the surface's horizon are dropped from every sum: the
// receiver's own surface is not a shadow caster, and their cosine weight is zero anyway. From
// the same samples: V = mean visibility, ∫cos·V and ∫cos, so exact and split shading differ by
// the split alone (their difference is −Ω·L·Cov(cos, V) over the light).
#include <penumbra/Error.h>
#include <penumbra/Files.h>
#include <penumbra/Reference.h>

#include "reference/EmbreeScene.h"
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

using reference::EmbreeScene;

// Self-intersection without moving a shadow (docs/reference.md, "Rays"). A shadow ray starts
// exactly at the G-buffer position p, which the rasteriser interpolated in float32 and so lies a
// few float spacings off the true surface. Two rules keep the ray from hitting that surface:
//  1. the receiver's own triangle (GBufferData::triangle) is skipped: a flat triangle cannot
//     shadow its own points toward directions above its plane, so every hit on it is rounding;
//  2. hits lower than δ above the receiver's plane are ignored: t_near = δ / (N·ω) along the ray,
//     δ = kPositionToleranceUlps float spacings of the largest magnitude p was computed from (its
//     own coordinates, and its triangle's world vertices with the transform's terms). Such a hit
//     is within p's own error of the surface: a neighbouring triangle near a shared edge, or the
//     receiver itself where its triangle is not known.
// Neither moves a shadow edge cast by anything that rises more than δ above the receiver (1 mm
// 1 km from the origin, 2 µm within 1 m of it), where an origin lifted by ε along N moved every
// edge by ε / tan(elevation) (the old ε = 1e-4 × scene size moved a 2 km scene's by 0.14 m).
// A G-buffer normal shorter than this is not a normal (an unwritten pixel): the pixel is unlit.
constexpr float kMinNormalLength = 1e-6f;

/// What every pixel shares for one light.
struct LightSetup {
  bool directional = true;
  bool soft = false;
  glm::vec3 centre{0.0f};             // spot: sphere centre (m)
  glm::vec3 toLight{0.0f, 1.0f, 0.0f};  // sun: unit direction toward the sun
  glm::vec3 spotAxis{0.0f, -1.0f, 0.0f};
  float cosCone = 0.0f;               // spot: cos of the cone's half angle
  float radiusM = 0.0f;               // spot: sphere radius
  float sunCapHeight = 0.0f;          // sun: 1 − cos(angular radius)
  glm::vec3 power{1.0f};              // colour × intensity: E at normal incidence (sun) or I (spot)
  glm::vec3 radiance{0.0f};           // soft lights: uniform emitted radiance L_e
};

LightSetup setupLight(const Light& light) {
  PN_CHECK(light.size >= 0.0f && std::isfinite(light.size),
           fmt::format("reference: light size {} must be finite and >= 0", light.size));
  PN_CHECK(glm::length(light.direction) > 0.0f, "reference: the light has a zero direction");
  LightSetup s;
  s.power = light.color * light.intensity;
  s.soft = light.size > 0.0f;
  if (light.type == LightType::Directional) {
    PN_CHECK(light.size < glm::half_pi<float>(),
             fmt::format("reference: sun angular radius {} rad must be below pi/2", light.size));
    s.toLight = -glm::normalize(light.direction);
    s.sunCapHeight = reference::oneMinusCos(light.size);
    // E at normal incidence = ∫_cone L_e cos dω = L_e · π sin²α.
    const float sinAlpha = std::sin(light.size);
    if (s.soft) s.radiance = s.power / (glm::pi<float>() * sinAlpha * sinAlpha);
  } else {
    PN_CHECK(light.coneAngleRad > 0.0f && light.coneAngleRad < glm::pi<float>(),
             fmt::format("reference: spot cone half angle {} rad must be in (0, pi)", light.coneAngleRad));
    s.directional = false;
    s.centre = light.position;
    s.spotAxis = glm::normalize(light.direction);
    s.cosCone = std::cos(light.coneAngleRad);
    s.radiusM = light.size;
    // A uniform sphere of radiance L_e has intensity L_e · πR² in every direction.
    if (s.soft) s.radiance = s.power / (glm::pi<float>() * light.size * light.size);
  }
  return s;
}

/// Spacing of float32 values at magnitude x ≥ 0.
float floatSpacing(float x) { return std::nextafter(x, std::numeric_limits<float>::infinity()) - x; }

/// One triangle as a receiver: the plane its points lie on, and the largest magnitude among the
/// float terms that make its world-space vertices, |M|·(|v|, 1): the GPU's transform and
/// interpolation round at that magnitude, even where the result is small.
struct ReceiverTriangle {
  glm::vec3 normal{0.0f};  // unit; zero for a degenerate triangle
  float magnitude = 0.0f;
};

/// Per object of the scene (casters or not: every object receives), per triangle of its mesh.
std::vector<std::vector<ReceiverTriangle>> receiverTriangles(const Scene& scene) {
  std::vector<std::vector<ReceiverTriangle>> out(scene.objects.size());
  for (size_t o = 0; o < scene.objects.size(); ++o) {
    const Object& object = scene.objects[o];
    const Mesh& mesh = scene.meshes[object.mesh];
    glm::mat4 absolute;
    for (int c = 0; c < 4; ++c) absolute[c] = glm::abs(object.worldFromObject[c]);
    std::vector<glm::vec3> world(mesh.vertices.size());
    std::vector<float> magnitude(mesh.vertices.size());
    for (size_t i = 0; i < mesh.vertices.size(); ++i) {
      world[i] = glm::vec3(object.worldFromObject * glm::vec4(mesh.vertices[i].position, 1.0f));
      const glm::vec4 terms = absolute * glm::vec4(glm::abs(mesh.vertices[i].position), 1.0f);
      magnitude[i] = std::max({terms.x, terms.y, terms.z});
    }
    out[o].resize(mesh.triangleCount());
    for (size_t t = 0; t < out[o].size(); ++t) {
      const uint32_t a = mesh.indices[3 * t], b = mesh.indices[3 * t + 1], c = mesh.indices[3 * t + 2];
      const glm::vec3 cross = glm::cross(world[b] - world[a], world[c] - world[a]);
      const float length = glm::length(cross);
      out[o][t].normal = length > 0.0f ? cross / length : glm::vec3(0.0f);
      out[o][t].magnitude = std::max({magnitude[a], magnitude[b], magnitude[c]});
    }
  }
  return out;
}

/// What the tracer knows of one receiving pixel beyond its position and normal.
struct Receiver {
  reference::TriangleId triangle;  // skipped by its rays; TriangleId::kNoObject = unknown
  float errorM = 0.0f;             // δ: hits lower than this above its plane are its own
  // Its triangle's plane, turned to the G-buffer normal's side; zero = unknown (then the G-buffer
  // normal stands in, which the rasteriser derived from rounded positions and stored in 16 bits).
  glm::vec3 planeNormal{0.0f};
};

struct PixelOut {
  bool lit = false;
  float visibility = 0.0f, visibilityCos = 0.0f;
  glm::vec3 exact{0.0f}, split{0.0f};
};

class PixelTracer {
public:
  PixelTracer(const EmbreeScene& scene, const LightSetup& light, int samples, uint32_t seed)
      : mScene(scene), mLight(light), mSamples(samples),
        mColumns(reference::strataColumns(samples)), mRows(samples / mColumns), mSeed(seed) {}

  PixelOut trace(size_t pixel, const glm::vec3& origin, const glm::vec3& normalIn, const glm::vec3& albedo,
                 const Receiver& receiver) const {
    PixelOut out;
    const float normalLength = glm::length(normalIn);
    if (!(normalLength > kMinNormalLength)) return out;
    const glm::vec3 n = normalIn / normalLength;

    glm::vec3 axis = mLight.toLight;
    float distanceM = std::numeric_limits<float>::infinity();
    if (!mLight.directional) {
      const glm::vec3 toCentre = mLight.centre - origin;
      distanceM = glm::length(toCentre);
      if (!(distanceM > 0.0f)) return out;
      axis = toCentre / distanceM;
      if (glm::dot(-axis, mLight.spotAxis) < mLight.cosCone) return out;  // outside the spot cone
    }
    if (glm::dot(n, axis) <= 0.0f) return out;  // faces away from the light's centre
    out.lit = true;
    const glm::vec3 brdf = albedo * glm::one_over_pi<float>();

    if (!mLight.soft || distanceM <= mLight.radiusM) return traceHard(out, origin, n, brdf, receiver);

    const float capHeight = mLight.directional ? mLight.sunCapHeight
                                               : reference::sphereOneMinusCos(mLight.radiusM, distanceM);
    const reference::Frame frame = reference::frameAround(axis);
    reference::Pcg32 rng(Hasher::finalise(pixel ^ (static_cast<uint64_t>(mSeed) << 32)), pixel);
    int above = 0;
    float sumV = 0.0f, sumCos = 0.0f, sumCosV = 0.0f;
    for (int row = 0; row < mRows; ++row) {
      for (int column = 0; column < mColumns; ++column) {
        const glm::vec2 u{(static_cast<float>(column) + rng.uniform()) / static_cast<float>(mColumns),
                          (static_cast<float>(row) + rng.uniform()) / static_cast<float>(mRows)};
        const glm::vec3 dir = frame.toWorld(reference::coneDirection(reference::concentricDisk(u), capHeight));
        const float cosTheta = glm::dot(n, dir);
        if (cosTheta <= 0.0f) continue;
        ++above;
        const float v = occluded(origin, dir, cosTheta, rayLength(origin, dir), receiver) ? 0.0f : 1.0f;
        sumV += v;
        sumCos += cosTheta;
        sumCosV += cosTheta * v;
      }
    }
    out.visibility = above > 0 ? sumV / static_cast<float>(above) : 0.0f;
    out.visibilityCos = sumCos > 0.0f ? sumCosV / sumCos : out.visibility;
    // Uniform over the cone: ∫ f dω ≈ (Ω / N) Σ f, with Ω = 2π(1 − cos α).
    const float weight = glm::two_pi<float>() * capHeight / static_cast<float>(mSamples);
    out.exact = brdf * mLight.radiance * (weight * sumCosV);
    out.split = brdf * mLight.radiance * (weight * sumCos * out.visibility);
    return out;
  }

private:
  PixelOut traceHard(PixelOut out, const glm::vec3& origin, const glm::vec3& n, const glm::vec3& brdf,
                     const Receiver& receiver) const {
    glm::vec3 dir = mLight.toLight;
    float length = std::numeric_limits<float>::infinity();
    glm::vec3 irradiance = mLight.power;
    if (!mLight.directional) {
      const glm::vec3 toCentre = mLight.centre - origin;
      length = glm::length(toCentre);
      dir = toCentre / length;
      // A point inside a spherical light is lit by all of it; the point-light law at r = R
      // keeps the value finite (such pixels are not a case the shadow maps can be judged on).
      const float r = std::max(length, mLight.radiusM);
      irradiance = mLight.power / (r * r);
      if (mLight.soft) length = 0.0f;
    }
    const float cosTheta = std::max(0.0f, glm::dot(n, dir));
    const float v = length > 0.0f && occluded(origin, dir, cosTheta, length, receiver) ? 0.0f : 1.0f;
    out.visibility = out.visibilityCos = v;
    out.exact = out.split = brdf * irradiance * (cosTheta * v);
    return out;
  }

  /// Whether a caster blocks the ray from the receiver along dir (cosTheta = N·dir > 0) before
  /// tFar, other than the receiver's own triangle and anything within its error of its plane.
  bool occluded(const glm::vec3& origin, const glm::vec3& dir, float cosTheta, float tFar,
                const Receiver& receiver) const {
    // The ray's height above the receiver's plane is t·cos; a ray that never rises above δ (its
    // true cos ≤ 0, beside a G-buffer normal a hair off) gets tNear = inf: nothing it meets is
    // distinguishable from the receiver's surface.
    const bool knowsPlane = receiver.planeNormal != glm::vec3(0.0f);
    const float cosPlane = knowsPlane ? glm::dot(receiver.planeNormal, dir) : cosTheta;
    const float tNear = cosPlane > 0.0f ? receiver.errorM / cosPlane : std::numeric_limits<float>::infinity();
    return tNear < tFar && mScene.occluded(origin, dir, tNear, tFar, receiver.triangle);
  }

  /// Rays end where they enter the spherical light: casters behind it do not shadow.
  float rayLength(const glm::vec3& origin, const glm::vec3& dir) const {
    if (mLight.directional) return std::numeric_limits<float>::infinity();
    const glm::vec3 toCentre = mLight.centre - origin;
    const float along = glm::dot(toCentre, dir);
    const glm::vec3 perpendicular = toCentre - along * dir;  // stable where R ≪ distance
    const float halfChord2 = mLight.radiusM * mLight.radiusM - glm::dot(perpendicular, perpendicular);
    return along - std::sqrt(std::max(0.0f, halfChord2));
  }

  const EmbreeScene& mScene;
  const LightSetup& mLight;
  int mSamples, mColumns, mRows;
  uint32_t mSeed;
};

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
  explicit Impl(const Scene& scene) : embree(scene), triangles(receiverTriangles(scene)) {}

  /// Per pixel: the triangle to skip and δ (position tolerance, m). Throws when the G-buffer
  /// names a triangle the scene does not have (a G-buffer of another scene).
  std::vector<Receiver> receivers(const GBufferData& g) const {
    std::vector<Receiver> out(g.position.size());
    for (size_t i = 0; i < out.size(); ++i) {
      const glm::vec3 p = glm::abs(glm::vec3(g.position[i]));
      float magnitude = std::max({p.x, p.y, p.z});
      if (!g.triangle.empty() && g.triangle[i].x > 0) {
        const uint32_t object = g.triangle[i].x - 1, triangle = g.triangle[i].y;
        PN_CHECK(object < triangles.size() && triangle < triangles[object].size(),
                 fmt::format("reference: G-buffer pixel {} shows triangle {} of object {}, which the scene does not have",
                             i, triangle, object));
        const ReceiverTriangle& t = triangles[object][triangle];
        out[i].triangle = {object, triangle};
        out[i].planeNormal = glm::dot(t.normal, glm::vec3(g.geoNormal[i])) < 0.0f ? -t.normal : t.normal;
        magnitude = std::max(magnitude, t.magnitude);
      }
      out[i].errorM = kPositionToleranceUlps * floatSpacing(magnitude);
    }
    return out;
  }

  uint64_t key(const GBufferData& g, std::span<const Receiver> receivers, const Light& light,
               const ReferenceOptions& options) const;

  EmbreeScene embree;
  std::vector<std::vector<ReceiverTriangle>> triangles;  // receiverTriangles(scene)
};

ReferenceTracer::ReferenceTracer(const Scene& scene) : mImpl(std::make_unique<Impl>(scene)) {}
ReferenceTracer::~ReferenceTracer() = default;

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
  const std::vector<Receiver> receivers = mImpl->receivers(g);
  const uint64_t key = mImpl->key(g, receivers, light, options);

  std::filesystem::path cacheDir;
  std::uintmax_t cacheMaxBytes = 0;
  if (options.useCache) {
    // No directory can be formed only without HOME; the result is the same, just not kept.
    cacheDir = options.cacheDir.empty() ? defaultCacheDir() : options.cacheDir;
    if (!cacheDir.empty()) {
      if (auto cached = reference::loadCachedResult(cacheDir, key);
          cached && cached->width == g.width && cached->height == g.height) {
        cached->seconds = secondsSince(start);
        return std::move(*cached);
      }
      reference::prepareCacheDir(cacheDir);
      cacheMaxBytes = options.cacheMaxBytes.value_or(defaultCacheMaxBytes());  // a bad variable stops us now
    }
  }

  ReferenceResult r;
  r.width = g.width;
  r.height = g.height;
  r.samplesPerPixel = samplesFor(light, options);
  r.cacheKey = key;
  const size_t pixels = static_cast<size_t>(g.width) * static_cast<size_t>(g.height);
  r.litMask.assign(pixels, 0);
  r.visibility.assign(pixels, 1.0f);
  r.visibilityCosWeighted.assign(pixels, 1.0f);
  r.shadingExact.assign(pixels, glm::vec3(0.0f));
  r.shadingSplit.assign(pixels, glm::vec3(0.0f));

  const PixelTracer tracer(mImpl->embree, setup, r.samplesPerPixel, options.seed);
  ProgressBar progress(fmt::format("reference {}x{} @ {} spp", g.width, g.height, r.samplesPerPixel),
                                  pixels, options.progress);
  // Rows, one task each: enough tasks to balance shadowed and empty rows across cores.
  tbb::parallel_for(tbb::blocked_range<int>(0, g.height), [&](const tbb::blocked_range<int>& rows) {
    for (int y = rows.begin(); y != rows.end(); ++y) {
      for (int x = 0; x < g.width; ++x) {
        const size_t i = static_cast<size_t>(y) * static_cast<size_t>(g.width) + static_cast<size_t>(x);
        if (!g.covered(i)) continue;  // background: nothing to shadow, V = 1
        const PixelOut p =
            tracer.trace(i, glm::vec3(g.position[i]), glm::vec3(g.geoNormal[i]), glm::vec3(g.albedo[i]), receivers[i]);
        r.litMask[i] = p.lit ? 1 : 0;
        r.visibility[i] = p.visibility;
        r.visibilityCosWeighted[i] = p.visibilityCos;
        r.shadingExact[i] = p.exact;
        r.shadingSplit[i] = p.split;
      }
      progress.advance(static_cast<size_t>(g.width));
    }
  });
  r.approximationError.resize(pixels);
  for (size_t i = 0; i < pixels; ++i) r.approximationError[i] = r.shadingSplit[i] - r.shadingExact[i];
  r.traceSeconds = secondsSince(start);
  r.seconds = r.traceSeconds;
  if (!cacheDir.empty()) {
    reference::storeCachedResult(cacheDir, r);
    trimCache(cacheDir, cacheMaxBytes);
  }
  return r;
}

}  // namespace penumbra
