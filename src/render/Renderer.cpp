// The frame: projection → shadow pass → prefilter → G-buffer → visibility → lit.
// No technique-specific branch lives here: the Projection and the Filter do that work.
#include <penumbra/Renderer.h>

#include "gl/Context.h"
#include "gl/Objects.h"
#include "render/FrameContext.h"
#include "render/GpuScene.h"
#include "render/PassTimer.h"
#include "shader/ShaderLibrary.h"
#include "shared/Bindings.h"
#include "shared/Frame.h"
#include "shared/Shadow.h"
#include "shared/VisibilityPoints.h"

#include <penumbra/Error.h>
#include <penumbra/ImageIO.h>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

namespace penumbra {

namespace {
constexpr size_t kFilterBlockBytes = 4096;  // room for any filter's uniform block
constexpr int kMaxScreenSide = 16384;
}  // namespace

struct Renderer::Impl {
  Scene scene;
  std::unique_ptr<GpuScene> gpuScene;
  PassTimer timer;
  gl::Buffer frameBlock{"frame block", sizeof(gpu::FrameUniforms)};
  gl::Buffer shadowBlock{"shadow block", sizeof(gpu::ShadowUniforms)};
  gl::Buffer filterBlock{"filter block", kFilterBlockBytes};
  // Screen targets
  glm::ivec2 size{0};
  gl::Texture position, normal, geoNormal, albedo, depth, visibility, color;
  gl::Framebuffer gbuffer;
  int frameIndex = 0;
  int mapSize = 0;                   // of the last frame
  int debugView = PN_VIEW_SHADED;    // of the last frame

  explicit Impl(bool cpuClock) : timer(cpuClock) {}

