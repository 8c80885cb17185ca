// Penumbra::shadows inside an engine of its own, written from docs/embedding.md: a Z-up
// right-handed world, 24-byte vertices (position, normal), its own depth pre-pass and matrices
// (GL's default depth range, reversed-Z with an infinite far plane, orthographic, left-handed),
// a rotated box and a floating sphere over a ground. Each light's V is checked against an exact
// CPU ray cast of the same triangles from each pixel's centre: outside a 2-pixel band around
// shadow edges and silhouettes at most 0.1 % of the pixels may differ. The cases are the
// conventions engines use: receivers not given, the engine's GL state left unusual
// (glDepthRange(0, 0.5) and more), 16-bit indices, no normal texture, orthographic and
// left-handed cameras, a cascaded sun and a point light in one Shadows.
#include "EngineTruth.h"
#include "GlFixture.h"

#include "gl/Objects.h"

#include <penumbra/ImageIO.h>
#include <penumbra/Shadows.h>
#include <penumbra/ShadowsDebug.h>

#include <epoxy/gl.h>
#include <fmt/format.h>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <array>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

using namespace penumbra;
using namespace penumbra::test;
using namespace penumbra::test::engine;

namespace {

constexpr int kMapSize = 1024;
// At most this share of the compared pixels may differ from the ray cast.
constexpr double kMaxDifferingPct = 0.1;

// ---- the engine's GL side -------------------------------------------------------------------

constexpr const char* kVertex = R"(#version 450 core
layout(location = 0) in vec3 a_position;
layout(location = 0) uniform mat4 u_clipFromWorld;
layout(location = 1) uniform mat4 u_worldFromObject;
out vec3 v_ws;
void main() {
  v_ws = (u_worldFromObject * vec4(a_position, 1.0)).xyz;
  gl_Position = u_clipFromWorld * vec4(v_ws, 1.0);
}
)";
// The geometric normal, facing the camera (the engine's eye, or its view direction when
// orthographic: u_eye.w = 0).
constexpr const char* kFragment = R"(#version 450 core
in vec3 v_ws;
layout(location = 2) uniform vec4 u_eye;
layout(location = 0) out vec4 o_normal;
void main() {
  vec3 g = normalize(cross(dFdx(v_ws), dFdy(v_ws)));
  vec3 toEye = u_eye.w > 0.5 ? u_eye.xyz - v_ws : -u_eye.xyz;
  if (dot(g, toEye) < 0.0) g = -g;
  o_normal = vec4(g, 0.0);
}
)";

/// How the engine renders its depth: its matrices and its depth convention.
struct EngineCamera {
  std::string name;
  glm::mat4 view{1.0f}, proj{1.0f};
  DepthConvention depth = DepthConvention::NegativeOneToOne;
  bool reversed = false;             ///< depth test GREATER, cleared to 0
  glm::vec2 ndcDepths{-1.0f, 0.0f};  ///< two ndc depths inside the volume, for the ray cast's rays
  glm::vec4 eye{0.0f};               ///< xyz + w = 1: its position; w = 0: the direction it looks
};

const glm::vec3 kEye(5.5f, -7.0f, 4.5f), kTarget(0.3f, -0.2f, 0.7f), kUp(0, 0, 1);

EngineCamera glDefaultCamera() {
  return {"GL default", glm::lookAt(kEye, kTarget, kUp), glm::perspective(0.75f, float(kW) / kH, 0.1f, 60.0f),
          DepthConvention::NegativeOneToOne, false, {-1.0f, 0.0f}, glm::vec4(kEye, 1.0f)};
}

EngineCamera reversedInfiniteCamera() {
  const float f = 1.0f / std::tan(0.5f * 0.75f), nearM = 0.1f;
  glm::mat4 p(0.0f);
  p[0][0] = f * kH / kW;
  p[1][1] = f;
  p[2][3] = -1.0f;
  p[3][2] = nearM;
  return {"reversed-Z, infinite far", glm::lookAt(kEye, kTarget, kUp), p, DepthConvention::ZeroToOne, true, {1.0f, 0.5f},
          glm::vec4(kEye, 1.0f)};
}

EngineCamera orthographicCamera() {
  const glm::vec3 forward = glm::normalize(kTarget - kEye);
  return {"orthographic", glm::lookAt(kEye, kTarget, kUp), glm::ortho(-6.0f, 6.0f, -4.5f, 4.5f, -5.0f, 40.0f),
          DepthConvention::NegativeOneToOne, false, {-1.0f, 1.0f}, glm::vec4(forward, 0.0f)};
}

