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
};

RayBenchmark::RayBenchmark(const Scene& scene, const GBufferData& g, const Light& light, int samples)
    : mImpl(std::make_unique<Impl>(scene, g, light, samples)) {
  PN_CHECK(light.size > 0.0f, "ray benchmark: the light must be soft (size > 0): a hard light casts one ray a pixel");
  mImpl->setup = setupLight(light);
  mImpl->receivers = receiversOf(g, receiverTriangles(scene));
  const std::vector<Receiver>& receivers = mImpl->receivers;
  const PixelTracer pixelTracer(mImpl->embree, mImpl->setup, samples, ReferenceOptions{}.seed);
  SoftSamples pixelSamples;
  const size_t pixels = static_cast<size_t>(g.width) * static_cast<size_t>(g.height);
  mImpl->start.assign(pixels + 1, 0);
  mImpl->skip.resize(pixels);
  for (size_t i = 0; i < pixels; ++i) {
    mImpl->start[i] = mImpl->rays.size();
    mImpl->skip[i] = receivers[i].triangle;
    if (!g.covered(i)) continue;
    const glm::vec3 origin(g.position[i]);
    glm::vec3 n;
    float distanceM = 0.0f;
    if (!pixelTracer.facesLight(origin, glm::vec3(g.geoNormal[i]), n, distanceM) || !pixelTracer.soft(distanceM)) continue;
    pixelTracer.softSamples(i, origin, n, receivers[i], distanceM, pixelSamples);
    mImpl->rays.insert(mImpl->rays.end(), pixelSamples.bundle.rays.begin(), pixelSamples.bundle.rays.end());
  }
  mImpl->start[pixels] = mImpl->rays.size();
  EmbreeScene::Bundle bundle;
  for (size_t i = 0; i < pixels; ++i) {
    bundle.rays.assign(mImpl->rays.begin() + static_cast<std::ptrdiff_t>(mImpl->start[i]),
                       mImpl->rays.begin() + static_cast<std::ptrdiff_t>(mImpl->start[i + 1]));
    mImpl->embree.occluded(bundle, mImpl->skip[i]);
    for (size_t k = 0; k < bundle.size(); ++k) mImpl->blocked += bundle.blocked(k);
  }
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

double RayBenchmark::tracePlainLoop() const {
  const Impl& m = *mImpl;
  std::atomic<size_t> blocked{0};  // kept: the answers are used, as the tracer uses them
  const auto start = std::chrono::steady_clock::now();
  tbb::parallel_for(tbb::blocked_range<int>(0, m.g.height), [&](const tbb::blocked_range<int>& rows) {
    thread_local EmbreeScene::Bundle bundle;  // Embree writes its answers into the rays: a copy
    size_t count = 0;
    for (int y = rows.begin(); y != rows.end(); ++y)
      for (int x = 0; x < m.g.width; ++x) {
        const size_t i = static_cast<size_t>(y) * static_cast<size_t>(m.g.width) + static_cast<size_t>(x);
        if (m.start[i] == m.start[i + 1]) continue;
        bundle.rays.assign(m.rays.begin() + static_cast<std::ptrdiff_t>(m.start[i]),
                           m.rays.begin() + static_cast<std::ptrdiff_t>(m.start[i + 1]));
        m.embree.occluded(bundle, m.skip[i]);
        for (size_t k = 0; k < bundle.size(); ++k) count += bundle.blocked(k);
      }
    blocked += count;
  });
  const double seconds = secondsSince(start);
  PN_CHECK(blocked.load() == m.blocked, "ray benchmark: the plain loop found other rays blocked than the recording did");
  return seconds;
}

double RayBenchmark::traceSingleRays() const {
  const Impl& m = *mImpl;
  std::atomic<size_t> blocked{0};  // kept: the answers are used, as the tracer uses them
  const auto start = std::chrono::steady_clock::now();
  tbb::parallel_for(tbb::blocked_range<int>(0, m.g.height), [&](const tbb::blocked_range<int>& rows) {
    size_t count = 0;
    for (int y = rows.begin(); y != rows.end(); ++y)
      for (int x = 0; x < m.g.width; ++x) {
        const size_t i = static_cast<size_t>(y) * static_cast<size_t>(m.g.width) + static_cast<size_t>(x);
        for (size_t k = m.start[i]; k != m.start[i + 1]; ++k) {
          const RTCRay& ray = m.rays[k];
          count += m.embree.occluded({ray.org_x, ray.org_y, ray.org_z}, {ray.dir_x, ray.dir_y, ray.dir_z}, ray.tnear,
                                     ray.tfar, m.skip[i]);
        }
      }
    blocked += count;
  });
  const double seconds = secondsSince(start);
  PN_CHECK(blocked.load() == m.blocked, "ray benchmark: one call a ray found other rays blocked than the stream did");
  return seconds;
}

double RayBenchmark::traceGeneratingLoop() const {
  const Impl& m = *mImpl;
  const PixelTracer pixelTracer(m.embree, m.setup, m.samples, ReferenceOptions{}.seed);
  std::atomic<size_t> rays{0};
  const auto start = std::chrono::steady_clock::now();
  tbb::parallel_for(tbb::blocked_range<int>(0, m.g.height), [&](const tbb::blocked_range<int>& rows) {
    thread_local SoftSamples samples;
    size_t count = 0;
    for (int y = rows.begin(); y != rows.end(); ++y)
      for (int x = 0; x < m.g.width; ++x) {
        const size_t i = static_cast<size_t>(y) * static_cast<size_t>(m.g.width) + static_cast<size_t>(x);
        if (!m.g.covered(i)) continue;
        const glm::vec3 origin(m.g.position[i]);
        glm::vec3 n;
        float distanceM = 0.0f;
        if (!pixelTracer.facesLight(origin, glm::vec3(m.g.geoNormal[i]), n, distanceM) || !pixelTracer.soft(distanceM)) continue;
        pixelTracer.softSamples(i, origin, n, m.receivers[i], distanceM, samples);
        m.embree.occluded(samples.bundle, m.receivers[i].triangle);
        count += samples.bundle.size();
      }
    rays += count;
  });
  const double seconds = secondsSince(start);
  PN_CHECK(rays.load() == m.rays.size(), "ray benchmark: the generating loop cast other rays than the recorded ones");
  return seconds;
}

}  // namespace penumbra::reference
