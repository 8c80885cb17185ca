#pragma once
// The reference's per-pixel machinery (ReferenceTracer.cpp, RayBenchmark.cpp): the light's shared
// values, what each receiving pixel skips and ignores, and the tracer of one pixel, which casts a
// soft light's samples as one coherent stream of rays (EmbreeScene::Bundle).
#include "base/Hash.h"
#include "reference/EmbreeScene.h"
#include "reference/LightSampling.h"

#include <penumbra/Reference.h>
#include <penumbra/Scene.h>

#include <glm/glm.hpp>
#include <glm/gtc/constants.hpp>

#include <cstdint>
#include <limits>
#include <vector>

namespace penumbra::reference {

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
  float cosCone = 0.0f;               // spot: cos of the cone's outer half angle (point: −2, no cone)
  float radiusM = 0.0f;               // spot, point: sphere radius
  float rangeM = 0.0f;                // spot, point: no light beyond it (0 = unlimited)
  Light light;                        // the light itself: its falloff scales the shading
  float sunCapHeight = 0.0f;          // sun: 1 − cos(angular radius)
  float sunSinRadius = 0.0f;          // sun: sin(angular radius): how far below the horizon its centre may sink
  glm::vec3 power{1.0f};              // colour × intensity: E at normal incidence (sun) or I (spot)
  glm::vec3 radiance{0.0f};           // soft lights: uniform emitted radiance L_e
};

/// The light's values every pixel shares. Throws penumbra::Error for a light the reference cannot
/// sample (a negative size, a zero direction, a sun wider than a hemisphere, a bad cone).
LightSetup setupLight(const Light& light);


/// One triangle as a receiver: the plane its points lie on, and the largest magnitude among the
/// float terms that make its world-space vertices, |M|·(|v|, 1): the GPU's transform and
/// interpolation round at that magnitude, even where the result is small.
struct ReceiverTriangle {
  glm::vec3 normal{0.0f};  // unit; zero for a degenerate triangle
  float magnitude = 0.0f;
};

/// Per object of the scene (casters or not: every object receives), per triangle of its mesh.
std::vector<std::vector<ReceiverTriangle>> receiverTriangles(const Scene& scene);

/// What the tracer knows of one receiving pixel beyond its position and normal.
struct Receiver {
  reference::TriangleId triangle;  // skipped by its rays; TriangleId::kNoObject = unknown
  float errorM = 0.0f;             // δ: hits lower than this above its plane are its own
  // Its triangle's plane, turned to the G-buffer normal's side; zero = unknown (then the G-buffer
  // normal stands in, which the rasteriser derived from rounded positions and stored in 16 bits).
  glm::vec3 planeNormal{0.0f};
  /// The plane its rays must rise above: its triangle's, else the pixel's unit normal n.
  glm::vec3 plane(const glm::vec3& n) const { return planeNormal != glm::vec3(0.0f) ? planeNormal : n; }
};

/// Pixel i of g as a receiver: the triangle its rays skip, its plane and δ (position tolerance, m),
/// from receiverTriangles(scene). Throws when the G-buffer names a triangle the scene does not have
/// there (a G-buffer of another scene).
Receiver receiverOf(const GBufferData& g, size_t i, const std::vector<std::vector<ReceiverTriangle>>& triangles);

/// receiverOf() for every pixel of g, over every core (the cache key hashes them all).
std::vector<Receiver> receiversOf(const GBufferData& g, const std::vector<std::vector<ReceiverTriangle>>& triangles);

/// How much of the light a receiving pixel can see above its horizon.
enum class Reach {
  None,     ///< none of it (no normal, outside the spot's cone or its range, the whole light below the horizon)
  Centre,   ///< the light's centre is above the horizon: the pixel is in litMask
  Horizon,  ///< a soft light's centre is below the horizon but part of the light is above it
};

struct PixelOut {
  bool lit = false;      // in litMask (Reach::Centre)
  bool horizon = false;  // Reach::Horizon: traced, outside litMask
  float visibility = 0.0f, visibilityCos = 0.0f;
  glm::vec3 exact{0.0f}, split{0.0f};
  glm::vec3 visibilityRgb{0.0f}, visibilityCosRgb{0.0f};  // only where the scene has translucent casters
};

