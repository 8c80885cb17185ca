// The engine-facing core (penumbra/Shadows.h) as an engine uses it: its own buffers as casters,
// its own depth and normal textures, its GL state left as it was, its mistakes named.
#include "GlFixture.h"

#include "gl/Debug.h"
#include "gl/Objects.h"

#include <penumbra/Error.h>
#include <penumbra/Shadows.h>
#include <fmt/format.h>

#include <epoxy/gl.h>
#include <glm/gtc/matrix_transform.hpp>

#include <array>
#include <functional>
#include <string>
#include <vector>

using namespace penumbra;
using namespace penumbra::test;

namespace {

constexpr int kSize = 32;

// One caster triangle 1 m above the origin, in an engine's own buffer (position, then 3 floats
// it does not tell Penumbra about).
struct EngineScene {
  gl::Buffer vertices;
  CasterMesh caster;
  EngineScene() {
    const float data[] = {-1, 1, -1, 9, 9, 9, 1, 1, -1, 9, 9, 9, 0, 1, 1, 9, 9, 9};
    vertices = gl::Buffer("engine vertices", sizeof(data), data, 0);
    caster.vertexBuffer = vertices.id();
    caster.stride = 6 * sizeof(float);
    caster.count = 3;
    caster.objectBounds.extend(glm::vec3(-1, 1, -1));
    caster.objectBounds.extend(glm::vec3(1, 1, 1));
  }
};

// An engine's surfaces: a depth texture (GL's default range) holding the ground plane y = 0 as
// seen from above, and its normals. Made by hand: each pixel's depth is the plane's.
struct EngineSurfaces {
  gl::Texture depth{"engine depth", {GL_TEXTURE_2D, GL_DEPTH_COMPONENT32F, kSize, kSize, 1, 1}};
  gl::Texture normal{"engine normal", {GL_TEXTURE_2D, GL_RGBA16F, kSize, kSize, 1, 1}};
  glm::mat4 view = glm::lookAt(glm::vec3(0, 5, 0), glm::vec3(0), glm::vec3(0, 0, -1));
  glm::mat4 proj = glm::perspective(0.8f, 1.0f, 0.1f, 50.0f);
  EngineSurfaces() {
    // Straight down at y = 0 from 5 m: clip depth of the ground, to window depth in [0, 1].
    const glm::vec4 c = proj * view * glm::vec4(0, 0, 0, 1);
    const float d = c.z / c.w * 0.5f + 0.5f;
    const std::vector<float> depths(kSize * kSize, d);
    glTextureSubImage2D(depth.id(), 0, 0, 0, kSize, kSize, GL_DEPTH_COMPONENT, GL_FLOAT, depths.data());
    std::vector<glm::vec4> normals(kSize * kSize, glm::vec4(0, 1, 0, 0));
    glTextureSubImage2D(normal.id(), 0, 0, 0, kSize, kSize, GL_RGBA, GL_FLOAT, normals.data());
  }
  ShadowFrameInputs inputs(const Light& light) const {
    ShadowFrameInputs in;
    in.camera = ShadowCamera::fromMatrices(view, proj, DepthConvention::NegativeOneToOne);
    in.surfaces = {.width = kSize, .height = kSize, .depth = depth.id(), .normal = normal.id()};
    in.lights = std::span<const Light>(&light, 1);
    return in;
  }
};

Light overheadSun() {
  Light sun;
  sun.direction = {0.0f, -1.0f, 0.0f};
  return sun;
}

std::string usageErrorFrom(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.kind() == ErrorKind::Usage ? e.what() : std::string("runtime: ") + e.what();
  }
  return "";
}

}  // namespace

