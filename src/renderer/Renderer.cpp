// Penumbra's own renderer: G-buffer → the core's shadows (projection → shadow pass → prefilter →
// visibility) → lit. No technique-specific branch lives here, and no shadow work either: the
// core (penumbra/Shadows.h) gets this G-buffer and the scene's buffers as an engine would.
#include <penumbra/Renderer.h>

#include "core/FrameBlocks.h"
#include "core/ShadowsAccess.h"
#include "frame/CasterSet.h"
#include "frame/FrameContext.h"
#include "frame/PassTimer.h"
#include "frame/ScreenTarget.h"
#include "gl/Debug.h"
#include "gl/Objects.h"
#include "renderer/GpuScene.h"
#include "shader/ShaderLibrary.h"
#include "shared/Bindings.h"
#include "shared/Frame.h"

#include <penumbra/Error.h>
#include <penumbra/Exr.h>
#include <penumbra/ImageIO.h>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iterator>

namespace penumbra {

namespace {
constexpr int kMaxScreenSide = 16384;

/// The screen textures the renderer allocates per frame size, with their texel sizes (for
/// Renderer::screenBytes).
struct ScreenTexture {
  const char* label;
  GLenum format;
  uint64_t bytesPerTexel;
};
constexpr ScreenTexture kScreenTextures[] = {
    {"gbuffer position", GL_RGBA32F, 16}, {"gbuffer normal", GL_RGBA16F, 8}, {"gbuffer geometric normal", GL_RGBA16F, 8},
    {"gbuffer albedo", GL_RGBA8, 4},      {"gbuffer triangle", GL_RG32UI, 8},
    {"gbuffer depth", GL_DEPTH_COMPONENT32F, 4}, {"color", GL_RGBA8, 4}};
// The core's own per-pixel texture: the visibility (R32F).
constexpr uint64_t kCoreBytesPerPixel = 4;
}  // namespace

uint64_t Renderer::screenBytes(int width, int height) {
  uint64_t perPixel = kCoreBytesPerPixel;
  for (const ScreenTexture& t : kScreenTextures) perPixel += t.bytesPerTexel;
  return perPixel * static_cast<uint64_t>(width) * static_cast<uint64_t>(height);
}

struct Renderer::Impl {
  Scene scene;
  std::unique_ptr<GpuScene> gpuScene;
  Shadows shadows;
  PassTimer timer{gl::isSoftwareRenderer(gl::glString(GL_RENDERER))};
  PassTimings timings;
  gl::Buffer frameBlock{"renderer frame block", sizeof(gpu::FrameUniforms)};
  gl::Buffer lightsBlock;  ///< the lit pass's lights (PN_SSBO_LIGHTS): LightGpu[PN_LIT_LIGHTS]
  // Screen targets
  glm::ivec2 size{0};
  gl::Texture position, normal, geoNormal, albedo, triangle, depth, color;
  gl::Framebuffer gbuffer;
  ScreenTarget litTarget;     // the lit pass draws into `color`
  int gbufferColors = 0;      // draw buffers of gbuffer: 5 with the triangle ids, 4 without
  gl::VertexArray emptyVao{"renderer full-screen vao"};  // the G-buffer background's (no attributes)
  int frameIndex = 0;
  bool rendered = false;             // a frame was rendered since setScene
  bool triangleIds = false;          // of the last frame
  int debugView = PN_VIEW_SHADED;    // of the last frame

  void ensureScreen(glm::ivec2 s) {
    if (s == size) return;
    PN_CHECK(s.x > 0 && s.y > 0 && s.x <= kMaxScreenSide && s.y <= kMaxScreenSide,
             fmt::format("image size {}x{} is outside 1..{}", s.x, s.y, kMaxScreenSide));
    gl::Texture* targets[] = {&position, &normal, &geoNormal, &albedo, &triangle, &depth, &color};  // kScreenTextures' order
    static_assert(std::size(kScreenTextures) == std::size(targets));
    try {
      for (size_t i = 0; i < std::size(kScreenTextures); ++i) {
        *targets[i] = gl::Texture(kScreenTextures[i].label, {GL_TEXTURE_2D, kScreenTextures[i].format, s.x, s.y, 1, 1});
        targets[i]->setSampling(GL_NEAREST, GL_NEAREST);
      }
      gbuffer = gl::Framebuffer("gbuffer");
      gbuffer.attach(GL_COLOR_ATTACHMENT0, position);
      gbuffer.attach(GL_COLOR_ATTACHMENT1, normal);
      gbuffer.attach(GL_COLOR_ATTACHMENT2, geoNormal);
      gbuffer.attach(GL_COLOR_ATTACHMENT3, albedo);
      gbuffer.attach(GL_COLOR_ATTACHMENT4, triangle);
      gbuffer.attach(GL_DEPTH_ATTACHMENT, depth);
      gbuffer.finish(5);
      gbufferColors = 5;
      litTarget = ScreenTarget("lit pass", color);
    } catch (const Error& e) {
      throw Error(fmt::format("the {}x{} image's targets: {}", s.x, s.y, e.what()));
    }
    size = s;
  }