EngineCamera leftHandedCamera() {
  return {"left-handed", glm::lookAtLH(kEye, kTarget, kUp), glm::perspectiveLH_ZO(0.75f, float(kW) / kH, 0.1f, 60.0f),
          DepthConvention::ZeroToOne, false, {0.0f, 0.5f}, glm::vec4(kEye, 1.0f)};
}

/// The engine on the GPU: its buffers (16- or 32-bit indices), its depth and normal targets.
struct Engine {
  std::vector<EngineMesh> meshes = engineScene();
  gl::Buffer vertices, indices;
  std::vector<CasterMesh> casters;
  gl::Texture depth{"engine depth", {GL_TEXTURE_2D, GL_DEPTH_COMPONENT32F, kW, kH, 1, 1}};
  gl::Texture normal{"engine normal", {GL_TEXTURE_2D, GL_RGBA16F, kW, kH, 1, 1}};
  gl::Framebuffer fb{"engine pre-pass"};
  gl::VertexArray vao{"engine vao"};
  GLuint program = 0;
  IndexType indexType;
  std::vector<uint32_t> firstIndex, baseVertex;

  explicit Engine(IndexType type) : indexType(type) {
    std::vector<EngineVertex> allVertices;
    std::vector<uint32_t> all32;
    for (const EngineMesh& m : meshes) {
      firstIndex.push_back(static_cast<uint32_t>(all32.size()));
      baseVertex.push_back(static_cast<uint32_t>(allVertices.size()));
      allVertices.insert(allVertices.end(), m.vertices.begin(), m.vertices.end());
      all32.insert(all32.end(), m.indices.begin(), m.indices.end());
    }
    vertices = gl::Buffer("engine vertices", allVertices.size() * sizeof(EngineVertex), allVertices.data(), 0);
    if (type == IndexType::UInt16) {
      const std::vector<uint16_t> all16(all32.begin(), all32.end());
      indices = gl::Buffer("engine indices", all16.size() * sizeof(uint16_t), all16.data(), 0);
    } else {
      indices = gl::Buffer("engine indices", all32.size() * sizeof(uint32_t), all32.data(), 0);
    }
    for (size_t m = 0; m < meshes.size(); ++m) {
      if (!meshes[m].caster) continue;
      CasterMesh c;
      c.vertexBuffer = vertices.id();
      c.stride = sizeof(EngineVertex);
      c.positionOffset = offsetof(EngineVertex, position);
      c.indexBuffer = indices.id();
      c.indexType = type;
      c.firstIndex = firstIndex[m];
      c.count = static_cast<uint32_t>(meshes[m].indices.size());
      c.baseVertex = static_cast<int32_t>(baseVertex[m]);
      c.worldFromObject = meshes[m].worldFromObject;
      for (const EngineVertex& v : meshes[m].vertices) c.objectBounds.extend(v.position);
      casters.push_back(c);
    }
    fb.attach(GL_COLOR_ATTACHMENT0, normal);
    fb.attach(GL_DEPTH_ATTACHMENT, depth);
    fb.finish(1);
    glVertexArrayVertexBuffer(vao.id(), 0, vertices.id(), 0, sizeof(EngineVertex));
    glVertexArrayElementBuffer(vao.id(), indices.id());
    glEnableVertexArrayAttrib(vao.id(), 0);
    glVertexArrayAttribFormat(vao.id(), 0, 3, GL_FLOAT, GL_FALSE, offsetof(EngineVertex, position));
    glVertexArrayAttribBinding(vao.id(), 0, 0);
    program = link();
  }
  ~Engine() { glDeleteProgram(program); }
  Engine(const Engine&) = delete;
  Engine& operator=(const Engine&) = delete;

  static GLuint link() {
    const GLuint p = glCreateProgram();
    for (const auto& [type, text] : {std::pair{GL_VERTEX_SHADER, kVertex}, std::pair{GL_FRAGMENT_SHADER, kFragment}}) {
      const GLuint s = glCreateShader(type);
      glShaderSource(s, 1, &text, nullptr);
      glCompileShader(s);
      glAttachShader(p, s);
      glDeleteShader(s);
    }
    glLinkProgram(p);
    GLint ok = 0;
    glGetProgramiv(p, GL_LINK_STATUS, &ok);
    EXPECT_TRUE(ok) << "the engine's pre-pass program";
    return p;
  }