  void ensureScreen(glm::ivec2 s) {
    if (s == size) return;
    PN_CHECK(s.x > 0 && s.y > 0 && s.x <= kMaxScreenSide && s.y <= kMaxScreenSide,
             fmt::format("image size {}x{} is outside 1..{}", s.x, s.y, kMaxScreenSide));
    auto make = [&](const char* label, GLenum format) {
      gl::Texture t(label, {GL_TEXTURE_2D, format, s.x, s.y, 1, 1});
      t.setSampling(GL_NEAREST, GL_NEAREST);
      return t;
    };
    position = make("gbuffer position", GL_RGBA32F);
    normal = make("gbuffer normal", GL_RGBA16F);
    geoNormal = make("gbuffer geometric normal", GL_RGBA16F);
    albedo = make("gbuffer albedo", GL_RGBA8);
    depth = make("gbuffer depth", GL_DEPTH_COMPONENT32F);
    visibility = make("visibility", GL_R32F);
    color = make("color", GL_RGBA8);
    gbuffer = gl::Framebuffer("gbuffer");
    gbuffer.attach(GL_COLOR_ATTACHMENT0, position);
    gbuffer.attach(GL_COLOR_ATTACHMENT1, normal);
    gbuffer.attach(GL_COLOR_ATTACHMENT2, geoNormal);
    gbuffer.attach(GL_COLOR_ATTACHMENT3, albedo);
    gbuffer.attach(GL_DEPTH_ATTACHMENT, depth);
    gbuffer.finish(4);
    size = s;
  }
};

Renderer::Renderer(gl::Context& context)
    : mContext(context), mShaders(std::make_unique<ShaderLibrary>()),
      mImpl(std::make_unique<Impl>(context.info().softwareRenderer)) {}

Renderer::~Renderer() = default;

const Scene& Renderer::scene() const { return mImpl->scene; }

void Renderer::setScene(const Scene& scene) {
  scene.validate();
  mImpl->scene = scene;
  mImpl->gpuScene = std::make_unique<GpuScene>(mImpl->scene);
}

void Renderer::setTechnique(std::unique_ptr<Projection> projection, std::unique_ptr<Filter> filter) {
  PN_CHECK(projection && filter, "setTechnique needs a projection and a filter");
  if (mImpl->gpuScene) {
    const std::string why = filter->incompatibility(projection->id(), mImpl->scene.light());
    if (!why.empty())
      throw usageError(fmt::format("--filter {} with --projection {} is not supported: {}", filter->id(),
                                   projection->id(), why));
  }
  mProjection = std::move(projection);
  mFilter = std::move(filter);
}

namespace {

gpu::FrameUniforms frameUniforms(const Scene& scene, glm::ivec2 size, int frameIndex) {
  const Camera& cam = scene.camera;
  const Light& light = scene.light();
  const float aspect = static_cast<float>(size.x) / static_cast<float>(size.y);
  gpu::FrameUniforms f{};
  f.viewFromWorld = cam.viewFromWorld();
  f.clipFromWorld = cam.clipFromView(aspect) * f.viewFromWorld;
  f.cameraPosition = glm::vec4(cam.position, 1.0f);
  const bool spot = light.type == LightType::Spot;
  f.lightDirection = glm::vec4(glm::normalize(light.direction), spot ? PN_LIGHT_SPOT : PN_LIGHT_SUN);
  f.lightPosition = glm::vec4(light.position, std::cos(light.coneAngleRad));
  f.lightRadiance = glm::vec4(light.color * light.intensity, light.size);
  f.ambient = glm::vec4(scene.ambient, 0.0f);
  f.screen = glm::ivec4(size.x, size.y, frameIndex, 0);
  f.sceneInfo = glm::vec4(scene.bounds().radius(), 0, 0, 0);
  return f;
}

gpu::ShadowUniforms shadowUniforms(const LightFrusta& frusta, int mapSize) {
  PN_CHECK(!frusta.views.empty() && frusta.views.size() <= PN_MAX_SHADOW_VIEWS,
           fmt::format("a projection produced {} shadow views (1..{} allowed)", frusta.views.size(), PN_MAX_SHADOW_VIEWS));
  gpu::ShadowUniforms s{};
  for (size_t i = 0; i < frusta.views.size(); ++i) {
    const ShadowView& v = frusta.views[i];
    s.views[i].clipFromWorld = v.clipFromWorld;
    s.views[i].depthPlane = v.depthPlane;
    s.views[i].range = glm::vec4(v.nearM, v.farM, v.perspective ? 1.0f : 0.0f, v.splitFarM);
    s.views[i].extent = glm::vec4(v.extent, frusta.blendBandM, v.warped ? 1.0f : 0.0f);
  }
  s.info = glm::ivec4(static_cast<int>(frusta.views.size()), mapSize, 0, 0);
  return s;
}

}  // namespace

void Renderer::render(const RenderOptions& options) {
  PN_CHECK(mImpl->gpuScene, "render() before setScene()");
  PN_CHECK(mProjection && mFilter, "render() before setTechnique()");
  Impl& im = *mImpl;
  const int maxSize = gl::maxTextureSize();
  if (options.shadowMapSize < 1 || options.shadowMapSize > maxSize)
    throw Error(fmt::format("shadow map size {} is outside 1..{} (the driver's maximum texture size)",
                            options.shadowMapSize, maxSize));
  im.ensureScreen({options.width, options.height});
  im.mapSize = options.shadowMapSize;
  im.debugView = options.debugView;
  const float aspect = static_cast<float>(options.width) / static_cast<float>(options.height);
  mFrusta = mProjection->computeFrusta(im.scene.camera, aspect, im.scene.light(), im.scene, options.shadowMapSize);

  const gpu::FrameUniforms frame = frameUniforms(im.scene, im.size, im.frameIndex++);
  const gpu::ShadowUniforms shadow = shadowUniforms(mFrusta, options.shadowMapSize);
  im.frameBlock.upload(frame);
  im.shadowBlock.upload(shadow);
  im.frameBlock.bindBase(GL_UNIFORM_BUFFER, PN_UBO_FRAME);
  im.shadowBlock.bindBase(GL_UNIFORM_BUFFER, PN_UBO_SHADOW);

  FrameContext ctx(im.scene, mFrusta, options.shadowMapSize, im.size, *mShaders, *im.gpuScene, im.filterBlock,
                   im.timer, &im.visibility);
  im.timer.beginFrame();
  {
    ScopedPass pass(im.timer, "shadow");
    mFilter->renderShadowMaps(ctx);
  }
  gl::throwIfGlError("the shadow pass");
  {
    ScopedPass pass(im.timer, "prefilter");
    mFilter->prefilter(ctx);
  }
  gl::throwIfGlError("the prefilter pass");
  {
    ScopedPass pass(im.timer, "gbuffer");
    ProgramDesc d;
    d.label = "gbuffer";
    d.vertex = {"passes/geometry.vert.glsl"};
    d.fragment = {"passes/gbuffer.frag.glsl"};
    const gl::Program& program = mShaders->program(d);
    glProgramUniform1i(program.id(), PN_LOC_VIEW, -1);
    glBindFramebuffer(GL_FRAMEBUFFER, im.gbuffer.id());
    glViewport(0, 0, im.size.x, im.size.y);
    const float zero[4] = {0, 0, 0, 0};
    const float farDepth = 0.0f;  // reversed-Z
    for (GLint i = 0; i < 4; ++i) glClearNamedFramebufferfv(im.gbuffer.id(), GL_COLOR, i, zero);
    glClearNamedFramebufferfv(im.gbuffer.id(), GL_DEPTH, 0, &farDepth);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_GREATER);
    glDepthMask(GL_TRUE);
    glDisable(GL_CULL_FACE);
    program.use();
    im.gpuScene->draw(program.id(), false);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
  }
  gl::throwIfGlError("the G-buffer pass");
  im.position.bindUnit(PN_TEX_GBUF_POSITION);
  im.normal.bindUnit(PN_TEX_GBUF_NORMAL);
  im.geoNormal.bindUnit(PN_TEX_GBUF_GEONORMAL);
  im.albedo.bindUnit(PN_TEX_GBUF_ALBEDO);
  {
    ScopedPass pass(im.timer, "visibility");
    mFilter->computeVisibility(ctx);
  }
  gl::throwIfGlError("the visibility pass");
  {
    ScopedPass pass(im.timer, "lit");
    runLitPass();
  }
  mTimings = im.timer.endFrame();
}

