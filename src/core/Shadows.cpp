// The engine-facing core (penumbra/Shadows.h): for each light, projection → shadow pass →
// prefilter → visibility (→ contact shadows → temporal accumulation), against the caller's
// camera, surfaces and casters, into that light's layer of the visibility array. No technique-specific branch lives here: the
// Projection and the Filter do that work. Each light has its own technique objects (their maps
// are its own): light 0 runs the technique set with setTechnique itself, the others copies of it,
// and a light's own shadow settings are applied over its copy for its frame.
#include <penumbra/Error.h>
#include <penumbra/Registry.h>
#include <penumbra/Shadows.h>

#include "core/FrameBlocks.h"
#include "core/GlState.h"
#include "base/Hash.h"
#include "core/MapUpdateSchedule.h"
#include "core/ShadowBudget.h"
#include "frame/CasterSet.h"
#include "frame/FrameContext.h"
#include "frame/PassTimer.h"
#include "frame/PixelBoundsReducer.h"
#include "gl/Debug.h"
#include "gl/Objects.h"
#include "shader/ShaderLibrary.h"
#include "shadows/contact/ContactShadows.h"
#include "shadows/temporal/TemporalAccumulation.h"
#include "shared/Bindings.h"
#include "shared/VisibilityPoints.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <optional>

namespace penumbra {
namespace {

constexpr size_t kFilterBlockBytes = 4096;  // room for any filter's uniform block
constexpr int kMaxSurfaceSide = 16384;      // pixels per side of the surfaces

/// Restores the saved state when the frame ends, however it ends.
class StateScope {
public:
  explicit StateScope(RestoreState restore) {
    if (restore == RestoreState::All) mSaved.emplace();
  }
  ~StateScope() {
    if (mSaved) mSaved->restore();
  }
  StateScope(const StateScope&) = delete;
  StateScope& operator=(const StateScope&) = delete;

private:
  std::optional<core::SavedGlState> mSaved;
};

/// Whether `key` ("pcss.blockerSamples") is a parameter of a registered projection or filter. A
/// light's settings may hold keys of techniques other than the one in use (a scene file written
/// for several): they apply when that technique runs.
bool isTechniqueParam(std::string_view key) {
  const std::string id(key.substr(0, key.find('.')));
  for (const std::string& p : projectionIds())
    if (p == id) return makeProjection(id)->hasParam(key);
  for (const std::string& f : filterIds())
    if (f == id) return makeFilter(id)->hasParam(key);
  return false;
}

void checkTexture(uint32_t name, const char* what) {
  if (name != 0 && !glIsTexture(name)) throw usageError(fmt::format("ShadowSurfaces::{} = {} is not a GL texture", what, name));
}

}  // namespace

/// One light's technique and what its last frame made.
struct LightSlot {
  std::unique_ptr<Projection> ownProjection;  ///< lights 1..: a copy of the technique's projection
  std::unique_ptr<Filter> ownFilter;          ///< … and filter (light 0 runs the technique's own)
  Light light;
  LightFrusta frusta;
  gl::Buffer frameBlock{"frame block", sizeof(gpu::FrameUniforms)};
  gl::Buffer shadowBlock{"shadow block", sizeof(gpu::ShadowUniforms)};
  gl::Texture visibilityView;  ///< its layer of the visibility array, as a 2D texture
  ScreenTarget visibilityTarget;  ///< its layer of the visibility array, as the visibility pass's target
  int mapSize = 0;
  std::vector<uint8_t> keptViews;  ///< per view: kept from an earlier frame (MapUpdates::Budget)
};

struct Shadows::Impl {
  ShaderLibrary shaders;
  PassTimer timer{gl::isSoftwareRenderer(gl::glString(GL_RENDERER))};
  gl::Buffer filterBlock{"filter block", kFilterBlockBytes};
  // Engine textures are read through this sampler, whatever their own sampling state.
  gl::Sampler surfaceSampler{"surface sampler", {GL_NEAREST, GL_NEAREST, GL_CLAMP_TO_EDGE, false}};
  gl::Texture visibility;  ///< 2D array, one layer per light
  CasterSet casters;
  SceneExtent extent;        ///< every caster and receiver
  SceneExtent staticExtent;  ///< the static casters and the receivers
  bool staticCasters = false;
  const Scene* cpuScene = nullptr;
  std::unique_ptr<Projection> projection;
  std::unique_ptr<Filter> filter;
  // What the filter allocates during its passes; a replaced filter's storage leaves the count
  // when it is destroyed.
  gl::MemoryAccount techniqueMemory;
  std::unique_ptr<Parameterized> addOns = makeAddOns();  // contact.*, temporal.*
  TemporalAccumulation temporal;
  int samplingFrame = 0;               // this frame's (TemporalAccumulation::beginFrame)
  glm::mat4 clipFromWorld{1.0f};       // the last frame's camera
  std::vector<std::unique_ptr<LightSlot>> slots;
  std::vector<LightShadowReport> reports;
  PassTimings timings;
  glm::ivec2 screen{0};
  SurfaceSource surface = SurfaceSource::Position;
  int frameIndex = 0;
  MapUpdates mapUpdates;
  MapCacheState mapCache;
  core::MapUpdateSchedule schedule;

