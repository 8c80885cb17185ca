// The engine-facing core (penumbra/Shadows.h): projection → shadow pass → prefilter →
// visibility, against the caller's camera, surfaces and casters. No technique-specific branch
// lives here: the Projection and the Filter do that work.
#include <penumbra/Error.h>
#include <penumbra/Registry.h>
#include <penumbra/Shadows.h>

#include "core/FrameBlocks.h"
#include "core/GlState.h"
#include "frame/CasterSet.h"
#include "frame/FrameContext.h"
#include "frame/PassTimer.h"
#include "gl/Debug.h"
#include "gl/Objects.h"
#include "shader/ShaderLibrary.h"
#include "shadows/contact/ContactShadows.h"
#include "shared/Bindings.h"
#include "shared/VisibilityPoints.h"

#include <fmt/format.h>

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

void checkTexture(uint32_t name, const char* what) {
  if (name != 0 && !glIsTexture(name)) throw usageError(fmt::format("ShadowSurfaces::{} = {} is not a GL texture", what, name));
}

}  // namespace

struct Shadows::Impl {
  ShaderLibrary shaders;
  PassTimer timer{gl::isSoftwareRenderer(gl::glString(GL_RENDERER))};
  gl::Buffer frameBlock{"frame block", sizeof(gpu::FrameUniforms)};
  gl::Buffer shadowBlock{"shadow block", sizeof(gpu::ShadowUniforms)};
  gl::Buffer filterBlock{"filter block", kFilterBlockBytes};
  // Engine textures are read through this sampler, whatever their own sampling state.
  gl::Sampler surfaceSampler{"surface sampler", {GL_NEAREST, GL_NEAREST, GL_CLAMP_TO_EDGE, false}};
  gl::Texture visibility;
  CasterSet casters;
  SceneExtent extent;
  const Scene* cpuScene = nullptr;
  std::unique_ptr<Projection> projection;
  std::unique_ptr<Filter> filter;
  // What the filter allocates during its passes; a replaced filter's storage leaves the count
  // when it is destroyed.
  gl::MemoryAccount techniqueMemory;
  ContactShadows contact;
  LightFrusta frusta;
  PassTimings timings;
  // The last frame's, for visibilityAt and bindFrameBlocks.
  Light light;
  int mapSize = 0;
  glm::ivec2 screen{0};
  SurfaceSource surface = SurfaceSource::Position;
  int frameIndex = 0;

  FrameContext frameContext() {
    return FrameContext({light, cpuScene, frusta, mapSize, screen, surface, shaders, casters, filterBlock, timer, &visibility});
  }
  void bindBlocks() const {
    frameBlock.bindBase(GL_UNIFORM_BUFFER, PN_UBO_FRAME);
    shadowBlock.bindBase(GL_UNIFORM_BUFFER, PN_UBO_SHADOW);
  }
  void checkPair(const Light& l) const {
    if (const std::string why = projection->incompatibility(l); !why.empty())
      throw usageError(fmt::format("--projection {} is not supported for this light: {}", projection->id(), why));
    const std::string why = filter->incompatibility(projection->id(), l);
    if (!why.empty())
      throw usageError(fmt::format("--filter {} with --projection {} is not supported: {}", filter->id(), projection->id(), why));
  }
};

Shadows::Shadows() {
  PN_CHECK(epoxy_gl_version() >= 45, fmt::format("penumbra::Shadows needs a current OpenGL 4.5 core context (this one is {}.{})",
                                                 epoxy_gl_version() / 10, epoxy_gl_version() % 10));
  mImpl = std::make_unique<Impl>();
  mImpl->projection = makeProjection("uniform");
  mImpl->filter = makeFilter("hard");
}

Shadows::~Shadows() = default;

void Shadows::setTechnique(std::unique_ptr<Projection> projection, std::unique_ptr<Filter> filter, const Light* light) {
  PN_CHECK(projection && filter, "setTechnique needs a projection and a filter");
  std::swap(mImpl->projection, projection);
  std::swap(mImpl->filter, filter);
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
    else if (mImpl->contact.hasParam(key))
      mImpl->contact.setParam(key, std::string_view(value));
    else
      throw usageError(fmt::format("unknown parameter '{}' for projection {} and filter {}", key, projectionId, filterId));
  }
  setTechnique(std::move(projection), std::move(filter));
}

Projection& Shadows::projection() { return *mImpl->projection; }
Filter& Shadows::filter() { return *mImpl->filter; }
Parameterized& Shadows::contactShadows() { return mImpl->contact; }

void Shadows::setCasters(std::span<const CasterMesh> casters, std::span<const Aabb> receiverBounds) {
  mImpl->casters.set(casters);
  mImpl->extent.bodies = mImpl->casters.bodies();
  for (const Aabb& b : receiverBounds) mImpl->extent.bodies.push_back({b, false});
}

void Shadows::setCasterGeometry(const Scene* scene) { mImpl->cpuScene = scene; }