  /// The scene's casters (and the bounds of the objects that only receive: the scene is every
  /// receiver there is) to the core, on the GPU and on the CPU (for filters that bake them).
  void sendCasters() {
    std::vector<Aabb> receivers;
    for (const Object& o : scene.objects)
      if (!o.castsShadow) receivers.push_back(scene.meshes[o.mesh].bounds().transformed(o.worldFromObject));
    shadows.setCasters(gpuScene->casterMeshes(scene), {.bounds = receivers, .complete = true});
    shadows.setCasterGeometry(casterGeometry(scene));
  }

  ShadowCamera camera() const {
    return ShadowCamera::fromCamera(scene.camera, static_cast<float>(size.x) / static_cast<float>(size.y));
  }

  /// The G-buffer and lit passes' frame block: the core's, plus the ambient the lit pass adds.
  void uploadFrameBlock() {
    gpu::FrameUniforms f = core::frameUniforms(camera(), scene.light(), size, frameIndex++, scene.bounds().radius());
    f.ambient = glm::vec4(scene.ambient, 0.0f);
    frameBlock.upload(f);
    frameBlock.bindBase(GL_UNIFORM_BUFFER, PN_UBO_FRAME);
  }
};

Renderer::Renderer() : mImpl(std::make_unique<Impl>()) {}

Renderer::~Renderer() = default;

const Scene& Renderer::scene() const { return mImpl->scene; }
const Technique& Renderer::technique() const { return mImpl->shadows.technique(); }
const LightFrusta& Renderer::frusta(size_t light) const { return penumbra::frusta(mImpl->shadows, light); }
const PassTimings& Renderer::timings() const { return mImpl->timings; }
ShaderLibrary& Renderer::shaders() { return shaderLibrary(mImpl->shadows); }
Shadows& Renderer::shadows() { return mImpl->shadows; }

void Renderer::setScene(Scene scene) {
  scene.validate();
  mImpl->scene = std::move(scene);
  mImpl->gpuScene = std::make_unique<GpuScene>(mImpl->scene);
  mImpl->rendered = false;
  mImpl->sendCasters();
}

void Renderer::setPose(const Scene& posed) {
  Impl& im = *mImpl;
  PN_CHECK(im.gpuScene, "setPose() before setScene()");
  PN_CHECK(posed.objects.size() == im.scene.objects.size(),
           fmt::format("setPose: {} objects for a scene of {}", posed.objects.size(), im.scene.objects.size()));
  setCameraAndLights(posed.camera, posed.lights);
  bool moved = false;
  for (size_t i = 0; i < posed.objects.size() && !moved; ++i)
    moved = posed.objects[i].worldFromObject != im.scene.objects[i].worldFromObject;
  if (!moved) return;
  for (size_t i = 0; i < posed.objects.size(); ++i) im.scene.objects[i].worldFromObject = posed.objects[i].worldFromObject;
  im.gpuScene->setTransforms(im.scene);
  im.sendCasters();
}

void Renderer::setTechnique(const Technique& technique) {
  if (mImpl->gpuScene) {
    const bool several = mImpl->scene.lights.size() > 1;
    for (size_t i = 0; i < mImpl->scene.lights.size(); ++i) {
      const Light& l = mImpl->scene.lights[i];
      const std::string which = several ? fmt::format("light {}", i) : "";
      const Technique merged = technique.forLight(l.shadow, which);
      if (const std::string why = l.castsShadow ? merged.problemWith(l) : ""; !why.empty())
        throw usageError(which.empty() ? why : fmt::format("{}: {}", which, why));
    }
  }
  mImpl->shadows.setTechnique(technique);
}

void Renderer::render(const RenderOptions& options) {
  PN_CHECK(mImpl->gpuScene, "render() before setScene()");
  Impl& im = *mImpl;
  im.ensureScreen({options.width, options.height});
  im.debugView = options.debugView;

  im.timer.beginFrame();
  {
    ScopedPass pass(im.timer, "gbuffer");
    im.uploadFrameBlock();
    im.triangleIds = options.triangleIds;
    const int colors = im.triangleIds ? 5 : 4;  // attachment 4 holds the triangle ids
    if (colors != im.gbufferColors) {
      im.gbuffer.finish(colors);
      im.gbufferColors = colors;
    }
    ProgramDesc d;
    d.label = "gbuffer";
    d.vertex = {"passes/geometry.vert.glsl"};
    d.fragment = {"passes/gbuffer.frag.glsl"};
    d.defines.set("PN_GBUFFER_TRIANGLES", im.triangleIds ? 1 : 0);
    const gl::Program& program = shaders().program(d);
    glProgramUniform1i(program.id(), PN_LOC_VIEW, -1);
    glBindFramebuffer(GL_FRAMEBUFFER, im.gbuffer.id());
    glViewport(0, 0, im.size.x, im.size.y);
    // Only the depth is cleared: the colour attachments get their background values from a
    // full-screen triangle drawn after the surfaces, on the far plane (fullscreen.vert.glsl: stored
    // depth 0, the value cleared here) with an EQUAL test, so it writes just the pixels no surface
    // covered instead of clearing all five over the whole screen.
    const float farDepth = 0.0f;  // reversed-Z
    glClearNamedFramebufferfv(im.gbuffer.id(), GL_DEPTH, 0, &farDepth);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_GREATER);
    glDepthMask(GL_TRUE);
    glDisable(GL_CULL_FACE);
    program.use();
    im.gpuScene->draw(program.id(), im.triangleIds ? PN_LOC_FIRST_TRIANGLE : -1);
    ProgramDesc b;
    b.label = "gbuffer background";
    b.vertex = {"passes/fullscreen.vert.glsl"};
    b.fragment = {"passes/gbuffer_background.frag.glsl"};
    b.defines = d.defines;
    const gl::Program& background = shaders().program(b);
    glDepthFunc(GL_EQUAL);
    glDepthMask(GL_FALSE);
    background.use();
    glBindVertexArray(im.emptyVao.id());
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glBindVertexArray(0);
    glDepthFunc(GL_GREATER);
    glDepthMask(GL_TRUE);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
  }
  gl::throwIfGlError("the G-buffer pass");
  const PassTimings gbuffer = im.timer.endFrame();