  /// The light's own map updates, or the Shadows' policy.
  const MapUpdates& updatesOf(const Light& l) const { return l.shadow.updates ? *l.shadow.updates : mapUpdates; }
  /// What the light's views are fitted to: every body, or with cached maps the static casters
  /// and the receivers (a moving dynamic caster then leaves the views, and so the maps' static
  /// layers, where they are), unless no caster is static.
  const SceneExtent& fitExtent(const Light& l) const { return updatesOf(l).cached() && staticCasters ? staticExtent : extent; }

  Projection& projectionOf(size_t i) { return i == 0 ? *projection : *slots[i]->ownProjection; }
  Filter& filterOf(size_t i) { return i == 0 ? *filter : *slots[i]->ownFilter; }
  const Filter& filterOf(size_t i) const { return i == 0 ? *filter : *slots[i]->ownFilter; }

  FrameContext frameContext(size_t i) {
    LightSlot& s = *slots[i];
    return FrameContext({s.light, cpuScene, s.frusta, s.mapSize, screen, surface, shaders, casters, filterBlock, timer,
                         &visibility, static_cast<int>(i), updatesOf(s.light).cached() ? &mapCache : nullptr, s.keptViews,
                         &s.visibilityTarget});
  }
  void bindBlocks(size_t i) const {
    slots[i]->frameBlock.bindBase(GL_UNIFORM_BUFFER, PN_UBO_FRAME);
    slots[i]->shadowBlock.bindBase(GL_UNIFORM_BUFFER, PN_UBO_SHADOW);
  }
  void checkPair(const Light& l, const std::string& which = "") const {
    if (const std::string why = projection->incompatibility(l); !why.empty())
      throw usageError(fmt::format("--projection {} is not supported for {}: {}", projection->id(),
                                   which.empty() ? "this light" : which, why));
    const std::string why = filter->incompatibility(projection->id(), l);
    if (!why.empty())
      throw usageError(fmt::format("{}--filter {} with --projection {} is not supported: {}", which.empty() ? "" : which + ": ",
                                   filter->id(), projection->id(), why));
  }

  /// One slot per light, with copies of the technique for lights 1.. (remade when the technique
  /// or the count changes; kept otherwise: the copies' maps stay allocated).
  void ensureSlots(size_t count) {
    const bool sameTechnique = slots.size() < 2 || (slots[1]->ownProjection->id() == projection->id() &&
                                                     slots[1]->ownFilter->id() == filter->id());
    if (slots.size() == count && sameTechnique) return;
    if (!sameTechnique) slots.clear();
    while (slots.size() > count) slots.pop_back();
    while (slots.size() < count) {
      auto s = std::make_unique<LightSlot>();
      if (!slots.empty()) {
        s->ownProjection = makeProjection(projection->id());
        s->ownFilter = makeFilter(filter->id());
      }
      slots.push_back(std::move(s));
    }
  }