void Shadows::render(const ShadowFrameInputs& in) {
  Impl& im = *mImpl;
  if (in.lights.empty()) throw usageError("Shadows::render: no light (ShadowFrameInputs::lights is empty)");
  if (in.lights.size() > 1)
    throw usageError(fmt::format("Shadows::render: {} lights given; one Shadows object shadows one light", in.lights.size()));
  const ShadowSurfaces& s = in.surfaces;
  if (s.width < 1 || s.height < 1 || s.width > kMaxSurfaceSide || s.height > kMaxSurfaceSide)
    throw usageError(fmt::format("image size {}x{} is outside 1..{}", s.width, s.height, kMaxSurfaceSide));
  if (s.normal == 0 || (s.depth == 0 && s.position == 0))
    throw usageError("ShadowSurfaces needs a normal texture and a depth (or position) texture");
  checkTexture(s.depth, "depth");
  checkTexture(s.normal, "normal");
  checkTexture(s.position, "position");
  const int maxSize = gl::maxTextureSize();
  if (in.mapSize < 1 || in.mapSize > maxSize)
    throw Error(fmt::format("shadow map size {} is outside 1..{} (the driver's maximum texture size)", in.mapSize, maxSize));
  const Light& light = in.lights.front();
  im.checkPair(light);
  // An error the caller's own calls left is theirs: say so, rather than blame a pass below.
  gl::throwIfGlError("the caller's GL calls before Shadows::render");

  const StateScope scope(in.restore);
  core::setPassDefaults();
  im.light = light;
  im.mapSize = in.mapSize;
  im.screen = {s.width, s.height};
  im.surface = s.position != 0 ? SurfaceSource::Position : SurfaceSource::Depth;
  if (im.visibility.width() != s.width || im.visibility.height() != s.height || !im.visibility) {
    im.visibility = gl::Texture("visibility", {GL_TEXTURE_2D, GL_R32F, s.width, s.height, 1, 1});
    im.visibility.setSampling(GL_NEAREST, GL_NEAREST);
  }
  im.frusta = im.projection->computeFrusta(in.camera.fit, in.camera.aspect, light, im.extent, in.mapSize);
  im.frameBlock.upload(core::frameUniforms(in.camera, light, im.screen, im.frameIndex++, im.extent.bounds().radius()));
  im.shadowBlock.upload(core::shadowUniforms(im.frusta, in.mapSize));
  im.bindBlocks();

  FrameContext ctx = im.frameContext();
  const gl::MemoryAccount::Charge charge(im.techniqueMemory);
  im.timer.beginFrame();
  {
    ScopedPass pass(im.timer, "shadow");
    im.filter->renderShadowMaps(ctx);
  }
  gl::throwIfGlError("the shadow pass");
  {
    ScopedPass pass(im.timer, "prefilter");
    im.filter->prefilter(ctx);
  }
  gl::throwIfGlError("the prefilter pass");
  glBindTextureUnit(PN_TEX_GBUF_POSITION, im.surface == SurfaceSource::Position ? s.position : s.depth);
  glBindTextureUnit(PN_TEX_GBUF_GEONORMAL, s.normal);
  im.surfaceSampler.bindUnit(PN_TEX_GBUF_POSITION);
  im.surfaceSampler.bindUnit(PN_TEX_GBUF_GEONORMAL);
  {
    ScopedPass pass(im.timer, "visibility");
    im.filter->computeVisibility(ctx);
  }
  if (im.contact.enabled()) {
    ScopedPass pass(im.timer, "contact");
    im.contact.apply(ctx);
  }
  gl::Sampler::unbindUnit(PN_TEX_GBUF_POSITION);
  gl::Sampler::unbindUnit(PN_TEX_GBUF_GEONORMAL);
  gl::throwIfGlError("the visibility pass");
  im.timings = im.timer.endFrame();
}

uint32_t Shadows::visibilityTexture(size_t light) const {
  PN_CHECK(light == 0, fmt::format("visibilityTexture({}): one light is shadowed", light));
  return mImpl->visibility.id();
}

std::vector<float> Shadows::readVisibility(size_t light) const {
  PN_CHECK(light == 0, fmt::format("readVisibility({}): one light is shadowed", light));
  const gl::Texture& t = mImpl->visibility;
  std::vector<float> v(static_cast<size_t>(t.width()) * static_cast<size_t>(t.height()));
  if (t) t.read(GL_RED, GL_FLOAT, v.data(), v.size() * sizeof(float));
  return v;
}

std::vector<float> Shadows::visibilityAt(std::span<const SurfaceSample> points) {
  Impl& im = *mImpl;
  PN_CHECK(im.mapSize > 0, "visibilityAt() before render()");
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
  im.bindBlocks();
  FrameContext ctx = im.frameContext();
  ctx.setPoints(&in, &out, static_cast<int>(points.size()));
  const gl::MemoryAccount::Charge charge(im.techniqueMemory);
  im.timer.beginFrame();  // a filter may time sub-passes; these times are not kept
  im.filter->computeVisibility(ctx);
  im.timer.endFrame();
  gl::throwIfGlError("the visibility pass at points");
  std::vector<float> v(points.size());
  out.download(v.data(), v.size() * sizeof(float));
  return v;
}

void Shadows::bindFrameBlocks() const { mImpl->bindBlocks(); }

ShaderLibrary& Shadows::shaders() { return mImpl->shaders; }

const LightFrusta& Shadows::frusta() const { return mImpl->frusta; }
const PassTimings& Shadows::timings() const { return mImpl->timings; }
std::size_t Shadows::techniqueMemoryBytes() const { return static_cast<std::size_t>(mImpl->techniqueMemory.bytes()); }

std::vector<DebugImage> Shadows::debugImages() const {
  std::vector<DebugImage> out = {{"visibility", &mImpl->visibility, "V: 1 = lit, 0 = in shadow"}};
  for (const DebugImage& d : mImpl->filter->debugImages()) out.push_back(d);
  return out;
}

}  // namespace penumbra