/// The scalar V of a ray's RGB light (EmbreeScene::transmittance): the mean of its channels, so
/// that a ray that meets no translucent caster counts exactly 1 and a blocked one exactly 0, as
/// in an opaque scene.
inline float channelMean(const glm::vec3& t) { return (t.x + t.y + t.z) / 3.0f; }

/// A soft light's samples of one pixel that lie above its horizon, in sample order: N·ω, and the
/// index of the sample's ray in `bundle` (-1: the ray never rises above the receiver's float
/// error, so nothing it meets can shadow: not traced).
struct SoftSamples {
  std::vector<float> cosTheta;
  std::vector<int> ray;
  EmbreeScene::Bundle bundle;
  // softSamples' scratch, one entry per sample, a structure of arrays so that its passes run
  // several samples per instruction: the point (square → disk), the world direction, N·ω and the
  // ray's segment.
  std::vector<float> x, y, dirX, dirY, dirZ, cos, tNear, tFar;
};

/// softSamples' default per-sample hook: nothing.
struct IgnoreSample {
  void operator()(float /*cosTheta*/) const {}
};

class PixelTracer {
public:
  PixelTracer(const EmbreeScene& scene, const LightSetup& light, int samples, uint32_t seed)
      : mScene(scene), mLight(light), mSamples(samples),
        mColumns(reference::strataColumns(samples)), mRows(samples / mColumns), mSeed(seed) {}

  PixelOut trace(size_t pixel, const glm::vec3& origin, const glm::vec3& normalIn, const glm::vec3& albedo,
                 const Receiver& receiver) const {
    PixelOut out;
    glm::vec3 n;
    float distanceM = 0.0f;
    const Reach reach = reaches(origin, normalIn, n, distanceM);
    if (reach == Reach::None) return out;
    out.lit = reach == Reach::Centre;
    out.horizon = reach == Reach::Horizon;
    const glm::vec3 brdf = albedo * glm::one_over_pi<float>();

    if (!soft(distanceM)) return traceHard(out, origin, n, brdf, receiver);
    if (mScene.hasTranslucentCasters()) return traceSoftColour(out, pixel, origin, n, brdf, receiver, distanceM);

    // The pixel's rays, one coherent stream through Embree (the samples' order is kept: the sums
    // add in it, so the result does not depend on how Embree groups the rays). Σ cos is summed as
    // the samples are made, where its additions hide behind the generator's latency.
    thread_local SoftSamples samples;
    float sumCos = 0.0f;
    softSamples(pixel, origin, n, receiver, distanceM, samples, [&sumCos](float cosTheta) { sumCos += cosTheta; });
    mScene.occluded(samples.bundle, receiver.triangle);
    const size_t above = samples.cosTheta.size();
    size_t blocked = 0;
    for (size_t k = 0; k < samples.bundle.size(); ++k) blocked += samples.bundle.blocked(k) ? 1 : 0;
    // Σ V and Σ cos·V over the samples in order, V = 0 for a blocked ray and 1 otherwise: a count
    // (exact in float below 2²⁴ samples), and Σ cos of the unblocked samples, since adding
    // cos·0 = +0 leaves a sum unchanged. Unshadowed or wholly blocked pixels need no second pass.
    const auto sumV = static_cast<float>(above - blocked);
    float sumCosV = blocked == 0 ? sumCos : 0.0f;
    if (blocked > 0 && blocked < above)
      for (size_t k = 0; k < above; ++k) {
        const int ray = samples.ray[k];
        if (ray < 0 || !samples.bundle.blocked(static_cast<size_t>(ray))) sumCosV += samples.cosTheta[k];
      }
    const float capHeight = this->capHeight(distanceM);
    out.visibility = above > 0 ? sumV / static_cast<float>(above) : 0.0f;
    out.visibilityCos = sumCos > 0.0f ? sumCosV / sumCos : out.visibility;
    // Uniform over the cone: ∫ f dω ≈ (Ω / N) Σ f, with Ω = 2π(1 − cos α).
    const float weight = glm::two_pi<float>() * capHeight / static_cast<float>(mSamples);
    // The spot cone's and the range's falloff, taken at the receiver (constant over the light;
    // none for the sun).
    const float falloff = mLight.directional ? 1.0f : lightFalloff(mLight.light, origin);
    out.exact = brdf * mLight.radiance * (falloff * weight * sumCosV);
    out.split = brdf * mLight.radiance * (falloff * weight * sumCos * out.visibility);
    return out;
  }