  /// The visibility array (one layer per light) and each slot's view of its layer. Slots remade by
  /// ensureSlots (a new technique, more lights) get their views here even when the array stays.
  void ensureVisibility(glm::ivec2 size, int layers) {
    if (!visibility || visibility.width() != size.x || visibility.height() != size.y || visibility.layers() != layers) {
      for (auto& s : slots) {
        s->visibilityView = gl::Texture();
        s->visibilityTarget = ScreenTarget();
      }
      visibility = gl::Texture("visibility", {GL_TEXTURE_2D_ARRAY, GL_R32F, size.x, size.y, layers, 1});
      visibility.setSampling(GL_NEAREST, GL_NEAREST);
    }
    for (size_t i = 0; i < slots.size(); ++i) {
      if (slots[i]->visibilityView) continue;
      slots[i]->visibilityView = gl::Texture::layerView(fmt::format("visibility of light {}", i), visibility, static_cast<int>(i));
      slots[i]->visibilityView.setSampling(GL_NEAREST, GL_NEAREST);
      slots[i]->visibilityTarget = ScreenTarget(fmt::format("visibility pass of light {}", i), visibility, static_cast<int>(i));
    }
  }

  /// The light's own settings over its technique for this frame: its copy's parameters are the
  /// technique's, then its overrides; light 0's overrides go on the technique itself and come off
  /// after the frame (the returned snapshot).
  std::optional<std::pair<Parameterized, Parameterized>> applySettings(size_t i, const Light& light) {
    Projection& p = projectionOf(i);
    Filter& f = filterOf(i);
    std::optional<std::pair<Parameterized, Parameterized>> snapshot;
    if (i > 0) {
      static_cast<Parameterized&>(p) = static_cast<const Parameterized&>(*projection);
      static_cast<Parameterized&>(f) = static_cast<const Parameterized&>(*filter);
    } else if (!light.shadow.params.empty()) {
      snapshot.emplace(static_cast<const Parameterized&>(p), static_cast<const Parameterized&>(f));
    }
    for (const auto& [key, value] : light.shadow.params) {
      if (p.hasParam(key)) p.setParam(key, std::string_view(value));
      else if (f.hasParam(key)) f.setParam(key, std::string_view(value));
      else if (!isTechniqueParam(key))  // another technique's key waits for it
        throw usageError(fmt::format("light {}: shadow.params.{}: not a parameter of any projection or filter", i, key));
    }
    return snapshot;
  }

  /// How many maps light i's projection makes for it (with its own settings).
  int viewCount(size_t i, const Light& light, const ShadowCamera& camera, int mapSize) {
    const auto snapshot = applySettings(i, light);
    const int views = static_cast<int>(projectionOf(i).computeFrusta(camera.fit, camera.aspect, light, fitExtent(light), mapSize).views.size());
    restore(i, snapshot);
    return views;
  }

  void restore(size_t i, const std::optional<std::pair<Parameterized, Parameterized>>& snapshot) {
    if (!snapshot) return;
    static_cast<Parameterized&>(projectionOf(i)) = snapshot->first;
    static_cast<Parameterized&>(filterOf(i)) = snapshot->second;
  }

  void renderLight(size_t i, const ShadowFrameInputs& in) {
    LightSlot& slot = *slots[i];
    const ShadowSurfaces& s = in.surfaces;
    gpu::FrameUniforms frame = core::frameUniforms(in.camera, slot.light, screen, frameIndex, extent.bounds().radius());
    frame.screen.w = samplingFrame;
    slot.frameBlock.upload(frame);
    if (!slot.light.castsShadow) {  // lit wherever the light reaches: V = 1 in its layer
      temporal.skip(static_cast<int>(i));
      const float one = 1.0f;
      glClearTexSubImage(visibility.id(), 0, 0, 0, static_cast<GLint>(i), screen.x, screen.y, 1, GL_RED, GL_FLOAT, &one);
      return;
    }
    const auto snapshot = applySettings(i, slot.light);
    Projection& projectionI = projectionOf(i);
    Filter& filterI = filterOf(i);
    // A projection fitted to the pixels (sdsm) measures them here, on the GPU, before its views
    // exist; the others ask nothing and no pass runs.
    PixelBoundsReducer pixels(shaders, surface, screen, in.camera.fit, timer,
                              [&] {
                                slot.frameBlock.bindBase(GL_UNIFORM_BUFFER, PN_UBO_FRAME);
                                bindSurfaces(s);
                              },
                              [] { unbindSurfaces(); });
    slot.frusta = projectionI.computeFrustaFromPixels(in.camera.fit, in.camera.aspect, slot.light, fitExtent(slot.light),
                                                      slot.mapSize, pixels);
    slot.keptViews = schedule.apply(i, slot.frusta, slot.mapSize);
    slot.shadowBlock.upload(core::shadowUniforms(slot.frusta, slot.mapSize));
    bindBlocks(i);
    FrameContext ctx = frameContext(i);
    {
      ScopedPass pass(timer, "shadow");
      filterI.renderShadowMaps(ctx);
    }
    gl::throwIfGlError("the shadow pass");
    {
      ScopedPass pass(timer, "prefilter");
      filterI.prefilter(ctx);
    }
    gl::throwIfGlError("the prefilter pass");
    bindSurfaces(s);
    {
      ScopedPass pass(timer, "visibility");
      filterI.computeVisibility(ctx);
    }
    if (ContactShadows::enabled(*addOns)) {
      ScopedPass pass(timer, "contact");
      ContactShadows::apply(ctx, *addOns);
    }
    if (TemporalAccumulation::enabled(*addOns)) {
      ScopedPass pass(timer, "temporal");
      temporal.apply(ctx, *addOns);
    }
    unbindSurfaces();
    gl::throwIfGlError("the visibility pass");
    restore(i, snapshot);
  }

