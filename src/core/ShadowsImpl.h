#pragma once
// What a Shadows object holds between calls (penumbra/Shadows.h): the shader library and the
// GL objects of its passes, the casters and what the views are fitted to, the technique, each
// light's state, the frame's reports. Its frame is run by Shadows.cpp; ShadowsDebug.cpp reads it
// for the tools.
#include <penumbra/Shadows.h>
#include <penumbra/ShadowsDebug.h>

#include "core/FrameBlocks.h"
#include "core/GlState.h"
#include "core/LightState.h"
#include "core/MapUpdateSchedule.h"
#include "core/ShadowBudget.h"
#include "core/SurfaceBounds.h"
#include "frame/CasterSet.h"
#include "frame/FrameContext.h"
#include "frame/PassTimer.h"
#include "frame/PixelBoundsReducer.h"
#include "gl/Debug.h"
#include "gl/Objects.h"
#include "shader/ShaderLibrary.h"
#include "techniques/contact/ContactShadows.h"
#include "techniques/temporal/TemporalAccumulation.h"
#include "techniques/translucent/TranslucentShadows.h"
#include "shared/Bindings.h"

#include <penumbra/Error.h>

#include <fmt/format.h>

#include <algorithm>
#include <map>
#include <optional>

namespace penumbra {
namespace core {

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

inline void checkTexture(uint32_t name, const char* what) {
  if (name != 0 && !glIsTexture(name)) throw usageError(fmt::format("ShadowSurfaces::{} = {} is not a GL texture", what, name));
}

inline void checkMapUpdates(const MapUpdates& updates, const std::string& which) {
  if (updates.policy == MapUpdates::Policy::Budget && updates.budgetMaps < 1)
    throw usageError(fmt::format("{}MapUpdates::budgetMaps = {}: a budget updates at least 1 map per frame", which, updates.budgetMaps));
}

}  // namespace core

struct Shadows::Impl {
  ShaderLibrary shaders;
  PassTimer timer{gl::isSoftwareRenderer(gl::glString(GL_RENDERER))};
  gl::Buffer filterBlock{"filter block", core::kFilterBlockBytes};
  // Engine textures are read through this sampler, whatever their own sampling state.
  gl::Sampler surfaceSampler{"surface sampler", {GL_NEAREST, GL_NEAREST, GL_CLAMP_TO_EDGE, false}};
  gl::Texture visibility;                ///< 2D array, one layer per light: R32F, or RGBA32F (colour)
  bool colour = false;                   ///< this frame's visibility holds RGB (tinted by translucent casters)
  std::vector<gl::Texture> layerViews;   ///< per layer: the layer as a 2D texture
  std::vector<ScreenTarget> layerTargets;  ///< per layer: the visibility pass's target
  CasterSet casters;
  SceneExtent extent;        ///< every caster and the given receivers
  SceneExtent staticExtent;  ///< the static casters and the given receivers
  bool staticCasters = false;
  bool receiversComplete = false;
  core::SurfaceBounds surfaceBounds;
  std::optional<std::vector<CasterGeometry>> geometry;  ///< none until setCasterGeometry
  Technique technique;
  // What the lights' filters and add-ons allocate during their passes; a light's storage leaves
  // the count when its state (or its filter) is destroyed.
  gl::MemoryAccount techniqueMemory;
  TemporalAccumulation temporal;
  int samplingFrame = 0;               // this frame's (TemporalAccumulation::beginFrame)
  glm::mat4 clipFromWorld{1.0f};       // the last frame's camera
  std::vector<std::unique_ptr<core::LightState>> states;  // the last frame's lights, in order
  std::vector<LightShadowReport> reports;
  PassTimings timings;
  glm::ivec2 screen{0};
  SurfaceFacts surface;
  int frameIndex = 0;
  MapUpdates mapUpdates;
  MapCacheState mapCache;
  core::MapUpdateSchedule schedule;

  /// The light's own map updates, or the Shadows' policy.
  const MapUpdates& updatesOf(const Light& l) const { return l.shadow.updates ? *l.shadow.updates : mapUpdates; }

  /// What the light's views are fitted to this frame: every body (and the measured surfaces),
  /// or with cached maps the static casters and the receivers (a moving dynamic caster then
  /// leaves the views, and so the maps' static layers, where they are), unless no caster is
  /// static.
  const SceneExtent& fitExtent(const Light& l, const SceneExtent& all, const SceneExtent& still) const {
    return updatesOf(l).cached() && staticCasters ? still : all;
  }

  core::LightState& stateAt(size_t light, const char* what) const {
    PN_CHECK(light < states.size(), fmt::format("{}({}): the last frame had {} lights", what, light, states.size()));
    return *states[light];
  }