  /// The engine's depth pre-pass with its camera, in its own conventions; puts back the clip
  /// control it found and leaves the rest at GL's defaults.
  void prepass(const EngineCamera& cam) {
    GLint origin = GL_LOWER_LEFT, depthMode = GL_NEGATIVE_ONE_TO_ONE;
    glGetIntegerv(GL_CLIP_ORIGIN, &origin);
    glGetIntegerv(GL_CLIP_DEPTH_MODE, &depthMode);
    glClipControl(GL_LOWER_LEFT, cam.depth == DepthConvention::ZeroToOne ? GL_ZERO_TO_ONE : GL_NEGATIVE_ONE_TO_ONE);
    glBindFramebuffer(GL_FRAMEBUFFER, fb.id());
    glViewport(0, 0, kW, kH);
    const float zero[4] = {0, 0, 0, 0}, clearDepth = cam.reversed ? 0.0f : 1.0f;
    glClearNamedFramebufferfv(fb.id(), GL_COLOR, 0, zero);
    glClearNamedFramebufferfv(fb.id(), GL_DEPTH, 0, &clearDepth);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(cam.reversed ? GL_GREATER : GL_LESS);
    glUseProgram(program);
    glBindVertexArray(vao.id());
    const glm::mat4 clipFromWorld = cam.proj * cam.view;
    glProgramUniformMatrix4fv(program, 0, 1, GL_FALSE, glm::value_ptr(clipFromWorld));
    glProgramUniform4fv(program, 2, 1, glm::value_ptr(cam.eye));
    for (size_t m = 0; m < meshes.size(); ++m) {
      glProgramUniformMatrix4fv(program, 1, 1, GL_FALSE, glm::value_ptr(meshes[m].worldFromObject));
      const uint32_t bytes = indexBytes(indexType);
      glDrawElementsBaseVertex(GL_TRIANGLES, static_cast<GLsizei>(meshes[m].indices.size()),
                               indexType == IndexType::UInt16 ? GL_UNSIGNED_SHORT : GL_UNSIGNED_INT,
                               reinterpret_cast<const void*>(static_cast<uintptr_t>(firstIndex[m]) * bytes),
                               static_cast<GLint>(baseVertex[m]));
    }
    glBindVertexArray(0);
    glUseProgram(0);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glDisable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glClipControl(static_cast<GLenum>(origin), static_cast<GLenum>(depthMode));
  }
};

std::vector<Light> sunAndPoint() {
  Light sun;
  sun.id = 10;
  sun.direction = glm::normalize(glm::vec3(-0.45f, -0.7f, -0.75f));
  Light lamp;
  lamp.id = 20;
  lamp.type = LightType::Point;
  lamp.position = {-2.6f, -1.4f, 3.4f};
  return {sun, lamp};
}

