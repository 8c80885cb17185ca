#include "reference/RayBenchmark.h"

#include "reference/PixelTracer.h"

#include <penumbra/Error.h>
#include <penumbra/Reference.h>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <atomic>
#include <chrono>

namespace penumbra::reference {

struct RayBenchmark::Impl {
  Impl(const Scene& s, const GBufferData& gbuffer, const Light& l, int n)
      : scene(s), g(gbuffer), light(l), samples(n), tracer(scene), embree(scene) {}
  Scene scene;
  GBufferData g;
  Light light;
  int samples;
  ReferenceTracer tracer;
  EmbreeScene embree;  // the same triangles, built the same way as the tracer's
  // Every traced ray of every pixel, in pixel order; pixel p's are [start[p], start[p + 1]).
  std::vector<RTCRay> rays;
  std::vector<size_t> start;
  std::vector<TriangleId> skip;
  size_t blocked = 0;  // how many of the rays a caster blocks: every way of casting them agrees
  LightSetup setup;
  std::vector<Receiver> receivers;

  /// Pixel i's rays into samples.bundle, as the tracer makes them; false for a pixel the soft
  /// light does not reach (no rays).
  bool generate(const PixelTracer& pixelTracer, size_t i, SoftSamples& out) const {
    if (!g.covered(i)) return false;
    const glm::vec3 origin(g.position[i]);
    glm::vec3 n;
    float distanceM = 0.0f;
    if (pixelTracer.reaches(origin, glm::vec3(g.geoNormal[i]), n, distanceM) == Reach::None || !pixelTracer.soft(distanceM))
      return false;
    pixelTracer.softSamples(i, origin, n, receivers[i], distanceM, out);
    return true;
  }

  /// Pixel i's recorded rays cast as one coherent stream (a copy in `bundle`: Embree writes its
  /// answers into the rays); how many are blocked.
  size_t castRecorded(size_t i, EmbreeScene::Bundle& bundle) const {
    if (start[i] == start[i + 1]) return 0;
    bundle.rays.assign(rays.begin() + static_cast<std::ptrdiff_t>(start[i]), rays.begin() + static_cast<std::ptrdiff_t>(start[i + 1]));
    embree.occluded(bundle, skip[i]);
    size_t count = 0;
    for (size_t k = 0; k < bundle.size(); ++k) count += bundle.blocked(k);
    return count;
  }

  /// Σ perPixel(i) over every pixel, rows over every core as the tracer runs them.
  template <class PerPixel>
  size_t sumOverPixels(const PerPixel& perPixel) const {
    std::atomic<size_t> sum{0};
    tbb::parallel_for(tbb::blocked_range<int>(0, g.height), [&](const tbb::blocked_range<int>& rows) {
      size_t part = 0;
      for (int y = rows.begin(); y != rows.end(); ++y)
        for (int x = 0; x < g.width; ++x)
          part += perPixel(static_cast<size_t>(y) * static_cast<size_t>(g.width) + static_cast<size_t>(x));
      sum += part;
    });
    return sum.load();
  }
};

RayBenchmark::RayBenchmark(const Scene& scene, const GBufferData& g, const Light& light, int samples)
    : mImpl(std::make_unique<Impl>(scene, g, light, samples)) {
  PN_CHECK(light.size > 0.0f, "ray benchmark: the light must be soft (size > 0): a hard light casts one ray a pixel");
  Impl& m = *mImpl;
  m.setup = setupLight(light);
  m.receivers = receiversOf(g, receiverTriangles(scene));
  const PixelTracer pixelTracer(m.embree, m.setup, samples, ReferenceOptions{}.seed);
  SoftSamples pixelSamples;
  const size_t pixels = static_cast<size_t>(g.width) * static_cast<size_t>(g.height);
  m.start.assign(pixels + 1, 0);
  m.skip.resize(pixels);
  for (size_t i = 0; i < pixels; ++i) {
    m.start[i] = m.rays.size();
    m.skip[i] = m.receivers[i].triangle;
    if (m.generate(pixelTracer, i, pixelSamples))
      m.rays.insert(m.rays.end(), pixelSamples.bundle.rays.begin(), pixelSamples.bundle.rays.end());
  }
  m.start[pixels] = m.rays.size();
  EmbreeScene::Bundle bundle;
  for (size_t i = 0; i < pixels; ++i) m.blocked += m.castRecorded(i, bundle);
}

RayBenchmark::~RayBenchmark() = default;

size_t RayBenchmark::rays() const { return mImpl->rays.size(); }

namespace {
double secondsSince(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}
}  // namespace

double RayBenchmark::traceReference() const {
  ReferenceOptions options;
  options.samples = mImpl->samples;
  options.useCache = false;
  options.progress = false;
  const auto start = std::chrono::steady_clock::now();
  const ReferenceResult r = mImpl->tracer.trace(mImpl->g, mImpl->light, options);
  PN_CHECK(r.width == mImpl->g.width, "ray benchmark: the reference traced another size");
  return secondsSince(start);
}

// The two loops over the recorded rays sum Embree's answers, as the tracer reads them, and check
// the sum against the recording's.

double RayBenchmark::tracePlainLoop() const {
  const Impl& m = *mImpl;
  const auto start = std::chrono::steady_clock::now();
  const size_t blocked = m.sumOverPixels([&m](size_t i) {
    thread_local EmbreeScene::Bundle bundle;
    return m.castRecorded(i, bundle);
  });
  const double seconds = secondsSince(start);
  PN_CHECK(blocked == m.blocked, "ray benchmark: the plain loop found other rays blocked than the recording did");
  return seconds;
}

double RayBenchmark::traceSingleRays() const {
  const Impl& m = *mImpl;
  const auto start = std::chrono::steady_clock::now();
  const size_t blocked = m.sumOverPixels([&m](size_t i) {
    size_t count = 0;
    for (size_t k = m.start[i]; k != m.start[i + 1]; ++k) {
      const RTCRay& ray = m.rays[k];
      count += m.embree.occluded({ray.org_x, ray.org_y, ray.org_z}, {ray.dir_x, ray.dir_y, ray.dir_z}, ray.tnear, ray.tfar,
                                 m.skip[i]);
    }
    return count;
  });
  const double seconds = secondsSince(start);
  PN_CHECK(blocked == m.blocked, "ray benchmark: one call a ray found other rays blocked than the stream did");
  return seconds;
}

double RayBenchmark::traceGeneratingLoop() const {
  const Impl& m = *mImpl;
  const PixelTracer pixelTracer(m.embree, m.setup, m.samples, ReferenceOptions{}.seed);
  const auto start = std::chrono::steady_clock::now();
  const size_t rays = m.sumOverPixels([&](size_t i) -> size_t {
    thread_local SoftSamples samples;
    if (!m.generate(pixelTracer, i, samples)) return 0;
    m.embree.occluded(samples.bundle, m.receivers[i].triangle);
    return samples.bundle.size();
  });
  const double seconds = secondsSince(start);
  PN_CHECK(rays == m.rays.size(), "ray benchmark: the generating loop cast other rays than the recorded ones");
  return seconds;
}

}  // namespace penumbra::reference