  /// Whether the light's V is tinted by the translucent casters: its filter or the add-on asks
  /// for it and there are some.
  bool tints(const core::LightState& s) const { return filterTints(s) || addOnTints(s); }
  /// The light's filter shadows through the translucent casters itself (msm.translucent).
  bool filterTints(const core::LightState& s) const {
    return casters.hasTranslucent() && s.filter && s.filter->shadowsThroughTranslucent(s.technique.filterValues());
  }
  /// The translucent add-on tints the light's V (translucent.*; never beside a filter that
  /// tints itself: Technique::problemWith refuses the pair).
  bool addOnTints(const core::LightState& s) const {
    const Parameterized& addOns = s.technique.addOnValues();
    return casters.hasTranslucent() && TranslucentShadows::enabled(addOns) && !stochastic(addOns) && !filterTints(s);
  }
  /// The add-on's stochastic method: on, with translucent.method=stochastic (its choice 1).
  static bool stochastic(const Parameterized& addOns) {
    constexpr int kStochastic = 1;
    return TranslucentShadows::enabled(addOns) && addOns.paramInt("translucent.method") == kStochastic;
  }
  /// The filter's maps dither the translucent casters by their opacity (FrameResources::
  /// ditherTranslucent): the add-on's stochastic method, where some caster is translucent.
  bool dithers(const core::LightState& s) const {
    return casters.hasTranslucent() && stochastic(s.technique.addOnValues()) && !filterTints(s);
  }

  FrameContext frameContext(core::LightState& s) {
    std::optional<std::span<const CasterGeometry>> cpu;
    if (geometry) cpu = std::span<const CasterGeometry>(*geometry);
    return FrameContext({s.light, s.technique.filterValues(), cpu, s.frusta, s.mapSize, screen, surface, shaders, casters,
                         filterBlock, timer, &visibility, static_cast<int>(s.layer),
                         updatesOf(s.light).cached() ? &mapCache : nullptr, s.keptViews, &layerTargets[s.layer], s.pages.get(),
                         tints(s) ? CasterSet::Translucent::Skip : CasterSet::Translucent::AsOpaque, colour, dithers(s)});
  }
  static void bindBlocks(const core::LightState& s) {
    s.frameBlock.bindBase(GL_UNIFORM_BUFFER, PN_UBO_FRAME);
    s.shadowBlock.bindBase(GL_UNIFORM_BUFFER, PN_UBO_SHADOW);
    if (s.pages) s.pages->bind();
  }

  /// Each light's technique this frame, checked against the light: the one place a light's
  /// settings meet the technique. Usage Errors name the light (when there are several) and the
  /// API field.
  std::vector<Technique> lightTechniques(std::span<const Light> lights) const {
    std::vector<Technique> out;
    const bool several = lights.size() > 1;
    std::map<uint64_t, size_t> ids;
    for (size_t i = 0; i < lights.size(); ++i) {
      const Light& l = lights[i];
      const std::string which = several ? fmt::format("light {}", i) : "";
      if (l.id != 0 && !ids.emplace(l.id, i).second)
        throw usageError(fmt::format("ShadowFrameInputs::lights: lights {} and {} have the same Light::id {}", ids[l.id], i, l.id));
      out.push_back(technique.forLight(l.shadow, which));
      if (l.castsShadow)
        if (const std::string why = out.back().problemWith(l); !why.empty())
          throw usageError(which.empty() ? why : fmt::format("{}: {}", which, why));
      if (l.shadow.updates) core::checkMapUpdates(*l.shadow.updates, fmt::format("light {}: LightShadowSettings::updates: ", i));
      const int maxSize = gl::maxTextureSize();
      if (out.back().mapSize() > maxSize)
        throw Error(fmt::format("{}shadow map size {} is outside 1..{} (the driver's maximum texture size)",
                                which.empty() ? "" : which + ": ", out.back().mapSize(), maxSize));
    }
    return out;
  }

  /// This frame's states, in the lights' order: each light's own (found by its key), made for
  /// a light seen for the first time; the states of lights that left are destroyed.
  void takeStates(std::span<const Light> lights, const std::vector<Technique>& techniques) {
    std::vector<std::unique_ptr<core::LightState>> next;
    for (size_t i = 0; i < lights.size(); ++i) {
      const core::LightKey key = core::LightKey::of(lights[i], i);
      auto it = std::find_if(states.begin(), states.end(), [&](const auto& s) { return s && s->key == key; });
      std::unique_ptr<core::LightState> s = it != states.end() ? std::move(*it) : std::make_unique<core::LightState>(key);
      const bool changed = !(s->technique == techniques[i]) || !s->filter;
      if (s->adopt(techniques[i]) || changed) schedule.forget(key);  // its maps are drawn anew
      s->light = lights[i];
      s->layer = i;
      if (!TemporalAccumulation::enabled(s->technique.addOnValues())) s->history = {};
      if (!TranslucentShadows::enabled(s->technique.addOnValues()) || stochastic(s->technique.addOnValues()))
        s->translucent.release();
      next.push_back(std::move(s));
    }
    states = std::move(next);
  }

