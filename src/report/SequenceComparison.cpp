// Error over time (SequenceComparison.h).
#include "report/SequenceComparison.h"

#include "report/FrameComparison.h"

#include <penumbra/Animation.h>
#include <penumbra/Error.h>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <deque>
#include <memory>

namespace penumbra::report {
namespace {

std::vector<glm::mat4> transforms(const Scene& s) {
  std::vector<glm::mat4> out;
  out.reserve(s.objects.size());
  for (const Object& o : s.objects) out.push_back(o.worldFromObject);
  return out;
}

}  // namespace

SequenceComparison compareSequence(Renderer& renderer, const Scene& scene, const RenderOptions& render, const SequenceTiming& timing,
                                   const ReferenceOptions& reference, const FlickerOptions& flickerOptions,
                                   const std::function<void(int)>& progress, const LagOptions& lagOptions) {
  if (timing.frames < 1 || !(timing.fps > 0.0f) || !std::isfinite(timing.fps) || !std::isfinite(timing.startS))
    throw usageError(fmt::format("a sequence needs at least 1 frame and a positive frame rate ({} frames at {} fps)", timing.frames, timing.fps));
  SequenceComparison out;
  Scene posed = scene;
  std::unique_ptr<ReferenceTracer> tracer;
  std::vector<glm::mat4> traced;  // the objects' transforms the tracer was built with
  std::deque<FlickerFrame> earlier;  // the last frames, nearest first: flicker reads the first, lag them all
  for (int f = 0; f < timing.frames; ++f) {
    SequenceFrame frame;
    frame.timeS = timing.timeS(f);
    poseScene(posed, frame.timeS);
    renderer.setPose(posed);
    renderer.render(render);
    const GBufferData gbuffer = renderer.readGBuffer();
    std::vector<glm::mat4> placed = transforms(posed);
    if (!tracer || placed != traced) {
      tracer = std::make_unique<ReferenceTracer>(posed);
      traced = placed;
    }
    const std::vector<ReferenceResult> refs = traceLights(*tracer, gbuffer, posed.lights, reference);
    for (const ReferenceResult& r : refs) {
      out.referenceSeconds += r.traceSeconds;
      out.referenceCached = out.referenceCached && (r.fromCache || r.width == 0);
    }
    const FrameComparison cmp = compareFrame(renderer, gbuffer, refs, false);
    frame.metrics = cmp.metrics;
    // Flicker on the first light that casts shadows (each light's own V and V_ref).
    const LightComparison& light = *std::find_if(cmp.lights.begin(), cmp.lights.end(), [](const LightComparison& l) { return l.castsShadow; });
    FlickerFrame now = makeFlickerFrame(gbuffer, posed.camera, light.visibility, refs[light.index].visibility,
                                        refs[light.index].litMask, std::move(placed));
    if (f > 0) {
      const FlickerFrame& previous = earlier.front();
      const std::vector<FollowedPoint> points = followPoints(previous, now, flickerOptions);
      std::vector<SurfaceSample> samples;
      samples.reserve(points.size());
      for (const FollowedPoint& p : points) samples.push_back(p.at);
      const std::vector<float> vAt = samples.empty() ? std::vector<float>() : renderer.visibilityAt(samples, light.index);
      frame.flicker = countFlicker(previous, now, points, vAt, flickerOptions);
      out.flicker += frame.flicker;
      std::vector<const FlickerFrame*> before;
      for (const FlickerFrame& e : earlier) before.push_back(&e);
      frame.lag = countLag(now, before, lagOptions);
      out.lag += frame.lag;
    }
    earlier.push_front(std::move(now));
    if (earlier.size() > static_cast<size_t>(std::max(lagOptions.frames, 1))) earlier.pop_back();
    out.frames.push_back(frame);
    if (progress) progress(f);
  }
  for (size_t f = 0; f < out.frames.size(); ++f) {
    const double rmse = out.frames[f].metrics.rmse;
    out.rmseMean += rmse / static_cast<double>(out.frames.size());
    if (f == 0 || rmse > out.rmseWorst) {
      out.rmseWorst = rmse;
      out.rmseWorstFrame = f;
    }
  }
  return out;
}

}  // namespace penumbra::report