  ShadowFrameInputs in;
  in.camera = im.camera();
  in.surfaces = {im.size.x, im.size.y, im.depth.id(), im.geoNormal.id(), im.position.id()};
  PN_CHECK(!im.scene.lights.empty(), "render(): the scene has no light");
  in.lights = im.scene.lights;
  in.mapBudgetTexels = options.shadowBudgetTexels;
  in.restore = RestoreState::None;  // this renderer sets what each of its passes needs
  in.cameraCut = options.cameraCut;
  im.shadows.render(in);
  im.rendered = true;

  im.timer.beginFrame();
  {
    ScopedPass pass(im.timer, "lit");
    runLitPass();
  }
  const PassTimings lit = im.timer.endFrame();
  im.timings = gbuffer;
  for (const auto& entry : im.shadows.timings().ms) im.timings.ms.push_back(entry);
  for (const auto& entry : lit.ms) im.timings.ms.push_back(entry);
}

void Renderer::runLitPass(const gl::Texture* visibility, bool colour) {
  Impl& im = *mImpl;
  if (!visibility) colour = im.shadows.visibilityHasColour();
  ProgramDesc d;
  d.label = "lit";
  d.fragment = {"passes/lit.glsl"};
  // Built per debug view (the shaded image runs none of the debug code), per light count (a
  // constant loop: about a fifth of the pass on llvmpipe) and without the spot and point code
  // when every light is a sun (llvmpipe runs both sides of a branch).
  d.defines.set("PN_DEBUG_VIEW", im.debugView);
  d.defines.set("PN_LIT_LIGHTS", static_cast<int>(im.scene.lights.size()));
  if (std::none_of(im.scene.lights.begin(), im.scene.lights.end(), [](const Light& l) { return isPositional(l); }))
    d.defines.set("PN_ONLY_SUNS");
  if (im.debugView != PN_VIEW_SHADED && im.shadows.lightCount() > 0) d.defines.merge(ShadowsAccess::viewDefines(im.shadows, 0));
  if (colour) d.defines.set("PN_VISIBILITY_RGB");
  const gl::Program& program = shaders().program(fullScreenProgram(d));
  std::vector<gpu::LightGpu> lights;
  for (const Light& l : im.scene.lights) lights.push_back(core::lightGpu(l));
  const size_t bytes = lights.size() * sizeof(gpu::LightGpu);
  if (im.lightsBlock.size() < bytes) im.lightsBlock = gl::Buffer("lit pass lights", bytes);
  im.lightsBlock.upload(lights.data(), bytes);
  im.lightsBlock.bindBase(GL_SHADER_STORAGE_BUFFER, PN_SSBO_LIGHTS);
  im.position.bindUnit(PN_TEX_GBUF_POSITION);
  im.normal.bindUnit(PN_TEX_GBUF_NORMAL);
  im.albedo.bindUnit(PN_TEX_GBUF_ALBEDO);
  glBindTextureUnit(PN_TEX_VISIBILITY, visibility ? visibility->id() : im.shadows.visibilityArrayTexture());
  bindFrameBlocks(im.shadows);  // the shadow views: cascade and texel-density debug views
  im.frameBlock.bindBase(GL_UNIFORM_BUFFER, PN_UBO_FRAME);
  glDisable(GL_DITHER);  // the colour is written as computed, as an image store would
  im.litTarget.draw(program, im.size);
  gl::throwIfGlError("the lit pass");
}

