// The engine-facing core (penumbra/Shadows.h): for each light, projection → shadow pass →
// prefilter → visibility (→ contact shadows → temporal accumulation), against the caller's
// camera, surfaces and casters, into that light's layer of the visibility array. No
// technique-specific branch lives here: the Projection and the Filter do that work. Each light
// has its own state (core/LightState.h) under its key, made from the light's technique: the
// Shadows' technique with the light's own settings merged in.
#include "core/ShadowsImpl.h"

namespace penumbra {

Shadows::Shadows() {
  PN_CHECK(epoxy_gl_version() >= 45, fmt::format("penumbra::Shadows needs a current OpenGL 4.5 core context (this one is {}.{})",
                                                 epoxy_gl_version() / 10, epoxy_gl_version() % 10));
  mImpl = std::make_unique<Impl>();
}

Shadows::~Shadows() = default;

void Shadows::setTechnique(const Technique& technique) { mImpl->technique = technique; }

const Technique& Shadows::technique() const { return mImpl->technique; }

void Shadows::setCasters(std::span<const CasterMesh> casters, const ShadowReceivers& receivers) {
  Impl& im = *mImpl;
  im.casters.set(casters);
  im.extent.bodies = im.casters.bodies();
  im.staticExtent.bodies = im.casters.bodies(CasterSet::Which::Static);
  im.staticCasters = !im.staticExtent.bodies.empty();
  for (const Aabb& b : receivers.bounds)
    for (SceneExtent* e : {&im.extent, &im.staticExtent}) e->bodies.push_back({b, false});
  im.receiversComplete = receivers.complete;
}

void Shadows::setCasterGeometry(std::span<const CasterGeometry> casters) {
  for (size_t i = 0; i < casters.size(); ++i) checkCasterGeometry(casters[i], i);
  mImpl->geometry.emplace(casters.begin(), casters.end());
}

void Shadows::setMapUpdates(const MapUpdates& updates) {
  core::checkMapUpdates(updates, "");
  Impl& im = *mImpl;
  im.mapUpdates = updates;
  im.mapCache = {};
  im.schedule.reset();
}

const MapUpdates& Shadows::mapUpdates() const { return mImpl->mapUpdates; }

Shadows::MapCacheStats Shadows::mapCacheStats() const {
  const Impl& im = *mImpl;
  return {im.mapCache.restored, im.mapCache.rendered, im.schedule.kept(), im.schedule.maxStaleness(), im.schedule.meanStaleness()};
}

void Shadows::render(const ShadowFrameInputs& in) {
  Impl& im = *mImpl;
  im.checkInputs(in);
  const std::vector<Technique> techniques = im.lightTechniques(in.lights);
  // An error the caller's own calls left is theirs: say so, rather than blame a pass below.
  gl::throwIfGlError("the caller's GL calls before Shadows::render");

  const core::StateScope scope(in.restore);
  core::setPassDefaults();
  const ShadowSurfaces& s = in.surfaces;
  im.screen = {s.width, s.height};
  im.surface = {s.position != 0 ? SurfaceSource::Position : SurfaceSource::Depth, s.normal == 0, in.camera.fit.orthographic()};
  im.takeStates(in.lights, techniques);
  im.colour = std::any_of(im.states.begin(), im.states.end(), [&](const auto& st) { return st->light.castsShadow && im.tints(*st); });
  im.ensureVisibility(im.screen, static_cast<int>(in.lights.size()));
  im.timer.beginFrame();

  // What the views are fitted to this frame: the casters, the given receivers and, unless they
  // are complete, the surfaces the camera sees.
  SceneExtent all = im.extent, still = im.staticExtent;
  if (!im.receiversComplete) {
    const Aabb seen = im.measureSurfaces(in);
    for (SceneExtent* e : {&all, &still})
      if (!seen.empty()) e->bodies.push_back({seen, false});
  }

  // The budget: each shadowed light's share by its importance on screen, counting the maps its
  // projection makes for it (cascades, cube faces) at the size its technique asks for.
  std::vector<core::BudgetRequest> requests;
  const Aabb bounds = all.bounds();
  for (const auto& st : im.states) {
    const int requested = st->technique.mapSize();
    int views = 0;
    if (st->light.castsShadow && in.mapBudgetTexels > 0)
      views = static_cast<int>(
          st->projection->computeFrusta(in.camera.fit, in.camera.aspect, st->light, im.fitExtent(st->light, all, still), requested).views.size());
    requests.push_back({requested, views, core::lightImportance(st->light, in.camera.fit, in.camera.aspect, bounds)});
  }
  const std::vector<int> sizes = core::allocateMapSizes(requests, in.mapBudgetTexels);
  im.reports.assign(in.lights.size(), {});
  const gl::MemoryAccount::Charge charge(im.techniqueMemory);
  im.clipFromWorld = in.camera.clipFromView * in.camera.viewFromWorld;
  bool accumulates = false;
  for (const auto& st : im.states) accumulates = accumulates || TemporalAccumulation::enabled(st->technique.addOnValues());
  // A pixel's width per metre of distance: 2·tan(fovY/2) / height, from the projection's y scale
  // (orthographic: the pixel's width itself).
  im.samplingFrame = im.temporal.beginFrame(accumulates, {.screen = im.screen,
                                                          .cut = in.cameraCut,
                                                          .clipFromWorld = im.clipFromWorld,
                                                          .pixelFootprintPerM = 2.0f / (in.camera.clipFromView[1][1] * static_cast<float>(s.height))});
  std::vector<core::MapUpdateSchedule::LightPolicy> policies;
  for (const auto& st : im.states)
    policies.push_back({st->key, st->light.castsShadow, im.updatesOf(st->light), st->light.shadow.updates.has_value()});
  im.schedule.beginFrame(policies);
  for (size_t i = 0; i < im.states.size(); ++i) {
    core::LightState& st = *im.states[i];
    st.mapSize = sizes[i];
    im.renderLight(st, in, all, still);
    const bool shadows = st.light.castsShadow;
    im.reports[i] = {st.light.id, requests[i].requestedMapSize, st.mapSize, shadows ? static_cast<int>(st.frusta.views.size()) : 0,
                     requests[i].importance, im.updatesOf(st.light),
                     shadows ? static_cast<int>(std::count(st.keptViews.begin(), st.keptViews.end(), uint8_t{1})) : 0,
                     shadows ? im.schedule.staleness(st.key) : 0, {}};
    if (shadows && st.pages) {
      const PageStats& p = st.pages->stats();
      im.reports[i].pages = {p.needed, p.drawn, p.resident, p.missing, p.poolPages, p.poolBytes};
    }
  }
  if (accumulates) {
    ScopedPass pass(im.timer, "temporal");
    im.endTemporalFrame(in);
  }
  ++im.frameIndex;
  im.timings = im.timer.endFrame();
}

size_t Shadows::lightCount() const { return mImpl->states.size(); }

uint32_t Shadows::visibilityTexture(size_t light) const {
  PN_CHECK(light < mImpl->layerViews.size(),
           fmt::format("visibilityTexture({}): the last frame had {} lights", light, mImpl->layerViews.size()));
  return mImpl->layerViews[light].id();
}

uint32_t Shadows::visibilityArrayTexture() const { return mImpl->visibility.id(); }

std::vector<float> Shadows::readVisibility(size_t light) const {
  PN_CHECK(light < mImpl->layerViews.size(),
           fmt::format("readVisibility({}): the last frame had {} lights", light, mImpl->layerViews.size()));
  if (mImpl->colour) {  // the mean of the channels, as the reference's one-channel V of a tinted light
    const std::vector<glm::vec3> rgb = readVisibilityRgb(light);
    std::vector<float> v(rgb.size());
    std::transform(rgb.begin(), rgb.end(), v.begin(), [](const glm::vec3& c) { return (c.r + c.g + c.b) / 3.0f; });
    return v;
  }
  const gl::Texture& t = mImpl->layerViews[light];
  std::vector<float> v(static_cast<size_t>(t.width()) * static_cast<size_t>(t.height()));
  const core::PixelTransferScope transfer;
  if (t) t.read(GL_RED, GL_FLOAT, v.data(), v.size() * sizeof(float));
  return v;
}

bool Shadows::visibilityHasColour() const { return mImpl->colour; }

std::vector<glm::vec3> Shadows::readVisibilityRgb(size_t light) const {
  PN_CHECK(light < mImpl->layerViews.size(),
           fmt::format("readVisibilityRgb({}): the last frame had {} lights", light, mImpl->layerViews.size()));
  if (!mImpl->colour) return {};
  const gl::Texture& t = mImpl->layerViews[light];
  std::vector<glm::vec4> texels(static_cast<size_t>(t.width()) * static_cast<size_t>(t.height()));
  {
    const core::PixelTransferScope transfer;
    t.read(GL_RGBA, GL_FLOAT, texels.data(), texels.size() * sizeof(glm::vec4));
  }
  std::vector<glm::vec3> v(texels.size());
  std::transform(texels.begin(), texels.end(), v.begin(), [](const glm::vec4& c) { return glm::vec3(c); });
  return v;
}

const std::vector<LightShadowReport>& Shadows::lightReports() const { return mImpl->reports; }
const PassTimings& Shadows::timings() const { return mImpl->timings; }
std::size_t Shadows::techniqueMemoryBytes() const { return static_cast<std::size_t>(mImpl->techniqueMemory.bytes()); }

}  // namespace penumbra