/// Every GL state value an engine's own passes could depend on and Penumbra's could touch, by name.
std::vector<std::pair<std::string, double>> glStateSnapshot() {
  std::vector<std::pair<std::string, double>> out;
  const auto ints = [&](const char* name, GLenum e, int n) {
    std::array<GLint, 4> v{};
    glGetIntegerv(e, v.data());
    for (int i = 0; i < n; ++i) out.emplace_back(fmt::format("{}[{}]", name, i), v[static_cast<size_t>(i)]);
  };
  const auto floats = [&](const char* name, GLenum e, int n) {
    std::array<GLfloat, 4> v{};
    glGetFloatv(e, v.data());
    for (int i = 0; i < n; ++i) out.emplace_back(fmt::format("{}[{}]", name, i), v[static_cast<size_t>(i)]);
  };
  const auto indexed = [&](const char* name, GLenum e, GLuint count) {
    for (GLuint i = 0; i < count; ++i) {
      GLint64 v = 0;
      glGetInteger64i_v(e, i, &v);
      out.emplace_back(fmt::format("{}[{}]", name, i), static_cast<double>(v));
    }
  };
  ints("draw framebuffer", GL_DRAW_FRAMEBUFFER_BINDING, 1);
  ints("read framebuffer", GL_READ_FRAMEBUFFER_BINDING, 1);
  ints("program", GL_CURRENT_PROGRAM, 1);
  ints("vertex array", GL_VERTEX_ARRAY_BINDING, 1);
  ints("active texture", GL_ACTIVE_TEXTURE, 1);
  ints("viewport", GL_VIEWPORT, 4);
  ints("scissor box", GL_SCISSOR_BOX, 4);
  floats("depth range", GL_DEPTH_RANGE, 2);
  ints("depth func", GL_DEPTH_FUNC, 1);
  ints("depth mask", GL_DEPTH_WRITEMASK, 1);
  ints("colour mask", GL_COLOR_WRITEMASK, 4);
  ints("cull face mode", GL_CULL_FACE_MODE, 1);
  ints("front face", GL_FRONT_FACE, 1);
  ints("polygon mode", GL_POLYGON_MODE, 2);
  floats("polygon offset factor", GL_POLYGON_OFFSET_FACTOR, 1);
  floats("polygon offset units", GL_POLYGON_OFFSET_UNITS, 1);
  ints("blend src", GL_BLEND_SRC_RGB, 1);
  ints("blend dst", GL_BLEND_DST_RGB, 1);
  ints("stencil func", GL_STENCIL_FUNC, 1);
  ints("clip origin", GL_CLIP_ORIGIN, 1);
  ints("clip depth mode", GL_CLIP_DEPTH_MODE, 1);
  ints("primitive restart index", GL_PRIMITIVE_RESTART_INDEX, 1);
  ints("logic op", GL_LOGIC_OP_MODE, 1);
  for (const auto& [name, e] : {std::pair{"pack alignment", GL_PACK_ALIGNMENT}, {"pack row length", GL_PACK_ROW_LENGTH},
                                {"pack image height", GL_PACK_IMAGE_HEIGHT}, {"pack skip pixels", GL_PACK_SKIP_PIXELS},
                                {"pack skip rows", GL_PACK_SKIP_ROWS}, {"pack skip images", GL_PACK_SKIP_IMAGES},
                                {"unpack alignment", GL_UNPACK_ALIGNMENT}, {"unpack row length", GL_UNPACK_ROW_LENGTH},
                                {"unpack image height", GL_UNPACK_IMAGE_HEIGHT}, {"unpack skip pixels", GL_UNPACK_SKIP_PIXELS},
                                {"unpack skip rows", GL_UNPACK_SKIP_ROWS}, {"unpack skip images", GL_UNPACK_SKIP_IMAGES},
                                {"pixel pack buffer", GL_PIXEL_PACK_BUFFER_BINDING}, {"pixel unpack buffer", GL_PIXEL_UNPACK_BUFFER_BINDING},
                                {"uniform buffer", GL_UNIFORM_BUFFER_BINDING}, {"storage buffer", GL_SHADER_STORAGE_BUFFER_BINDING}})
    ints(name, e, 1);
  for (const auto& [name, cap] : {std::pair{"blend", GL_BLEND}, {"scissor test", GL_SCISSOR_TEST}, {"stencil test", GL_STENCIL_TEST},
                                  {"polygon offset fill", GL_POLYGON_OFFSET_FILL}, {"rasterizer discard", GL_RASTERIZER_DISCARD},
                                  {"colour logic op", GL_COLOR_LOGIC_OP}, {"primitive restart", GL_PRIMITIVE_RESTART},
                                  {"primitive restart fixed index", GL_PRIMITIVE_RESTART_FIXED_INDEX},
                                  {"framebuffer sRGB", GL_FRAMEBUFFER_SRGB}, {"alpha to coverage", GL_SAMPLE_ALPHA_TO_COVERAGE},
                                  {"depth test", GL_DEPTH_TEST}, {"depth clamp", GL_DEPTH_CLAMP}, {"cull face", GL_CULL_FACE},
                                  {"dither", GL_DITHER}})
    out.emplace_back(name, glIsEnabled(cap));
  for (GLuint i = 0; i < 8; ++i) out.emplace_back(fmt::format("clip distance {}", i), glIsEnabled(GL_CLIP_DISTANCE0 + i));
  indexed("uniform buffer", GL_UNIFORM_BUFFER_BINDING, 4);
  indexed("uniform buffer start", GL_UNIFORM_BUFFER_START, 4);
  indexed("uniform buffer size", GL_UNIFORM_BUFFER_SIZE, 4);
  indexed("storage buffer", GL_SHADER_STORAGE_BUFFER_BINDING, 8);
  indexed("image unit", GL_IMAGE_BINDING_NAME, 4);
  GLint active = 0;
  glGetIntegerv(GL_ACTIVE_TEXTURE, &active);
  for (GLuint u = 0; u < 16; ++u) {
    glActiveTexture(GL_TEXTURE0 + u);
    for (const auto& [name, e] : {std::pair{"2D", GL_TEXTURE_BINDING_2D}, {"2D array", GL_TEXTURE_BINDING_2D_ARRAY},
                                  {"3D", GL_TEXTURE_BINDING_3D}, {"sampler", GL_SAMPLER_BINDING}}) {
      GLint v = 0;
      glGetIntegerv(e, &v);
      out.emplace_back(fmt::format("texture unit {} {}", u, name), v);
    }
  }
  glActiveTexture(static_cast<GLenum>(active));
  return out;
}