std::vector<float> Renderer::visibilityAt(std::span<const SurfaceSample> points, size_t light) {
  PN_CHECK(mImpl->gpuScene && mImpl->rendered, "visibilityAt() before render()");
  return penumbra::visibilityAt(mImpl->shadows, points, light);
}

std::vector<float> Renderer::computeScreenScalar(const std::string& computeShader) {
  PN_CHECK(mImpl->gpuScene && mImpl->rendered, "computeScreenScalar() before render()");
  Impl& im = *mImpl;
  ProgramDesc d;
  d.label = computeShader;
  d.compute = {computeShader};
  if (im.shadows.lightCount() > 0) d.defines = ShadowsAccess::viewDefines(im.shadows, 0);  // the first light's views, as bound
  const gl::Program& program = shaders().program(d);
  gl::Texture target("screen scalar", {GL_TEXTURE_2D, GL_R32F, im.size.x, im.size.y, 1, 1});
  im.position.bindUnit(PN_TEX_GBUF_POSITION);
  im.normal.bindUnit(PN_TEX_GBUF_NORMAL);
  im.geoNormal.bindUnit(PN_TEX_GBUF_GEONORMAL);
  im.albedo.bindUnit(PN_TEX_GBUF_ALBEDO);
  bindFrameBlocks(im.shadows);
  im.frameBlock.bindBase(GL_UNIFORM_BUFFER, PN_UBO_FRAME);
  target.bindImage(PN_IMG_OUTPUT, GL_WRITE_ONLY);
  FrameContext::dispatch2D(program, im.size.x, im.size.y, PN_SCREEN_GROUP);
  gl::throwIfGlError(computeShader.c_str());
  std::vector<float> v(static_cast<size_t>(im.size.x) * static_cast<size_t>(im.size.y));
  target.read(GL_RED, GL_FLOAT, v.data(), v.size() * sizeof(float));
  return v;
}