  /// The visibility array (one layer per light) and each layer's view and target: one channel,
  /// or RGB when some light's V is tinted by translucent casters (`colour`).
  void ensureVisibility(glm::ivec2 size, int layers) {
    const GLenum format = static_cast<GLenum>(colour ? GL_RGBA32F : GL_R32F);
    if (visibility && visibility.width() == size.x && visibility.height() == size.y && visibility.layers() == layers &&
        visibility.desc().format == format)
      return;
    layerViews.clear();
    layerTargets.clear();
    visibility = gl::Texture("visibility", {GL_TEXTURE_2D_ARRAY, format, size.x, size.y, layers, 1});
    visibility.setSampling(GL_NEAREST, GL_NEAREST);
    for (int i = 0; i < layers; ++i) {
      layerViews.push_back(gl::Texture::layerView(fmt::format("visibility of light {}", i), visibility, i));
      layerViews.back().setSampling(GL_NEAREST, GL_NEAREST);
      layerTargets.emplace_back(fmt::format("visibility pass of light {}", i), visibility, i);
    }
  }

  void renderLight(core::LightState& s, const ShadowFrameInputs& in, const SceneExtent& all, const SceneExtent& still) {
    const bool accumulates = TemporalAccumulation::enabled(s.technique.addOnValues());
    gpu::FrameUniforms frame = core::frameUniforms(in.camera, s.light, screen, frameIndex, all.bounds().radius());
    frame.screen.w = accumulates ? samplingFrame : 0;
    s.frameBlock.upload(frame);
    if (!s.light.castsShadow) {  // lit wherever the light reaches: V = 1 in its layer
      const glm::vec4 one(1.0f);
      glClearTexSubImage(visibility.id(), 0, 0, 0, static_cast<GLint>(s.layer), screen.x, screen.y, 1, colour ? GL_RGBA : GL_RED,
                         GL_FLOAT, &one.x);
      return;
    }
    // A projection fitted to the pixels (sdsm) measures them here, on the GPU, before its views
    // exist; the others ask nothing and no pass runs.
    PixelBoundsReducer pixels(shaders, surfaceDefines(surface), screen, in.camera.fit, timer,
                              [&] {
                                s.frameBlock.bindBase(GL_UNIFORM_BUFFER, PN_UBO_FRAME);
                                bindSurfaces(in.surfaces);
                              },
                              [] { unbindSurfaces(); });
    // A paged projection's views are virtual maps of its own size, drawn page by page where the
    // pixels need them; its pages keep their own cache (VirtualPages), outside map budgets.
    const std::optional<PageLayout> layout = s.projection->pageLayout();
    if (!layout) s.pages.reset();
    else if (!s.pages) s.pages = std::make_unique<VirtualPages>();
    if (layout) s.mapSize = layout->virtualSize;
    s.frusta = s.projection->computeFrustaFromPixels(in.camera.fit, in.camera.aspect, s.light, fitExtent(s.light, all, still),
                                                     s.mapSize, pixels);
    s.keptViews = layout ? std::vector<uint8_t>{} : schedule.apply(s.key, s.frusta, s.mapSize);
    s.shadowBlock.upload(core::shadowUniforms(s.frusta, s.mapSize));
    bindBlocks(s);
    if (layout) {
      // A pixel's width per metre of distance, 2·tan(fovY/2) / height (orthographic: its width).
      const float pixelWidthPerM = 2.0f / (in.camera.clipFromView[1][1] * static_cast<float>(screen.y));
      // A point light's views are its six cube faces' levels (VirtualProjection).
      const int maps = s.light.type == LightType::Point ? kCubeFaces : 1;
      s.pages->beginFrame(*layout, s.frusta, maps, pixelWidthPerM, updatesOf(s.light).cached());
    }
    FrameContext ctx = frameContext(s);
    if (s.pages) {
      ScopedPass pass(timer, "projection");
      bindSurfaces(in.surfaces);
      s.pages->mark(ctx);
      unbindSurfaces();
      gl::throwIfGlError("the page marking pass");
    }
    const bool tinted = addOnTints(s);
    {
      ScopedPass pass(timer, "shadow");
      s.filter->renderShadowMaps(ctx);
      if (tinted) s.translucent.renderMaps(ctx, s.technique.addOnValues());
    }
    gl::throwIfGlError("the shadow pass");
    {
      ScopedPass pass(timer, "prefilter");
      s.filter->prefilter(ctx);
    }
    gl::throwIfGlError("the prefilter pass");
    bindSurfaces(in.surfaces);
    const Parameterized& addOns = s.technique.addOnValues();
    {
      ScopedPass pass(timer, "visibility");
      s.filter->computeVisibility(ctx);
      if (tinted) s.translucent.apply(ctx, addOns);
    }
    if (ContactShadows::enabled(addOns)) {
      ScopedPass pass(timer, "contact");
      ContactShadows::apply(ctx, addOns);
    }
    if (accumulates) {
      ScopedPass pass(timer, "temporal");
      temporal.apply(ctx, addOns, s.history, core::accumulationKey(s.technique));
    }
    unbindSurfaces();
    gl::throwIfGlError("the visibility pass");
  }