void Renderer::runLitPass() {
  Impl& im = *mImpl;
  ProgramDesc d;
  d.label = "lit";
  d.compute = {"passes/lit.comp.glsl"};
  const gl::Program& program = mShaders->program(d);
  glProgramUniform1i(program.id(), PN_LOC_LEVEL, im.debugView);
  im.position.bindUnit(PN_TEX_GBUF_POSITION);
  im.normal.bindUnit(PN_TEX_GBUF_NORMAL);
  im.albedo.bindUnit(PN_TEX_GBUF_ALBEDO);
  im.visibility.bindUnit(PN_TEX_VISIBILITY);
  im.color.bindImage(PN_IMG_OUTPUT, GL_WRITE_ONLY);
  im.frameBlock.bindBase(GL_UNIFORM_BUFFER, PN_UBO_FRAME);
  im.shadowBlock.bindBase(GL_UNIFORM_BUFFER, PN_UBO_SHADOW);  // cascade and texel-density views
  FrameContext::dispatch2D(program, im.size.x, im.size.y, PN_SCREEN_GROUP);
  gl::throwIfGlError("the lit pass");
}

std::vector<float> Renderer::visibilityAt(std::span<const SurfaceSample> points) {
  PN_CHECK(mImpl->gpuScene && mImpl->mapSize > 0, "visibilityAt() before render()");
  Impl& im = *mImpl;
  if (points.empty()) return {};
  const glm::ivec4 header(static_cast<int>(points.size()), PN_POINTS_GRID_WIDTH, 0, 0);
  std::vector<gpu::VisibilityPointGpu> data(points.size());
  for (size_t i = 0; i < points.size(); ++i)
    data[i] = {glm::vec4(points[i].position, 1.0f), glm::vec4(points[i].geoNormal, 0.0f), glm::ivec4(points[i].pixel, 0, 0)};
  gl::Buffer in("visibility points", sizeof(header) + data.size() * sizeof(gpu::VisibilityPointGpu));
  in.upload(&header, sizeof(header));
  in.upload(data.data(), data.size() * sizeof(gpu::VisibilityPointGpu), sizeof(header));
  gl::Buffer out("visibility at points", points.size() * sizeof(float));
  im.frameBlock.bindBase(GL_UNIFORM_BUFFER, PN_UBO_FRAME);
  im.shadowBlock.bindBase(GL_UNIFORM_BUFFER, PN_UBO_SHADOW);
  FrameContext ctx(im.scene, mFrusta, im.mapSize, im.size, *mShaders, *im.gpuScene, im.filterBlock, im.timer, &im.visibility);
  ctx.setPoints(&in, &out, static_cast<int>(points.size()));
  im.timer.beginFrame();  // a filter may time sub-passes; these times are not kept
  mFilter->computeVisibility(ctx);
  im.timer.endFrame();
  gl::throwIfGlError("the visibility pass at points");
  std::vector<float> v(points.size());
  out.download(v.data(), v.size() * sizeof(float));
  return v;
}