  /// A pixel's unit normal, its distance to a spot light's centre (inf for the sun) and how much of
  /// the light it sees above its horizon. A soft light whose centre is below the horizon still
  /// lights the pixel where the light's cap of half angle α reaches above it (N·L > −sin α): a box
  /// top beside a lamp lower than it, the shadow side of a ball under a large lamp.
  Reach reaches(const glm::vec3& origin, const glm::vec3& normalIn, glm::vec3& n, float& distanceM) const {
    const float normalLength = glm::length(normalIn);
    if (!(normalLength > kMinNormalLength)) return Reach::None;
    n = normalIn / normalLength;
    glm::vec3 axis = mLight.toLight;
    distanceM = std::numeric_limits<float>::infinity();
    float sinRadius = mLight.sunSinRadius;
    if (!mLight.directional) {
      const glm::vec3 toCentre = mLight.centre - origin;
      distanceM = glm::length(toCentre);
      if (!(distanceM > 0.0f)) return Reach::None;
      axis = toCentre / distanceM;
      if (glm::dot(-axis, mLight.spotAxis) < mLight.cosCone) return Reach::None;  // outside the spot cone
      if (mLight.rangeM > 0.0f && distanceM >= mLight.rangeM) return Reach::None;  // beyond its range
      sinRadius = soft(distanceM) ? mLight.radiusM / distanceM : 0.0f;
    }
    const float cosCentre = glm::dot(n, axis);
    if (cosCentre > 0.0f) return Reach::Centre;  // faces the light's centre
    return mLight.soft && cosCentre > -sinRadius ? Reach::Horizon : Reach::None;
  }

  /// Whether a pixel that sees the light (reaches) is lit softly: by softSamples' rays.
  bool soft(float distanceM) const { return mLight.soft && distanceM > mLight.radiusM; }