TEST(ShadowsApi, EngineDepthAndBuffersGiveTheShadowUnderTheCaster) {
  glContext();
  const EngineScene scene;
  const EngineSurfaces surfaces;
  Shadows shadows;
  shadows.setTechnique(Technique("uniform", "hard").setMapSize(256));
  const Aabb ground{{-3, 0, -3}, {3, 0, 3}};
  shadows.setCasters(std::span<const CasterMesh>(&scene.caster, 1), {.bounds = std::span<const Aabb>(&ground, 1)});
  const Light sun = overheadSun();
  shadows.render(surfaces.inputs(sun));
  const std::vector<float> v = shadows.readVisibility();
  ASSERT_EQ(v.size(), size_t(kSize * kSize));
  // The centre pixel looks at the origin, under the triangle; a corner looks ~1.9 m off it.
  const float centre = v[(kSize / 2) * kSize + kSize / 2], corner = v[0];
  std::printf("V under the caster %.2f, at the corner %.2f\n", centre, corner);
  EXPECT_EQ(centre, 0.0f);
  EXPECT_EQ(corner, 1.0f);
}

TEST(ShadowsApi, RestoresTheCallersGlState) {
  glContext();
  const EngineScene scene;
  const EngineSurfaces surfaces;
  Shadows shadows;
  shadows.setTechnique(Technique("csm", "pcss").setMapSize(256));  // shadow, prefilter and visibility passes all run
  shadows.setCasters(std::span<const CasterMesh>(&scene.caster, 1));

  // The engine's state: unusual values everywhere Penumbra works.
  gl::Framebuffer fb("engine fb");
  gl::Texture target("engine target", {GL_TEXTURE_2D, GL_RGBA8, 8, 8, 1, 1});
  fb.attach(GL_COLOR_ATTACHMENT0, target);
  fb.finish(1);
  gl::VertexArray vao("engine vao");
  gl::Buffer ubo("engine ubo", 256), ssbo("engine ssbo", 256);
  gl::Texture unit9("engine unit 9", {GL_TEXTURE_2D, GL_R32F, 4, 4, 1, 1});
  gl::Sampler sampler("engine sampler", {});
  glBindFramebuffer(GL_FRAMEBUFFER, fb.id());
  glViewport(3, 4, 50, 60);
  glBindVertexArray(vao.id());
  glEnable(GL_BLEND);
  glEnable(GL_SCISSOR_TEST);
  glEnable(GL_CULL_FACE);
  glDisable(GL_DEPTH_TEST);
  glDepthFunc(GL_GEQUAL);
  glDepthMask(GL_FALSE);
  glColorMask(GL_TRUE, GL_FALSE, GL_TRUE, GL_FALSE);
  glClipControl(GL_UPPER_LEFT, GL_NEGATIVE_ONE_TO_ONE);
  glBindBufferRange(GL_UNIFORM_BUFFER, 1, ubo.id(), 0, 128);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, ssbo.id());
  glBindTextureUnit(9, unit9.id());
  glBindSampler(0, sampler.id());
  glBindImageTexture(1, unit9.id(), 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32F);
  glActiveTexture(GL_TEXTURE5);
  glDepthRange(0.25, 0.5);
  glFrontFace(GL_CW);
  for (const GLenum cap : {GL_FRAMEBUFFER_SRGB, GL_PRIMITIVE_RESTART, GL_CLIP_DISTANCE2, GL_COLOR_LOGIC_OP}) glEnable(cap);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glPixelStorei(GL_UNPACK_ROW_LENGTH, 7);
  gl::Buffer pbo("engine pixel buffer", 256);
  glBindBuffer(GL_PIXEL_UNPACK_BUFFER, pbo.id());
  glBindBuffer(GL_PIXEL_PACK_BUFFER, pbo.id());

  const Light sun = overheadSun();
  shadows.render(surfaces.inputs(sun));
  gl::throwIfGlError("the test");

  const auto integer = [](GLenum e) { GLint v = 0; glGetIntegerv(e, &v); return v; };
  const auto indexed = [](GLenum e, GLuint i) { GLint v = 0; glGetIntegeri_v(e, i, &v); return v; };
  EXPECT_EQ(integer(GL_DRAW_FRAMEBUFFER_BINDING), GLint(fb.id()));
  std::array<GLint, 4> viewport{};
  glGetIntegerv(GL_VIEWPORT, viewport.data());
  EXPECT_EQ(viewport, (std::array<GLint, 4>{3, 4, 50, 60}));
  EXPECT_EQ(integer(GL_VERTEX_ARRAY_BINDING), GLint(vao.id()));
  EXPECT_EQ(integer(GL_CURRENT_PROGRAM), 0);
  EXPECT_TRUE(glIsEnabled(GL_BLEND));
  EXPECT_TRUE(glIsEnabled(GL_SCISSOR_TEST));
  EXPECT_TRUE(glIsEnabled(GL_CULL_FACE));
  EXPECT_FALSE(glIsEnabled(GL_DEPTH_TEST));
  EXPECT_FALSE(glIsEnabled(GL_DEPTH_CLAMP));
  EXPECT_EQ(integer(GL_DEPTH_FUNC), GL_GEQUAL);
  GLboolean depthMask = GL_TRUE;
  glGetBooleanv(GL_DEPTH_WRITEMASK, &depthMask);
  EXPECT_EQ(depthMask, GL_FALSE);
  std::array<GLboolean, 4> colorMask{};
  glGetBooleanv(GL_COLOR_WRITEMASK, colorMask.data());
  EXPECT_EQ(colorMask, (std::array<GLboolean, 4>{GL_TRUE, GL_FALSE, GL_TRUE, GL_FALSE}));
  EXPECT_EQ(integer(GL_CLIP_ORIGIN), GL_UPPER_LEFT);
  EXPECT_EQ(integer(GL_CLIP_DEPTH_MODE), GL_NEGATIVE_ONE_TO_ONE);
  EXPECT_EQ(indexed(GL_UNIFORM_BUFFER_BINDING, 1), GLint(ubo.id()));
  EXPECT_EQ(indexed(GL_UNIFORM_BUFFER_SIZE, 1), 128);
  EXPECT_EQ(indexed(GL_UNIFORM_BUFFER_BINDING, 0), 0);
  EXPECT_EQ(indexed(GL_SHADER_STORAGE_BUFFER_BINDING, 3), GLint(ssbo.id()));
  EXPECT_EQ(indexed(GL_SHADER_STORAGE_BUFFER_BINDING, 0), 0);
  EXPECT_EQ(indexed(GL_IMAGE_BINDING_NAME, 1), GLint(unit9.id()));
  EXPECT_EQ(indexed(GL_IMAGE_BINDING_NAME, 0), 0);
  EXPECT_EQ(integer(GL_ACTIVE_TEXTURE), GL_TEXTURE5);
  glActiveTexture(GL_TEXTURE9);
  EXPECT_EQ(integer(GL_TEXTURE_BINDING_2D), GLint(unit9.id()));
  glActiveTexture(GL_TEXTURE0);
  EXPECT_EQ(integer(GL_SAMPLER_BINDING), GLint(sampler.id()));
  EXPECT_EQ(integer(GL_TEXTURE_BINDING_2D), 0);
  EXPECT_EQ(integer(GL_TEXTURE_BINDING_2D_ARRAY), 0);
  std::array<GLdouble, 2> range{};
  glGetDoublev(GL_DEPTH_RANGE, range.data());
  EXPECT_EQ(range, (std::array<GLdouble, 2>{0.25, 0.5}));
  EXPECT_EQ(integer(GL_FRONT_FACE), GL_CW);
  for (const GLenum cap : {GL_FRAMEBUFFER_SRGB, GL_PRIMITIVE_RESTART, GL_CLIP_DISTANCE2, GL_COLOR_LOGIC_OP}) EXPECT_TRUE(glIsEnabled(cap)) << cap;
  EXPECT_EQ(integer(GL_PACK_ALIGNMENT), 1);
  EXPECT_EQ(integer(GL_UNPACK_ROW_LENGTH), 7);
  EXPECT_EQ(integer(GL_PIXEL_UNPACK_BUFFER_BINDING), GLint(pbo.id()));
  EXPECT_EQ(integer(GL_PIXEL_PACK_BUFFER_BINDING), GLint(pbo.id()));

  // Back to what the rest of the test binary expects.
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glBindVertexArray(0);
  glDisable(GL_BLEND);
  glDisable(GL_SCISSOR_TEST);
  glDisable(GL_CULL_FACE);
  glDepthMask(GL_TRUE);
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
  glBindSampler(0, 0);
  glBindImageTexture(1, 0, 0, GL_FALSE, 0, GL_READ_ONLY, GL_R32F);
  glActiveTexture(GL_TEXTURE0);
  glDepthRange(0.0, 1.0);
  glFrontFace(GL_CCW);
  for (const GLenum cap : {GL_FRAMEBUFFER_SRGB, GL_PRIMITIVE_RESTART, GL_CLIP_DISTANCE2, GL_COLOR_LOGIC_OP}) glDisable(cap);
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
  glBindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
  glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
}