struct Case {
  EngineCamera camera;
  IndexType indices = IndexType::UInt32;
  bool normals = true;
  bool receiversGiven = true;
  Technique technique = Technique("uniform", "hard").setMapSize(kMapSize);
  std::vector<Light> lights = sunAndPoint();
  /// Leaves the engine's GL state as it wants before render() (nothing by default).
  std::function<void()> engineState = [] {};
  /// Compares every value of glStateSnapshot() before and after render().
  bool checkGlState = false;
};

/// Runs the case and checks each light's V against the ray cast; returns the agreements.
std::vector<Agreement> run(const Case& c, const std::string& what) {
  glContext();
  Engine engine(c.indices);
  engine.prepass(c.camera);
  Shadows shadows;
  shadows.setTechnique(c.technique);
  const Aabb groundBounds{{-9, -9, 0}, {9, 9, 0}};
  if (c.receiversGiven)
    shadows.setCasters(engine.casters, {.bounds = std::span<const Aabb>(&groundBounds, 1), .complete = true});
  else
    shadows.setCasters(engine.casters);
  ShadowFrameInputs in;
  in.camera = ShadowCamera::fromMatrices(c.camera.view, c.camera.proj, c.camera.depth);
  in.surfaces = {.width = kW, .height = kH, .depth = engine.depth.id(), .normal = c.normals ? engine.normal.id() : 0u};
  in.lights = c.lights;
  c.engineState();
  const auto before = glStateSnapshot();
  shadows.render(in);
  if (c.checkGlState) {
    const auto after = glStateSnapshot();
    size_t differ = 0;
    for (size_t i = 0; i < before.size(); ++i)
      if (before[i].second != after[i].second) {
        ++differ;
        ADD_FAILURE() << what << ": " << before[i].first << " was " << before[i].second << ", is " << after[i].second;
      }
    std::printf("  %s: %zu of %zu GL state values differ after render()\n", what.c_str(), differ, before.size());
  }
  const Truth truth = rayCast(engine.meshes, c.camera.proj * c.camera.view, c.camera.ndcDepths, c.lights);
  std::vector<Agreement> out;
  for (size_t l = 0; l < c.lights.size(); ++l) {
    const std::vector<float> v = shadows.readVisibility(l);
    if (const char* dir = std::getenv("PENUMBRA_TEST_ARTIFACTS")) {  // V | the ray cast's V, for a person to look at
      std::vector<uint8_t> rgba(static_cast<size_t>(2 * kW * kH) * 4, 255);
      for (int y = 0; y < kH; ++y)
        for (int x = 0; x < 2 * kW; ++x) {
          const size_t i = static_cast<size_t>(y) * kW + static_cast<size_t>(x % kW);
          const float value = truth.object[i] < 0 ? 0.5f : (x < kW ? v[i] : truth.v[l][i]);
          const size_t o = (static_cast<size_t>(kH - 1 - y) * 2 * kW + static_cast<size_t>(x)) * 4;
          rgba[o] = rgba[o + 1] = rgba[o + 2] = static_cast<uint8_t>(value * 255.0f);
        }
      std::string stem = what;
      for (char& ch : stem)
        if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '-';
      writePng(std::filesystem::path(dir) / fmt::format("engine-{}-light{}.png", stem, l), 2 * kW, kH, rgba);
    }
    const Agreement a = compare(v, truth, l);
    std::printf("  %-34s light %zu (%s): %zu pixels compared, %zu shadowed, %zu differ (%.3f %%)\n", what.c_str(), l,
                lightTypeName(c.lights[l].type), a.compared, a.shadowed, a.differing, a.differingPct());
    EXPECT_LE(a.differingPct(), kMaxDifferingPct) << what << ", light " << l;
    EXPECT_GT(a.shadowed, a.compared / 100) << what << ", light " << l << ": too few shadowed pixels to mean anything";
    EXPECT_GT(a.compared, static_cast<size_t>(kW * kH / 3)) << what << ", light " << l;
    out.push_back(a);
  }
  return out;
}

}  // namespace

TEST(Engine, ReceiversNotGiven) {
  Case c;
  c.camera = glDefaultCamera();
  c.receiversGiven = false;  // the ground is neither a caster nor given: measured from the depth
  run(c, "receivers not given");
}