  /// The caller's surfaces where the screen passes read them, through Penumbra's own sampler.
  void bindSurfaces(const ShadowSurfaces& s) {
    glBindTextureUnit(PN_TEX_GBUF_POSITION, surface == SurfaceSource::Position ? s.position : s.depth);
    glBindTextureUnit(PN_TEX_GBUF_GEONORMAL, s.normal);
    surfaceSampler.bindUnit(PN_TEX_GBUF_POSITION);
    surfaceSampler.bindUnit(PN_TEX_GBUF_GEONORMAL);
  }
  static void unbindSurfaces() {
    gl::Sampler::unbindUnit(PN_TEX_GBUF_POSITION);
    gl::Sampler::unbindUnit(PN_TEX_GBUF_GEONORMAL);
  }

  /// What the accumulated V depends on besides the surfaces and the lights: the technique and
  /// every parameter but the accumulation's own (its history is dropped when this changes).
  uint64_t techniqueKey() const {
    Hasher h;
    const auto values = [&h](const Parameterized& p, bool skipTemporal) {
      for (const ParamDesc& d : p.paramDescs())
        if (!(skipTemporal && d.key.starts_with("temporal."))) h.value(p.param(d.key));
    };
    h.text(projection->id());
    h.text(filter->id());
    values(*projection, false);
    values(*filter, false);
    values(*addOns, true);
    return h.digest();
  }

  /// With accumulation on, V at world points as accumulated: the last frame's layer, bilinear
  /// between the four pixel centres around each point's position on screen. Points off screen
  /// keep the V they have.
  void accumulatedAt(std::span<const SurfaceSample> points, size_t light, std::vector<float>& v) const {
    const gl::Texture& layer = slots[light]->visibilityView;
    std::vector<float> image(static_cast<size_t>(screen.x) * static_cast<size_t>(screen.y));
    layer.read(GL_RED, GL_FLOAT, image.data(), image.size() * sizeof(float));
    const auto at = [&](int x, int y) {
      return image[static_cast<size_t>(std::clamp(y, 0, screen.y - 1)) * static_cast<size_t>(screen.x) +
                   static_cast<size_t>(std::clamp(x, 0, screen.x - 1))];
    };
    for (size_t k = 0; k < points.size(); ++k) {
      const glm::vec4 clip = clipFromWorld * glm::vec4(points[k].position, 1.0f);
      if (clip.w <= 0.0f) continue;
      const glm::vec2 px = (glm::vec2(clip) / clip.w * 0.5f + 0.5f) * glm::vec2(screen);
      if (!(px.x >= 0.0f && px.y >= 0.0f && px.x < static_cast<float>(screen.x) && px.y < static_cast<float>(screen.y))) continue;
      const glm::vec2 c = px - 0.5f;  // pixel-centre coordinates
      const int x = static_cast<int>(std::floor(c.x)), y = static_cast<int>(std::floor(c.y));
      const float fx = c.x - static_cast<float>(x), fy = c.y - static_cast<float>(y);
      v[k] = (1.0f - fy) * ((1.0f - fx) * at(x, y) + fx * at(x + 1, y)) + fy * ((1.0f - fx) * at(x, y + 1) + fx * at(x + 1, y + 1));
    }
  }