std::vector<float> Renderer::computeScreenScalar(const std::string& computeShader) {
  PN_CHECK(mImpl->gpuScene && mImpl->mapSize > 0, "computeScreenScalar() before render()");
  Impl& im = *mImpl;
  ProgramDesc d;
  d.label = computeShader;
  d.compute = {computeShader};
  const gl::Program& program = mShaders->program(d);
  gl::Texture target("screen scalar", {GL_TEXTURE_2D, GL_R32F, im.size.x, im.size.y, 1, 1});
  im.position.bindUnit(PN_TEX_GBUF_POSITION);
  im.normal.bindUnit(PN_TEX_GBUF_NORMAL);
  im.geoNormal.bindUnit(PN_TEX_GBUF_GEONORMAL);
  im.albedo.bindUnit(PN_TEX_GBUF_ALBEDO);
  im.frameBlock.bindBase(GL_UNIFORM_BUFFER, PN_UBO_FRAME);
  im.shadowBlock.bindBase(GL_UNIFORM_BUFFER, PN_UBO_SHADOW);
  target.bindImage(PN_IMG_OUTPUT, GL_WRITE_ONLY);
  FrameContext::dispatch2D(program, im.size.x, im.size.y, PN_SCREEN_GROUP);
  gl::throwIfGlError(computeShader.c_str());
  std::vector<float> v(static_cast<size_t>(im.size.x) * static_cast<size_t>(im.size.y));
  target.read(GL_RED, GL_FLOAT, v.data(), v.size() * sizeof(float));
  return v;
}

ColorImage Renderer::shadeWithVisibility(std::span<const float> visibility) {
  Impl& im = *mImpl;
  const size_t n = static_cast<size_t>(im.size.x) * static_cast<size_t>(im.size.y);
  PN_CHECK(visibility.size() == n, fmt::format("shadeWithVisibility: {} values for a {}x{} frame", visibility.size(), im.size.x, im.size.y));
  const std::vector<float> own = readVisibility();
  glTextureSubImage2D(im.visibility.id(), 0, 0, 0, im.size.x, im.size.y, GL_RED, GL_FLOAT, visibility.data());
  runLitPass();
  ColorImage out = readColor();
  glTextureSubImage2D(im.visibility.id(), 0, 0, 0, im.size.x, im.size.y, GL_RED, GL_FLOAT, own.data());
  runLitPass();
  return out;
}

void Renderer::setCameraAndLights(const Camera& camera, const std::vector<Light>& lights) {
  if (lights.empty()) throw usageError("setCameraAndLights: a scene needs at least one light");
  mImpl->scene.camera = camera;
  mImpl->scene.lights = lights;
}

const gl::Texture& Renderer::colorTexture() const { return mImpl->color; }

std::vector<DebugImage> Renderer::debugImages() const {
  std::vector<DebugImage> out = {{"visibility", &mImpl->visibility},
                                 {"gbuffer-depth", &mImpl->depth},
                                 {"gbuffer-normal", &mImpl->normal},
                                 {"gbuffer-albedo", &mImpl->albedo}};
  if (mFilter)
    for (const DebugImage& d : mFilter->debugImages()) out.push_back(d);
  return out;
}

std::vector<float> Renderer::readVisibility() const {
  std::vector<float> v(static_cast<size_t>(mImpl->size.x) * static_cast<size_t>(mImpl->size.y));
  mImpl->visibility.read(GL_RED, GL_FLOAT, v.data(), v.size() * sizeof(float));
  return v;
}

GBufferData Renderer::readGBuffer() const {
  GBufferData g;
  g.width = mImpl->size.x;
  g.height = mImpl->size.y;
  const size_t n = static_cast<size_t>(g.width) * static_cast<size_t>(g.height);
  auto read = [&](const gl::Texture& t, std::vector<glm::vec4>& out) {
    out.resize(n);
    t.read(GL_RGBA, GL_FLOAT, out.data(), n * sizeof(glm::vec4));
  };
  read(mImpl->position, g.position);
  read(mImpl->geoNormal, g.geoNormal);
  read(mImpl->normal, g.normal);
  read(mImpl->albedo, g.albedo);
  return g;
}