// The engine's state when it calls render(): every switch a shadow pass could trip over set the
// wrong way. V is still right, and every one of those values comes back.
TEST(Engine, UnusualGlStateOfTheEngine) {
  glContext();
  Case c;
  c.camera = reversedInfiniteCamera();
  gl::Texture scratch{"engine scratch", {GL_TEXTURE_2D, GL_RGBA8, 4, 4, 1, 1}};
  gl::Buffer pixels{"engine pixel buffer", 1024};
  c.engineState = [&] {
    glDepthRange(0.0, 0.5);
    glEnable(GL_BLEND);
    glBlendFunc(GL_ZERO, GL_ONE);
    glEnable(GL_SCISSOR_TEST);
    glScissor(0, 0, 3, 3);
    glEnable(GL_CULL_FACE);
    glCullFace(GL_FRONT_AND_BACK);
    glFrontFace(GL_CW);
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    glDepthMask(GL_FALSE);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_NEVER);
    glEnable(GL_POLYGON_OFFSET_FILL);
    glPolygonOffset(50.0f, 50.0f);
    glEnable(GL_STENCIL_TEST);
    glStencilFunc(GL_NEVER, 0, 0xff);
    glClipControl(GL_UPPER_LEFT, GL_ZERO_TO_ONE);
    glEnable(GL_PRIMITIVE_RESTART);
    glPrimitiveRestartIndex(0);
    glEnable(GL_FRAMEBUFFER_SRGB);
    glEnable(GL_CLIP_DISTANCE0);
    glEnable(GL_COLOR_LOGIC_OP);
    glLogicOp(GL_CLEAR);
    glPolygonMode(GL_FRONT_AND_BACK, GL_LINE);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glPixelStorei(GL_UNPACK_ROW_LENGTH, 3);
    glPixelStorei(GL_PACK_SKIP_ROWS, 2);
    glBindBuffer(GL_PIXEL_UNPACK_BUFFER, pixels.id());
    glBindBuffer(GL_PIXEL_PACK_BUFFER, pixels.id());
    glBindTextureUnit(0, scratch.id());
  };
  c.checkGlState = true;
  run(c, "glDepthRange(0, 0.5) and more");
  // Back to the GL defaults the rest of the binary expects.
  glDepthRange(0.0, 1.0);
  glDisable(GL_BLEND);
  glBlendFunc(GL_ONE, GL_ZERO);
  glDisable(GL_SCISSOR_TEST);
  glDisable(GL_CULL_FACE);
  glCullFace(GL_BACK);
  glFrontFace(GL_CCW);
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  glDepthMask(GL_TRUE);
  glDisable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDisable(GL_POLYGON_OFFSET_FILL);
  glPolygonOffset(0.0f, 0.0f);
  glDisable(GL_STENCIL_TEST);
  glStencilFunc(GL_ALWAYS, 0, 0xff);
  glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
  glDisable(GL_PRIMITIVE_RESTART);
  glDisable(GL_FRAMEBUFFER_SRGB);
  glDisable(GL_CLIP_DISTANCE0);
  glDisable(GL_COLOR_LOGIC_OP);
  glLogicOp(GL_COPY);
  glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
  glPixelStorei(GL_PACK_SKIP_ROWS, 0);
  glBindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
  glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
  glBindTextureUnit(0, 0);
}

TEST(Engine, SixteenBitIndices) {
  Case c;
  c.camera = glDefaultCamera();
  c.indices = IndexType::UInt16;
  run(c, "16-bit indices");
}

TEST(Engine, NoNormalTexture) {
  Case c;
  c.camera = reversedInfiniteCamera();
  c.normals = false;  // normals reconstructed from the depth
  run(c, "no normal texture");
}

TEST(Engine, OrthographicCamera) {
  Case c;
  c.camera = orthographicCamera();
  run(c, "orthographic camera");
}

TEST(Engine, LeftHandedCamera) {
  Case c;
  c.camera = leftHandedCamera();
  run(c, "left-handed camera");
}

// One Shadows: the sun's cascades and the lamp's cube, the lamp naming its own projection.
TEST(Engine, CascadedSunAndPointLightInOneShadows) {
  Case c;
  c.camera = glDefaultCamera();
  c.technique = Technique("csm", "hard").setMapSize(kMapSize);
  c.lights[1].shadow.projection = "uniform";
  c.receiversGiven = false;  // the cascades fit the ground the camera sees, measured
  run(c, "csm sun + point light");
}