  /// Ends the frame's accumulation (the surfaces become the next frame's), on the frame block of
  /// a light that casts shadows (one that has views); without one nothing was accumulated.
  void endTemporalFrame(const ShadowFrameInputs& in) {
    for (size_t i = 0; i < slots.size(); ++i) {
      if (!slots[i]->light.castsShadow) continue;
      bindBlocks(i);
      bindSurfaces(in.surfaces);
      FrameContext ctx = frameContext(i);
      temporal.endFrame(ctx, *addOns);
      unbindSurfaces();
      return;
    }
  }
};

Shadows::Shadows() {
  PN_CHECK(epoxy_gl_version() >= 45, fmt::format("penumbra::Shadows needs a current OpenGL 4.5 core context (this one is {}.{})",
                                                 epoxy_gl_version() / 10, epoxy_gl_version() % 10));
  mImpl = std::make_unique<Impl>();
  mImpl->projection = makeProjection("uniform");
  mImpl->filter = makeFilter("hard");
  mImpl->ensureSlots(1);  // light 0 exists before the first frame (its debug images are listed)
}

Shadows::~Shadows() = default;

void Shadows::setTechnique(std::unique_ptr<Projection> projection, std::unique_ptr<Filter> filter, const Light* light) {
  PN_CHECK(projection && filter, "setTechnique needs a projection and a filter");
  std::swap(mImpl->projection, projection);
  std::swap(mImpl->filter, filter);
  mImpl->schedule.reset();  // the new technique's maps are drawn anew
  if (light) {
    try {
      mImpl->checkPair(*light);
    } catch (...) {
      std::swap(mImpl->projection, projection);
      std::swap(mImpl->filter, filter);
      throw;
    }
  }
}

void Shadows::setTechnique(std::string_view projectionId, std::string_view filterId,
                           const std::vector<std::pair<std::string, std::string>>& params) {
  std::unique_ptr<Projection> projection = makeProjection(projectionId);
  std::unique_ptr<Filter> filter = makeFilter(filterId);
  for (const auto& [key, value] : params) {
    if (projection->hasParam(key))
      projection->setParam(key, std::string_view(value));
    else if (filter->hasParam(key))
      filter->setParam(key, std::string_view(value));
    else if (mImpl->addOns->hasParam(key))
      mImpl->addOns->setParam(key, std::string_view(value));
    else
      throw usageError(fmt::format("unknown parameter '{}' for projection {} and filter {}", key, projectionId, filterId));
  }
  setTechnique(std::move(projection), std::move(filter));
}

Projection& Shadows::projection() { return *mImpl->projection; }
Filter& Shadows::filter() { return *mImpl->filter; }
Parameterized& Shadows::addOns() { return *mImpl->addOns; }

void Shadows::setCasters(std::span<const CasterMesh> casters, std::span<const Aabb> receiverBounds) {
  Impl& im = *mImpl;
  im.casters.set(casters);
  im.extent.bodies = im.casters.bodies();
  im.staticExtent.bodies = im.casters.bodies(CasterSet::Which::Static);
  im.staticCasters = !im.staticExtent.bodies.empty();
  for (const Aabb& b : receiverBounds)
    for (SceneExtent* e : {&im.extent, &im.staticExtent}) e->bodies.push_back({b, false});
}

void Shadows::setCasterGeometry(const Scene* scene) { mImpl->cpuScene = scene; }

namespace {
void checkMapUpdates(const MapUpdates& updates, const std::string& which) {
  if (updates.policy == MapUpdates::Policy::Budget && updates.budgetMaps < 1)
    throw usageError(fmt::format("{}MapUpdates::budgetMaps = {}: a budget updates at least 1 map per frame", which, updates.budgetMaps));
}
}  // namespace

void Shadows::setMapUpdates(const MapUpdates& updates) {
  checkMapUpdates(updates, "");
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
  if (in.lights.empty()) throw usageError("Shadows::render: no light (ShadowFrameInputs::lights is empty)");
  if (in.lights.size() > kMaxShadowedLights)
    throw usageError(fmt::format("Shadows::render: {} lights given; at most {}", in.lights.size(), kMaxShadowedLights));
  const ShadowSurfaces& s = in.surfaces;
  if (s.width < 1 || s.height < 1 || s.width > kMaxSurfaceSide || s.height > kMaxSurfaceSide)
    throw usageError(fmt::format("image size {}x{} is outside 1..{}", s.width, s.height, kMaxSurfaceSide));
  if (s.normal == 0 || (s.depth == 0 && s.position == 0))
    throw usageError("ShadowSurfaces needs a normal texture and a depth (or position) texture");
  checkTexture(s.depth, "depth");
  checkTexture(s.normal, "normal");
  checkTexture(s.position, "position");
  const int maxSize = gl::maxTextureSize();
  const auto checkMapSize = [maxSize](int size, const std::string& what) {
    if (size < 1 || size > maxSize)
      throw Error(fmt::format("{}shadow map size {} is outside 1..{} (the driver's maximum texture size)", what, size, maxSize));
  };
  checkMapSize(in.mapSize, "");
  const bool several = in.lights.size() > 1;
  for (size_t i = 0; i < in.lights.size(); ++i) {
    const Light& l = in.lights[i];
    const std::string which = several ? fmt::format("light {}", i) : "";
    if (l.castsShadow) im.checkPair(l, which);
    if (l.shadow.mapSize > 0) checkMapSize(l.shadow.mapSize, which.empty() ? "" : which + ": ");
    if (l.shadow.updates) checkMapUpdates(*l.shadow.updates, fmt::format("light {}: shadow.updates: ", i));
  }
  // An error the caller's own calls left is theirs: say so, rather than blame a pass below.
  gl::throwIfGlError("the caller's GL calls before Shadows::render");

  const StateScope scope(in.restore);
  core::setPassDefaults();
  im.ensureSlots(in.lights.size());
  im.screen = {s.width, s.height};
  im.surface = s.position != 0 ? SurfaceSource::Position : SurfaceSource::Depth;
  im.ensureVisibility(im.screen, static_cast<int>(in.lights.size()));

  // The budget: each shadowed light's share by its importance on screen, counting the maps its
  // projection makes for it (cascades, cube faces) at the size it asks for.
  std::vector<core::BudgetRequest> requests;
  const Aabb bounds = im.extent.bounds();
  for (size_t i = 0; i < in.lights.size(); ++i) {
    const Light& l = in.lights[i];
    const int requested = l.shadow.mapSize > 0 ? l.shadow.mapSize : in.mapSize;
    int views = 0;
    if (l.castsShadow && in.mapBudgetTexels > 0) views = im.viewCount(i, l, in.camera, requested);
    requests.push_back({requested, views, core::lightImportance(l, in.camera.fit, in.camera.aspect, bounds)});
  }
  const std::vector<int> sizes = core::allocateMapSizes(requests, in.mapBudgetTexels);
  im.reports.assign(in.lights.size(), {});
  const gl::MemoryAccount::Charge charge(im.techniqueMemory);
  im.clipFromWorld = in.camera.clipFromView * in.camera.viewFromWorld;
  // A pixel's width per metre of distance: 2·tan(fovY/2) / height, from the projection's y scale.
  im.samplingFrame = im.temporal.beginFrame(*im.addOns, {.screen = im.screen,
                                                         .layers = static_cast<int>(in.lights.size()),
                                                         .techniqueKey = im.techniqueKey(),
                                                         .cut = in.cameraCut,
                                                         .clipFromWorld = im.clipFromWorld,
                                                         .pixelFootprintPerM = 2.0f / (in.camera.clipFromView[1][1] * static_cast<float>(s.height))});
  std::vector<core::MapUpdateSchedule::LightPolicy> policies;
  for (const Light& l : in.lights) policies.push_back({l.castsShadow, im.updatesOf(l), l.shadow.updates.has_value()});
  im.schedule.beginFrame(policies);
  im.timer.beginFrame();
  for (size_t i = 0; i < in.lights.size(); ++i) {
    LightSlot& slot = *im.slots[i];
    slot.light = in.lights[i];
    slot.mapSize = sizes[i];
    im.renderLight(i, in);
    const bool shadows = slot.light.castsShadow;
    im.reports[i] = {requests[i].requestedMapSize, sizes[i], shadows ? static_cast<int>(slot.frusta.views.size()) : 0,
                     requests[i].importance, im.updatesOf(slot.light),
                     shadows ? static_cast<int>(std::count(slot.keptViews.begin(), slot.keptViews.end(), uint8_t{1})) : 0,
                     shadows ? im.schedule.staleness(i) : 0};
  }
  if (TemporalAccumulation::enabled(*im.addOns)) {
    ScopedPass pass(im.timer, "temporal");
    im.endTemporalFrame(in);
  }
  ++im.frameIndex;
  im.timings = im.timer.endFrame();
}

size_t Shadows::lightCount() const { return mImpl->slots.size(); }

uint32_t Shadows::visibilityTexture(size_t light) const {
  PN_CHECK(light < mImpl->slots.size(), fmt::format("visibilityTexture({}): the last frame had {} lights", light, mImpl->slots.size()));
  return mImpl->slots[light]->visibilityView.id();
}

uint32_t Shadows::visibilityArrayTexture() const { return mImpl->visibility.id(); }

std::vector<float> Shadows::readVisibility(size_t light) const {
  PN_CHECK(light < mImpl->slots.size(), fmt::format("readVisibility({}): the last frame had {} lights", light, mImpl->slots.size()));
  const gl::Texture& t = mImpl->slots[light]->visibilityView;
  std::vector<float> v(static_cast<size_t>(t.width()) * static_cast<size_t>(t.height()));
  if (t) t.read(GL_RED, GL_FLOAT, v.data(), v.size() * sizeof(float));
  return v;
}

std::vector<float> Shadows::visibilityAt(std::span<const SurfaceSample> points, size_t light) {
  Impl& im = *mImpl;
  PN_CHECK(light < im.slots.size() && im.slots[light]->mapSize > 0, "visibilityAt() before render()");
  if (points.empty()) return {};
  const glm::ivec4 header(static_cast<int>(points.size()), PN_POINTS_GRID_WIDTH, 0, 0);
  std::vector<gpu::VisibilityPointGpu> data(points.size());
  for (size_t i = 0; i < points.size(); ++i)
    data[i] = {glm::vec4(points[i].position, 1.0f), glm::vec4(points[i].geoNormal, 0.0f), glm::ivec4(points[i].pixel, 0, 0)};
  gl::Buffer in("visibility points", sizeof(header) + data.size() * sizeof(gpu::VisibilityPointGpu));
  in.upload(&header, sizeof(header));
  in.upload(data.data(), data.size() * sizeof(gpu::VisibilityPointGpu), sizeof(header));
  gl::Buffer out("visibility at points", points.size() * sizeof(float));
  const StateScope scope(RestoreState::All);
  core::setPassDefaults();
  im.bindBlocks(light);
  FrameContext ctx = im.frameContext(light);
  ctx.setPoints(&in, &out, static_cast<int>(points.size()));
  const gl::MemoryAccount::Charge charge(im.techniqueMemory);
  im.timer.beginFrame();  // a filter may time sub-passes; these times are not kept
  im.filterOf(light).computeVisibility(ctx);
  im.timer.endFrame();
  gl::throwIfGlError("the visibility pass at points");
  std::vector<float> v(points.size());
  out.download(v.data(), v.size() * sizeof(float));
  if (TemporalAccumulation::enabled(*im.addOns) && im.temporal.historyFrames() > 0) im.accumulatedAt(points, light, v);
  return v;
}

void Shadows::bindFrameBlocks(size_t light) const {
  PN_CHECK(light < mImpl->slots.size(), fmt::format("bindFrameBlocks({}): the last frame had {} lights", light, mImpl->slots.size()));
  mImpl->bindBlocks(light);
}

ShaderLibrary& Shadows::shaders() { return mImpl->shaders; }

const LightFrusta& Shadows::frusta(size_t light) const {
  PN_CHECK(light < mImpl->slots.size(), fmt::format("frusta({}): the last frame had {} lights", light, mImpl->slots.size()));
  return mImpl->slots[light]->frusta;
}
const std::vector<LightShadowReport>& Shadows::lightReports() const { return mImpl->reports; }
const PassTimings& Shadows::timings() const { return mImpl->timings; }
std::size_t Shadows::techniqueMemoryBytes() const { return static_cast<std::size_t>(mImpl->techniqueMemory.bytes()); }

std::vector<DebugImage> Shadows::debugImages(size_t light) const {
  PN_CHECK(light < mImpl->slots.size(), fmt::format("debugImages({}): the last frame had {} lights", light, mImpl->slots.size()));
  std::vector<DebugImage> out = {{"visibility", &mImpl->slots[light]->visibilityView, "V: 1 = lit, 0 = in shadow"}};
  for (const DebugImage& d : mImpl->filterOf(light).debugImages()) out.push_back(d);
  return out;
}

}  // namespace penumbra