  /// The soft light's samples of one pixel (distanceM: to a spot light's centre, inf for the sun),
  /// from the pixel's own random stream: the same rays on every call. onAbove(N·ω) is called for
  /// each sample above the horizon, in sample order.
  template <class OnAbove = IgnoreSample>
  void softSamples(size_t pixel, const glm::vec3& origin, const glm::vec3& n, const Receiver& receiver, float distanceM,
                   SoftSamples& out, OnAbove&& onAbove = {}) const {
    const reference::Frame frame = reference::frameAround(
        mLight.directional ? mLight.toLight : glm::normalize(mLight.centre - origin));
    const float capHeight = this->capHeight(distanceM);
    // In passes over all of the pixel's samples, each a loop whose samples are independent with
    // no call, branch or store between their arithmetic but to their own arrays, so the compiler
    // runs them several to an instruction (the generator's cost, not Embree's, was most of the
    // reference's time). The same operations in the same order as one sample at a time: the same
    // bits.
    const auto count = static_cast<size_t>(mSamples);
    for (std::vector<float>* a : {&out.x, &out.y, &out.dirX, &out.dirY, &out.dirZ, &out.cos, &out.tNear, &out.tFar})
      a->resize(count);
    float* __restrict const x = out.x.data();
    float* __restrict const y = out.y.data();
    {  // jittered in the unit square: the pixel's one random stream, x before y
      reference::Pcg32 rng(Hasher::finalise(pixel ^ (static_cast<uint64_t>(mSeed) << 32)), pixel);
      size_t k = 0;
      for (int row = 0; row < mRows; ++row)
        for (int column = 0; column < mColumns; ++column, ++k) {
          x[k] = (static_cast<float>(column) + rng.uniform()) / static_cast<float>(mColumns);
          y[k] = (static_cast<float>(row) + rng.uniform()) / static_cast<float>(mRows);
        }
    }
    for (size_t k = 0; k < count; ++k) {  // onto the unit disk
      const glm::vec2 disk = reference::concentricDisk(x[k], y[k]);
      x[k] = disk.x;
      y[k] = disk.y;
    }
    float* const dirX = out.dirX.data();
    float* const dirY = out.dirY.data();
    float* const dirZ = out.dirZ.data();
    float* const tNear = out.tNear.data();
    float* const tFar = out.tFar.data();
    directions(count, x, y, frame, capHeight, n, receiver.plane(n), receiver.errorM, dirX, dirY, dirZ, out.cos.data(),
               tNear);
    constexpr float kInf = std::numeric_limits<float>::infinity();
    if (mLight.directional) {
      std::fill(tFar, tFar + count, kInf);
    } else {
      for (size_t k = 0; k < count; ++k) tFar[k] = rayLength(origin, {dirX[k], dirY[k], dirZ[k]});
    }
    // The samples above the horizon, in order; a ray for each whose segment is not empty.
    out.cosTheta.clear();
    out.ray.clear();
    out.bundle.clear();
    const float* const cosN = out.cos.data();
    for (size_t k = 0; k < count; ++k) {
      const float cosTheta = cosN[k];
      if (cosTheta <= 0.0f) continue;
      onAbove(cosTheta);
      out.cosTheta.push_back(cosTheta);
      if (tNear[k] < tFar[k]) {
        out.ray.push_back(static_cast<int>(out.bundle.size()));
        out.bundle.add(origin, {dirX[k], dirY[k], dirZ[k]}, tNear[k], tFar[k]);
      } else {
        out.ray.push_back(-1);
      }
    }
  }

private:
  /// softSamples' directions pass: the disk points (x, y) → world directions in the cone about
  /// frame.n, N·ω (cosN) and where each ray starts (nearEnd against `plane`), for `count` samples.
  /// By value and restrict-qualified, so that nothing the loop stores can change what it reads.
  static void directions(size_t count, const float* __restrict x, const float* __restrict y, reference::Frame frame,
                         float capHeight, glm::vec3 normal, glm::vec3 plane, float errorM, float* __restrict dirX,
                         float* __restrict dirY, float* __restrict dirZ, float* __restrict cosN,
                         float* __restrict tNear) {
    for (size_t k = 0; k < count; ++k) {
      const glm::vec3 dir = frame.toWorld(reference::coneDirection(x[k], y[k], capHeight));
      dirX[k] = dir.x;
      dirY[k] = dir.y;
      dirZ[k] = dir.z;
      cosN[k] = glm::dot(normal, dir);
      tNear[k] = nearEnd(glm::dot(plane, dir), errorM);
    }
  }