  /// The caller's surfaces where the screen passes read them, through Penumbra's own sampler.
  void bindSurfaces(const ShadowSurfaces& s) {
    glBindTextureUnit(PN_TEX_GBUF_POSITION, surface.source == SurfaceSource::Position ? s.position : s.depth);
    glBindTextureUnit(PN_TEX_GBUF_GEONORMAL, s.normal);
    surfaceSampler.bindUnit(PN_TEX_GBUF_POSITION);
    surfaceSampler.bindUnit(PN_TEX_GBUF_GEONORMAL);
  }
  static void unbindSurfaces() {
    gl::Sampler::unbindUnit(PN_TEX_GBUF_POSITION);
    gl::Sampler::unbindUnit(PN_TEX_GBUF_GEONORMAL);
  }

  /// The visible surfaces' bounds (ShadowReceivers::complete false), on the first light's frame
  /// block (its camera part is every light's).
  Aabb measureSurfaces(const ShadowFrameInputs& in) {
    ScopedPass pass(timer, "receivers");
    gpu::FrameUniforms frame = core::frameUniforms(in.camera, in.lights.front(), screen, frameIndex, extent.bounds().radius());
    states.front()->frameBlock.upload(frame);
    states.front()->frameBlock.bindBase(GL_UNIFORM_BUFFER, PN_UBO_FRAME);
    bindSurfaces(in.surfaces);
    const Aabb box = surfaceBounds.measure(shaders, screen, surfaceDefines(surface));
    unbindSurfaces();
    gl::throwIfGlError("the surface bounds pass");
    return box;
  }

  /// With accumulation on, V at world points as accumulated: the last frame's layer, bilinear
  /// between the four pixel centres around each point's position on screen. Points off screen
  /// keep the V they have.
  void accumulatedAt(std::span<const SurfaceSample> points, size_t light, std::vector<float>& v) const {
    const gl::Texture& layer = layerViews[light];
    std::vector<float> image(static_cast<size_t>(screen.x) * static_cast<size_t>(screen.y));
    if (colour) {  // the channels' mean, as readVisibility
      std::vector<glm::vec4> rgba(image.size());
      {
        const core::PixelTransferScope transfer;
        layer.read(GL_RGBA, GL_FLOAT, rgba.data(), rgba.size() * sizeof(glm::vec4));
      }
      std::transform(rgba.begin(), rgba.end(), image.begin(), [](const glm::vec4& c) { return (c.r + c.g + c.b) / 3.0f; });
    } else {
      const core::PixelTransferScope transfer;
      layer.read(GL_RED, GL_FLOAT, image.data(), image.size() * sizeof(float));
    }
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
    std::vector<TemporalHistory*> histories;
    core::LightState* first = nullptr;
    for (const auto& s : states) {
      if (!TemporalAccumulation::enabled(s->technique.addOnValues())) continue;
      histories.push_back(&s->history);
      if (!first && s->light.castsShadow) first = s.get();
    }
    if (!first) return;
    bindBlocks(*first);
    bindSurfaces(in.surfaces);
    FrameContext ctx = frameContext(*first);
    temporal.endFrame(ctx, first->technique.addOnValues(), histories);
    unbindSurfaces();
  }

  void checkInputs(const ShadowFrameInputs& in) const {
    if (in.lights.empty()) throw usageError("Shadows::render: no light (ShadowFrameInputs::lights is empty)");
    if (in.lights.size() > kMaxShadowedLights)
      throw usageError(fmt::format("Shadows::render: {} lights given; at most {}", in.lights.size(), kMaxShadowedLights));
    const ShadowSurfaces& s = in.surfaces;
    if (s.width < 1 || s.height < 1 || s.width > core::kMaxSurfaceSide || s.height > core::kMaxSurfaceSide)
      throw usageError(fmt::format("ShadowSurfaces::width × height = {}x{} is outside 1..{}", s.width, s.height, core::kMaxSurfaceSide));
    if (s.depth == 0 && s.position == 0)
      throw usageError("ShadowSurfaces::depth and ShadowSurfaces::position are both 0: the surfaces need a depth (or position) texture");
    core::checkTexture(s.depth, "depth");
    core::checkTexture(s.normal, "normal");
    core::checkTexture(s.position, "position");
  }
};

}  // namespace penumbra