TEST(ShadowsApi, ReleasesEveryObjectItMade) {
  glContext();
  const EngineScene scene;
  const EngineSurfaces surfaces;
  const int before = gl::liveObjectCount();
  {
    Shadows shadows;
    shadows.setTechnique(Technique("csm", "vssm").setMapSize(256));
    shadows.setCasters(std::span<const CasterMesh>(&scene.caster, 1));
    const Light sun = overheadSun();
    shadows.render(surfaces.inputs(sun));
    EXPECT_GT(gl::liveObjectCount(), before);
  }
  EXPECT_EQ(gl::liveObjectCount(), before);
}

TEST(ShadowsApi, NamesTheCallersMistakes) {
  glContext();
  const EngineScene scene;
  const EngineSurfaces surfaces;
  Shadows shadows;
  const Light sun = overheadSun();

  CasterMesh bad = scene.caster;
  bad.count = 30;  // 30 vertices from a buffer of 3
  std::string m = usageErrorFrom([&] { shadows.setCasters(std::span<const CasterMesh>(&bad, 1)); });
  EXPECT_NE(m.find("caster 0: vertices 0..29 lie beyond vertex buffer"), std::string::npos) << m;
  bad = scene.caster;
  bad.vertexBuffer = 424242;
  m = usageErrorFrom([&] { shadows.setCasters(std::span<const CasterMesh>(&bad, 1)); });
  EXPECT_NE(m.find("caster 0: vertexBuffer 424242 is not a GL buffer"), std::string::npos) << m;
  bad = scene.caster;
  bad.alphaTexture = surfaces.normal.id();
  m = usageErrorFrom([&] { shadows.setCasters(std::span<const CasterMesh>(&bad, 1)); });
  EXPECT_NE(m.find("needs a uvOffset"), std::string::npos) << m;

  shadows.setCasters(std::span<const CasterMesh>(&scene.caster, 1));
  std::vector<Light> tooMany(kMaxShadowedLights + 1, sun);
  ShadowFrameInputs in = surfaces.inputs(sun);
  in.lights = tooMany;
  m = usageErrorFrom([&] { shadows.render(in); });
  EXPECT_NE(m.find(fmt::format("{} lights given; at most {}", kMaxShadowedLights + 1, kMaxShadowedLights)),
            std::string::npos)
      << m;
  in = surfaces.inputs(sun);
  in.lights = {};
  m = usageErrorFrom([&] { shadows.render(in); });
  EXPECT_NE(m.find("no light (ShadowFrameInputs::lights is empty)"), std::string::npos) << m;
  in = surfaces.inputs(sun);
  in.surfaces.depth = 0;
  m = usageErrorFrom([&] { shadows.render(in); });
  EXPECT_NE(m.find("ShadowSurfaces::depth and ShadowSurfaces::position are both 0"), std::string::npos) << m;
  in = surfaces.inputs(sun);
  in.surfaces.depth = 31337;
  m = usageErrorFrom([&] { shadows.render(in); });
  EXPECT_NE(m.find("ShadowSurfaces::depth = 31337 is not a GL texture"), std::string::npos) << m;
  m = usageErrorFrom([&] { shadows.setTechnique(Technique("uniform", "pcf", {{"pcss.blockerSamples", "8"}})); });
  EXPECT_NE(m.find("unknown parameter 'pcss.blockerSamples'"), std::string::npos) << m;
  // A GL error the caller left behind is reported as the caller's.
  shadows.setTechnique(Technique("uniform", "hard").setMapSize(256));
  glBindTexture(0x1234, 0);
  try {
    shadows.render(surfaces.inputs(sun));
    ADD_FAILURE() << "a pending GL error went unreported";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("the caller's GL calls before Shadows::render"), std::string::npos) << e.what();
  }
}
