// Error over time (SequenceComparison.h).
#include "comparison/SequenceComparison.h"

#include "comparison/FrameComparison.h"

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

void addCameraWalk(Scene& scene, const SequenceTiming& timing) {
  SceneAnimation walk;
  const Camera& c = scene.camera;
  const glm::vec3 offset = c.position - c.target;
  for (int f = 0; f < timing.frames; ++f) {
    const float t = timing.timeS(f);
    const float angle = glm::radians(kWalkDegreesPerSecond * (t - timing.startS));
    const float cs = std::cos(angle), sn = std::sin(angle);
    const glm::vec3 turned{cs * offset.x + sn * offset.z, offset.y, -sn * offset.x + cs * offset.z};
    walk.camera.position.timesS.push_back(t);
    walk.camera.position.values.push_back(c.target + turned);
    walk.camera.target.timesS.push_back(t);
    walk.camera.target.values.push_back(c.target);
  }
  scene.animation = std::move(walk);
}

SequenceComparison compareSequence(Renderer& renderer, const Scene& scene, const RenderOptions& render, const SequenceTiming& timing,
                                   const ReferenceOptions& reference, const FlickerOptions& flickerOptions,
                                   const std::function<void(int)>& progress, const LagOptions& lagOptions,
                                   SequenceReferences* shared) {
  if (timing.frames < 1 || !(timing.fps > 0.0f) || !std::isfinite(timing.fps) || !std::isfinite(timing.startS))
    throw usageError(fmt::format("a sequence needs at least 1 frame and a positive frame rate ({} frames at {} fps)", timing.frames, timing.fps));
  SequenceComparison out;
  Scene posed = scene;
  std::unique_ptr<ReferenceTracer> tracer;
  std::vector<glm::mat4> traced;  // the objects' transforms the tracer was built with
  // Per shadow-casting light, its last frames, nearest first: flicker reads the first, lag them all.
  std::vector<std::deque<FlickerFrame>> earlier;
  SequenceReferences::Frame owned;  // this frame's, without `shared`
  for (int f = 0; f < timing.frames; ++f) {
    SequenceFrame frame;
    frame.timeS = timing.timeS(f);
    poseScene(posed, frame.timeS);
    renderer.setPose(posed);
    renderer.render(render);
    frame.lights = renderer.shadows().lightReports();
    const std::vector<glm::mat4> placed = transforms(posed);
    const auto f0 = static_cast<size_t>(f);
    if (!shared || shared->frames.size() <= f0) {
      SequenceReferences::Frame fresh;
      fresh.gbuffer = renderer.readGBuffer();
      if (!tracer || placed != traced) {
        tracer = std::make_unique<ReferenceTracer>(posed);
        traced = placed;
      }
      fresh.lights = traceLights(*tracer, fresh.gbuffer, posed.lights, reference);
      if (shared) {
        PN_CHECK(shared->frames.size() == f0, "compareSequence: shared references fill frame by frame");
        shared->frames.push_back(std::move(fresh));
      } else {
        owned = std::move(fresh);
      }
    }
    const SequenceReferences::Frame& at = shared ? shared->frames[f0] : owned;
    const GBufferData& gbuffer = at.gbuffer;
    const std::vector<ReferenceResult>& refs = at.lights;
    for (const ReferenceResult& r : refs) {
      out.referenceSeconds += r.traceSeconds;
      out.referenceCached = out.referenceCached && (r.fromCache || r.width == 0);
    }
    const FrameComparison cmp = compareFrame(renderer, gbuffer, refs, false);
    frame.metrics = cmp.metrics;
    frame.colour = cmp.colour;
    // Flicker and lag of each light that casts shadows (its own V and V_ref).
    size_t shadowed = 0;
    for (const LightComparison& light : cmp.lights) {
      if (!light.castsShadow) continue;
      if (shadowed == out.lights.size()) {
        out.lights.push_back({light.index, {}, {}});
        earlier.emplace_back();
      }
      LightSequence& sequence = out.lights[shadowed];
      std::deque<FlickerFrame>& before = earlier[shadowed++];
      FlickerFrame now = makeFlickerFrame(gbuffer, posed.camera, light.visibility, refs[light.index].visibility,
                                          refs[light.index].litMask, placed);
      if (f > 0) {
        const FlickerFrame& previous = before.front();
        const std::vector<FollowedPoint> points = followPoints(previous, now, flickerOptions);
        std::vector<SurfaceSample> samples;
        samples.reserve(points.size());
        for (const FollowedPoint& p : points) samples.push_back(p.at);
        // A V tinted by translucent casters (RGB) is not what visibilityAt gives (the filter's V
        // of the opaque casters alone): its flicker is read from the frame's own V at the pixel
        // the point lands on.
        std::vector<float> vAt;
        if (!light.visibilityRgb.empty())
          for (const FollowedPoint& p : points) vAt.push_back(now.v[p.to]);
        else if (!samples.empty())
          vAt = renderer.visibilityAt(samples, light.index);
        const FlickerCounts flicker = countFlicker(previous, now, points, vAt, flickerOptions);
        std::vector<const FlickerFrame*> frames;
        for (const FlickerFrame& e : before) frames.push_back(&e);
        const LagCounts lag = countLag(now, frames, lagOptions);
        sequence.flicker += flicker;
        sequence.lag += lag;
        frame.flicker += flicker;
        frame.lag += lag;
      }
      before.push_front(std::move(now));
      if (before.size() > static_cast<size_t>(std::max(lagOptions.frames, 1))) before.pop_back();
    }
    out.flicker += frame.flicker;
    out.lag += frame.lag;
    out.frames.push_back(frame);
    if (progress) progress(f);
  }
  for (size_t f = 0; f < out.frames.size(); ++f) {
    const double rmse = out.frames[f].metrics.rmse;
    out.rmseMean += rmse / static_cast<double>(out.frames.size());
    out.penumbraRmseMean += out.frames[f].metrics.penumbraRmse / static_cast<double>(out.frames.size());
    if (f == 0 || rmse > out.rmseWorst) {
      out.rmseWorst = rmse;
      out.rmseWorstFrame = f;
    }
  }
  return out;
}

}  // namespace penumbra::report