ColorImage Renderer::shadeWithVisibility(const std::vector<std::vector<float>>& perLight,
                                         const std::vector<std::vector<glm::vec3>>& perLightRgb) {
  Impl& im = *mImpl;
  const size_t n = static_cast<size_t>(im.size.x) * static_cast<size_t>(im.size.y);
  PN_CHECK(perLight.size() == lightCount(), fmt::format("shadeWithVisibility: {} visibilities for {} lights", perLight.size(), lightCount()));
  PN_CHECK(perLightRgb.empty() || perLightRgb.size() == perLight.size(),
           fmt::format("shadeWithVisibility: {} colour visibilities for {} lights", perLightRgb.size(), perLight.size()));
  const bool colour = std::any_of(perLightRgb.begin(), perLightRgb.end(), [](const auto& v) { return !v.empty(); });
  // The lit pass reads an array of the caller's values (the frame's own V stays as it is).
  gl::Texture array("shaded visibility", {GL_TEXTURE_2D_ARRAY, static_cast<GLenum>(colour ? GL_RGBA32F : GL_R32F), im.size.x, im.size.y,
                                          static_cast<int>(perLight.size()), 1});
  array.setSampling(GL_NEAREST, GL_NEAREST);
  for (size_t i = 0; i < perLight.size(); ++i) {
    PN_CHECK(perLight[i].size() == n, fmt::format("shadeWithVisibility: {} values for a {}x{} frame", perLight[i].size(), im.size.x, im.size.y));
    const void* data = perLight[i].data();
    GLenum format = GL_RED;
    std::vector<glm::vec3> grey;
    if (colour && i < perLightRgb.size() && !perLightRgb[i].empty()) {
      PN_CHECK(perLightRgb[i].size() == n, fmt::format("shadeWithVisibility: {} colour values for a {}x{} frame", perLightRgb[i].size(), im.size.x, im.size.y));
      data = perLightRgb[i].data();
      format = GL_RGB;
    } else if (colour) {  // a light without colour: its one value in every channel
      grey.resize(n);
      std::transform(perLight[i].begin(), perLight[i].end(), grey.begin(), [](float v) { return glm::vec3(v); });
      data = grey.data();
      format = GL_RGB;
    }
    glTextureSubImage3D(array.id(), 0, 0, 0, static_cast<GLint>(i), im.size.x, im.size.y, 1, format, GL_FLOAT, data);
  }
  runLitPass(&array, colour);
  ColorImage out = readColor();
  runLitPass();
  return out;
}

ColorImage Renderer::shadeWithVisibility(std::span<const float> visibility) {
  return shadeWithVisibility(std::vector<std::vector<float>>{std::vector<float>(visibility.begin(), visibility.end())});
}

size_t Renderer::lightCount() const { return mImpl->shadows.lightCount(); }

void Renderer::setCameraAndLights(const Camera& camera, const std::vector<Light>& lights) {
  if (lights.empty()) throw usageError("setCameraAndLights: a scene needs at least one light");
  mImpl->scene.camera = camera;
  mImpl->scene.lights = lights;
}

const gl::Texture& Renderer::colorTexture() const { return mImpl->color; }

std::vector<DebugImage> Renderer::debugImages(size_t light) const {
  std::vector<DebugImage> core = penumbra::debugImages(mImpl->shadows, light);
  std::vector<DebugImage> out = {core.front(),  // the visibility
                                 {"gbuffer-depth", &mImpl->depth, "camera depth, reversed-Z: 1 = near plane, 0 = infinitely far"},
                                 {"gbuffer-normal", &mImpl->normal, "world-space shading normal, x y z in [−1, 1]"},
                                 {"gbuffer-albedo", &mImpl->albedo, "albedo, linear RGB"}};
  out.insert(out.end(), core.begin() + 1, core.end());
  return out;
}

std::vector<float> Renderer::readVisibility(size_t light) const { return mImpl->shadows.readVisibility(light); }

std::vector<glm::vec3> Renderer::readVisibilityRgb(size_t light) const { return mImpl->shadows.readVisibilityRgb(light); }

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
  if (mImpl->triangleIds) {
    g.triangle.resize(n);
    mImpl->triangle.read(GL_RG_INTEGER, GL_UNSIGNED_INT, g.triangle.data(), n * sizeof(glm::uvec2));
  }
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
  const std::vector<DebugImage> images = penumbra::debugImages(mImpl->shadows);
  for (const DebugImage& d : images)
    if (d.name == "visibility" && d.texture) dumpTexture(dir, d.name, *d.texture);
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
  for (const DebugImage& d : images)
    if (d.name != "visibility" && d.texture && *d.texture) dumpTexture(dir, d.name, *d.texture);
}

}  // namespace penumbra