ColorImage Renderer::readColor() const {
  ColorImage img;
  img.width = mImpl->size.x;
  img.height = mImpl->size.y;
  std::vector<uint8_t> raw(static_cast<size_t>(img.width) * static_cast<size_t>(img.height) * 4);
  mImpl->color.read(GL_RGBA, GL_UNSIGNED_BYTE, raw.data(), raw.size());
  img.rgba = flipRows<uint8_t>(raw, img.width, img.height, 4);
  return img;
}

namespace {

// Writes channel 0 of every layer of `t` as EXR (exact values) and PNG (normalised to its range).
void dumpTexture(const std::filesystem::path& dir, const std::string& name, const gl::Texture& t) {
  const bool depth = t.desc().format == GL_DEPTH_COMPONENT32F || t.desc().format == GL_DEPTH_COMPONENT24;
  const int w = t.width(), h = t.height(), layers = t.desc().target == GL_TEXTURE_2D ? 1 : t.layers();
  const size_t perLayer = static_cast<size_t>(w) * static_cast<size_t>(h);
  std::vector<float> all(perLayer * static_cast<size_t>(layers) * (depth ? 1 : 4));
  t.read(depth ? GL_DEPTH_COMPONENT : GL_RGBA, GL_FLOAT, all.data(), all.size() * sizeof(float));
  const size_t stride = depth ? 1 : 4;
  for (int l = 0; l < layers; ++l) {
    std::vector<float> c(perLayer);
    for (size_t i = 0; i < perLayer; ++i) c[i] = all[(static_cast<size_t>(l) * perLayer + i) * stride];
    const std::string base = layers > 1 ? fmt::format("{}-{}", name, l) : name;
    const std::vector<float> top = flipRows<float>(c, w, h);
    writeExr(dir / (base + ".exr"), w, h, top);
    float lo = 1e30f, hi = -1e30f;
    for (float v : top) if (std::isfinite(v)) { lo = std::min(lo, v); hi = std::max(hi, v); }
    const float scale = hi > lo ? 1.0f / (hi - lo) : 1.0f;
    std::vector<uint8_t> rgba(perLayer * 4);
    for (size_t i = 0; i < perLayer; ++i) {
      const auto g = static_cast<uint8_t>(std::clamp((top[i] - lo) * scale, 0.0f, 1.0f) * 255.0f + 0.5f);
      rgba[i * 4] = rgba[i * 4 + 1] = rgba[i * 4 + 2] = g;
      rgba[i * 4 + 3] = 255;
    }
    writePng(dir / (base + ".png"), w, h, rgba);
  }
}

}  // namespace

void Renderer::dump(const std::string& dirName) const {
  const std::filesystem::path dir(dirName);
  const ColorImage color = readColor();
  writePng(dir / "color.png", color.width, color.height, color.rgba);
  dumpTexture(dir, "visibility", mImpl->visibility);
  dumpTexture(dir, "gbuffer-depth", mImpl->depth);
  // Normals and albedo as viewable colour images.
  const GBufferData g = readGBuffer();
  auto writeVec = [&](const char* file, const std::vector<glm::vec4>& data, float scale, float bias) {
    std::vector<uint8_t> rgba(data.size() * 4);
    for (size_t i = 0; i < data.size(); ++i) {
      for (int c = 0; c < 3; ++c)
        rgba[i * 4 + static_cast<size_t>(c)] = static_cast<uint8_t>(std::clamp(data[i][c] * scale + bias, 0.0f, 1.0f) * 255.0f);
      rgba[i * 4 + 3] = 255;
    }
    writePng(dir / file, g.width, g.height, flipRows<uint8_t>(rgba, g.width, g.height, 4));
  };
  writeVec("gbuffer-normal.png", g.normal, 0.5f, 0.5f);
  writeVec("gbuffer-geometric-normal.png", g.geoNormal, 0.5f, 0.5f);
  writeVec("gbuffer-albedo.png", g.albedo, 1.0f, 0.0f);
  for (const DebugImage& d : mFilter->debugImages())
    if (d.texture && *d.texture) dumpTexture(dir, d.name, *d.texture);
}

}  // namespace penumbra
