// penumbra/ShadowsDebug.h and core/ShadowsAccess.h: what the tools reach of a Shadows object.
#include <penumbra/ShadowsDebug.h>

#include "core/ShadowsAccess.h"
#include "core/ShadowsImpl.h"
#include "gl/Objects.h"
#include "shared/VisibilityPoints.h"

namespace penumbra {

// ---- what tools reach (penumbra/ShadowsDebug.h, core/ShadowsAccess.h) ------------------------

core::LightState& ShadowsAccess::light(const Shadows& shadows, size_t light, const char* what) {
  return shadows.mImpl->stateAt(light, what);
}

ShaderLibrary& ShadowsAccess::shaders(Shadows& shadows) { return shadows.mImpl->shaders; }

std::vector<float> ShadowsAccess::visibilityAt(Shadows& shadows, std::span<const SurfaceSample> points, size_t light) {
  Shadows::Impl& im = *shadows.mImpl;
  PN_CHECK(light < im.states.size() && im.states[light]->mapSize > 0, "visibilityAt() before render()");
  if (points.empty()) return {};
  core::LightState& st = *im.states[light];
  const glm::ivec4 header(static_cast<int>(points.size()), PN_POINTS_GRID_WIDTH, 0, 0);
  std::vector<gpu::VisibilityPointGpu> data(points.size());
  for (size_t i = 0; i < points.size(); ++i)
    data[i] = {glm::vec4(points[i].position, 1.0f), glm::vec4(points[i].geoNormal, 0.0f), glm::ivec4(points[i].pixel, 0, 0)};
  gl::Buffer in("visibility points", sizeof(header) + data.size() * sizeof(gpu::VisibilityPointGpu));
  in.upload(&header, sizeof(header));
  in.upload(data.data(), data.size() * sizeof(gpu::VisibilityPointGpu), sizeof(header));
  gl::Buffer out("visibility at points", points.size() * sizeof(float));
  const core::StateScope scope(RestoreState::All);
  core::setPassDefaults();
  Shadows::Impl::bindBlocks(st);
  FrameContext ctx = im.frameContext(st);
  ctx.setPoints(&in, &out, static_cast<int>(points.size()));
  const gl::MemoryAccount::Charge charge(im.techniqueMemory);
  im.timer.beginFrame();  // a filter may time sub-passes; these times are not kept
  st.filter->computeVisibility(ctx);
  im.timer.endFrame();
  gl::throwIfGlError("the visibility pass at points");
  std::vector<float> v(points.size());
  out.download(v.data(), v.size() * sizeof(float));
  if (TemporalAccumulation::enabled(st.technique.addOnValues()) && im.temporal.historyFrames() > 0) im.accumulatedAt(points, light, v);
  return v;
}

void ShadowsAccess::bindFrameBlocks(const Shadows& shadows, size_t light) {
  Shadows::Impl::bindBlocks(shadows.mImpl->stateAt(light, "bindFrameBlocks"));
}

ShaderDefines ShadowsAccess::viewDefines(const Shadows& shadows, size_t light) {
  const Shadows::Impl& im = *shadows.mImpl;
  if (light >= im.states.size() || !im.states[light]->pages) return {};
  return im.states[light]->pages->defines();
}

const VirtualPages* ShadowsAccess::pages(const Shadows& shadows, size_t light) {
  return ShadowsAccess::light(shadows, light, "pages").pages.get();
}

std::vector<DebugImage> ShadowsAccess::debugImages(const Shadows& shadows, size_t light) {
  const Shadows::Impl& im = *shadows.mImpl;
  // Before a frame has the light: its visibility, without a texture yet.
  std::vector<DebugImage> out = {{"visibility", light < im.layerViews.size() ? &im.layerViews[light] : nullptr,
                                  im.colour ? "V per colour channel (RGB, tinted by translucent casters): 1 = lit, 0 = in shadow"
                                            : "V: 1 = lit, 0 = in shadow"}};
  if (light < im.states.size()) {
    for (const DebugImage& d : im.states[light]->filter->debugImages()) out.push_back(d);
    for (const DebugImage& d : im.states[light]->translucent.debugImages()) out.push_back(d);
  }
  return out;
}

// ---- penumbra/ShadowsDebug.h --------------------------------------------------------------------

const LightFrusta& frusta(const Shadows& shadows, size_t light) { return ShadowsAccess::light(shadows, light, "frusta").frusta; }

std::vector<DebugTexture> debugTextures(const Shadows& shadows, size_t light) {
  std::vector<DebugTexture> out;
  for (const DebugImage& d : ShadowsAccess::debugImages(shadows, light)) {
    if (!d.texture || !*d.texture) continue;
    const gl::TextureDesc& t = d.texture->desc();
    out.push_back({d.name, d.texture->id(), t.target, t.width, t.height, t.target == GL_TEXTURE_2D ? 1 : t.depth, d.meaning});
  }
  return out;
}

std::vector<float> visibilityAt(Shadows& shadows, std::span<const SurfaceSample> points, size_t light) {
  return ShadowsAccess::visibilityAt(shadows, points, light);
}

void bindFrameBlocks(const Shadows& shadows, size_t light) { ShadowsAccess::bindFrameBlocks(shadows, light); }

void setShaderSourceTree(Shadows& shadows, const std::filesystem::path& root) { ShadowsAccess::shaders(shadows).setSourceTree(root); }

std::vector<std::string> reloadShaders(Shadows& shadows) { return ShadowsAccess::shaders(shadows).reloadAll(); }

std::vector<OneOffCost> oneOffCosts(const Shadows& shadows, size_t light) {
  return ShadowsAccess::light(shadows, light, "oneOffCosts").filter->oneOffCosts();
}

}  // namespace penumbra