  /// trace() of a soft light where the scene has translucent casters: every ray carries the RGB
  /// product of the transmittances it crosses (0 when an opaque caster stops it). The scalar V is
  /// the mean of the channels, summed in sample order like the opaque path's count, so that
  /// where no ray meets a translucent caster every value is the opaque path's, bit for bit.
  PixelOut traceSoftColour(PixelOut out, size_t pixel, const glm::vec3& origin, const glm::vec3& n, const glm::vec3& brdf,
                           const Receiver& receiver, float distanceM) const {
    thread_local SoftSamples samples;
    thread_local std::vector<glm::vec3> light;
    float sumCos = 0.0f;
    softSamples(pixel, origin, n, receiver, distanceM, samples, [&sumCos](float cosTheta) { sumCos += cosTheta; });
    mScene.transmittance(samples.bundle, light, receiver.triangle);
    const size_t above = samples.cosTheta.size();
    float sumV = 0.0f, sumCosV = 0.0f;
    glm::vec3 sumRgb(0.0f), sumCosRgb(0.0f);
    for (size_t k = 0; k < above; ++k) {
      const int ray = samples.ray[k];
      const glm::vec3 t = ray < 0 ? glm::vec3(1.0f) : light[static_cast<size_t>(ray)];
      const float v = channelMean(t), cosTheta = samples.cosTheta[k];
      sumV += v;
      sumCosV += cosTheta * v;
      sumRgb += t;
      sumCosRgb += cosTheta * t;
    }
    const float count = static_cast<float>(above);
    out.visibility = above > 0 ? sumV / count : 0.0f;
    out.visibilityCos = sumCos > 0.0f ? sumCosV / sumCos : out.visibility;
    out.visibilityRgb = above > 0 ? sumRgb / count : glm::vec3(0.0f);
    out.visibilityCosRgb = sumCos > 0.0f ? sumCosRgb / sumCos : out.visibilityRgb;
    const float weight = glm::two_pi<float>() * capHeight(distanceM) / static_cast<float>(mSamples);
    const float falloff = mLight.directional ? 1.0f : lightFalloff(mLight.light, origin);
    out.exact = brdf * mLight.radiance * ((falloff * weight) * sumCosRgb);
    out.split = brdf * mLight.radiance * (falloff * weight * sumCos * out.visibilityRgb);
    return out;
  }

  float capHeight(float distanceM) const {
    return mLight.directional ? mLight.sunCapHeight : reference::sphereOneMinusCos(mLight.radiusM, distanceM);
  }

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
      irradiance = mLight.power * (lightFalloff(mLight.light, origin) / (r * r));
      if (mLight.soft) length = 0.0f;
    }
    const float cosTheta = std::max(0.0f, glm::dot(n, dir));
    if (mScene.hasTranslucentCasters()) {  // the ray's RGB light through translucent casters
      const glm::vec3 t = length > 0.0f ? transmittance(origin, dir, n, length, receiver) : glm::vec3(1.0f);
      out.visibility = out.visibilityCos = channelMean(t);
      out.visibilityRgb = out.visibilityCosRgb = t;
      out.exact = out.split = brdf * irradiance * (cosTheta * t);
      return out;
    }
    const float v = length > 0.0f && occluded(origin, dir, n, length, receiver) ? 0.0f : 1.0f;
    out.visibility = out.visibilityCos = v;
    out.exact = out.split = brdf * irradiance * (cosTheta * v);
    return out;
  }

  /// Where a ray from the receiver starts, from the cosine between the ray and the receiver's
  /// plane (cosPlane = Receiver::plane(n)·dir) and δ: past anything within its error of its plane.
  /// The ray's height above that plane is t·cosPlane; a ray that never rises above δ (its true cos
  /// ≤ 0, beside a G-buffer normal a hair off) starts at inf: nothing it meets is distinguishable
  /// from the receiver's surface. Without a branch: the quotient is made whatever the sign, and
  /// dropped where the ray does not rise.
  static float nearEnd(float cosPlane, float errorM) {
    const float t = errorM / cosPlane;
    return cosPlane > 0.0f ? t : std::numeric_limits<float>::infinity();
  }

  /// Whether a caster blocks the ray from the receiver along dir before tFar, other than the
  /// receiver's own triangle and anything within its error of its plane.
  bool occluded(const glm::vec3& origin, const glm::vec3& dir, const glm::vec3& n, float tFar,
                const Receiver& receiver) const {
    const float tNear = nearEnd(glm::dot(receiver.plane(n), dir), receiver.errorM);
    return tNear < tFar && mScene.occluded(origin, dir, tNear, tFar, receiver.triangle);
  }

  /// occluded()'s RGB twin: the ray's light through the translucent casters it crosses.
  glm::vec3 transmittance(const glm::vec3& origin, const glm::vec3& dir, const glm::vec3& n, float tFar,
                          const Receiver& receiver) const {
    const float tNear = nearEnd(glm::dot(receiver.plane(n), dir), receiver.errorM);
    return tNear < tFar ? mScene.transmittance(origin, dir, tNear, tFar, receiver.triangle) : glm::vec3(1.0f);
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

}  // namespace penumbra::reference
