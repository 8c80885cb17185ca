// A small engine that takes its shadows from Penumbra (docs/embedding.md).
//
// The engine owns everything a real one owns: its OpenGL context (headless EGL here), its
// meshes in its own buffers, its depth pre-pass (standard depth, glm::perspective) with a
// normal attachment, and its forward lit pass with its own shaders. Penumbra gets the camera's
// matrices, the depth and normal textures, the light and the caster buffers, and hands back a
// visibility texture that the lit pass samples at gl_FragCoord.
//
//   penumbra_example_engine [--scene NAME|FILE] [--projection ID] [--filter ID] [--set key=value]...
//                           [--size WxH] [--shadow-map N] [--out FILE.png]
//
// The scene comes from Penumbra's scene floor (built-in scenes, scene files, glTF/OBJ) only
// because that is the quickest way to get geometry here; textures are ignored.
#include <penumbra/Error.h>
#include <penumbra/ImageIO.h>
#include <penumbra/SceneIO.h>
#include <penumbra/Shadows.h>

#include <epoxy/egl.h>
#include <epoxy/gl.h>
#include <glm/gtc/matrix_inverse.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <cmath>
#include <cstddef>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace {

struct Options {
  std::string scene = "boxes", projection, filter, out = "example.png";
  std::vector<std::pair<std::string, std::string>> params;
  int width = 640, height = 360, mapSize = 2048;
};

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const auto next = [&]() -> std::string {
      if (i + 1 >= argc) throw std::runtime_error(a + " needs a value");
      return argv[++i];
    };
    if (a == "--scene") o.scene = next();
    else if (a == "--projection") o.projection = next();
    else if (a == "--filter") o.filter = next();
    else if (a == "--out") o.out = next();
    else if (a == "--shadow-map") o.mapSize = std::stoi(next());
    else if (a == "--size") {
      const std::string s = next();
      if (std::sscanf(s.c_str(), "%dx%d", &o.width, &o.height) != 2) throw std::runtime_error("--size wants WxH");
    } else if (a == "--set") {
      const std::string kv = next();
      const size_t eq = kv.find('=');
      if (eq == std::string::npos) throw std::runtime_error("--set wants key=value");
      o.params.emplace_back(kv.substr(0, eq), kv.substr(eq + 1));
    } else {
      throw std::runtime_error("unknown option " + a);
    }
  }
  return o;
}

// ---- the engine's context: EGL on Mesa's surfaceless platform --------------------------------
struct EglContext {
  EGLDisplay display = EGL_NO_DISPLAY;
  EGLContext context = EGL_NO_CONTEXT;
  EglContext() {
    display = eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    if (display == EGL_NO_DISPLAY || !eglInitialize(display, nullptr, nullptr) || !eglBindAPI(EGL_OPENGL_API))
      throw std::runtime_error("no EGL surfaceless display with desktop OpenGL");
    const EGLint attribs[] = {EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 5, EGL_CONTEXT_OPENGL_PROFILE_MASK,
                              EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
    context = eglCreateContext(display, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attribs);
    if (context == EGL_NO_CONTEXT || !eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context))
      throw std::runtime_error("no OpenGL 4.5 core context");
  }
  ~EglContext() {
    eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(display, context);
    eglTerminate(display);
  }
};

// ---- the engine's shaders ---------------------------------------------------------------------
constexpr const char* kVertex = R"(#version 450 core
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
layout(location = 0) uniform mat4 u_clipFromWorld;
layout(location = 1) uniform mat4 u_worldFromObject;
layout(location = 2) uniform mat4 u_normalFromObject;
out vec3 v_ws;
out vec3 v_normal;
void main() {
  vec4 ws = u_worldFromObject * vec4(a_position, 1.0);
  v_ws = ws.xyz;
  v_normal = mat3(u_normalFromObject) * a_normal;
  gl_Position = u_clipFromWorld * ws;
}
)";

// Depth pre-pass: depth, and the geometric normal (the triangle's plane) turned toward the camera.
constexpr const char* kPrepassFragment = R"(#version 450 core
in vec3 v_ws;
in vec3 v_normal;
layout(location = 3) uniform vec3 u_cameraPosition;
layout(location = 0) out vec4 o_normal;
void main() {
  vec3 g = normalize(cross(dFdx(v_ws), dFdy(v_ws)));
  if (dot(g, u_cameraPosition - v_ws) < 0.0) g = -g;
  o_normal = vec4(g, 0.0);
}
)";

// Forward lit pass: ambient + V · (Lambert + Blinn-Phong), a filmic tone map, sRGB. V is
// Penumbra's, read at this pixel.
constexpr const char* kLitFragment = R"(#version 450 core
in vec3 v_ws;
in vec3 v_normal;
layout(location = 3) uniform vec3 u_cameraPosition;
layout(location = 4) uniform vec3 u_albedo;
layout(location = 5) uniform vec4 u_lightDirection;  // w: 0 = sun, 1 = spot, 2 = point
layout(location = 6) uniform vec4 u_lightPosition;   // w: unused
layout(location = 9) uniform vec4 u_lightCone;       // x: cos outer, y: cos inner half angle, z: range (0 = none)
layout(location = 7) uniform vec3 u_radiance;
layout(location = 8) uniform vec3 u_ambient;
layout(binding = 0) uniform sampler2D s_visibility;
layout(location = 0) out vec4 o_color;
vec3 aces(vec3 x) { return clamp((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0); }
vec3 srgb(vec3 c) { return mix(12.92 * c, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(vec3(0.0031308), c)); }
void main() {
  float v = texelFetch(s_visibility, ivec2(gl_FragCoord.xy), 0).r;
  vec3 toCamera = u_cameraPosition - v_ws;
  vec3 g = normalize(cross(dFdx(v_ws), dFdy(v_ws)));
  if (dot(g, toCamera) < 0.0) g = -g;
  vec3 n = dot(v_normal, v_normal) > 0.0 ? normalize(v_normal) : g;  // a mesh without normals: flat
  if (dot(n, g) < 0.0) n = -n;
  bool positional = u_lightDirection.w > 0.5, spot = abs(u_lightDirection.w - 1.0) < 0.5;
  vec3 l = positional ? normalize(u_lightPosition.xyz - v_ws) : -u_lightDirection.xyz;
  vec3 radiance = u_radiance;
  if (positional) {
    vec3 d = u_lightPosition.xyz - v_ws;
    float falloff = 1.0;
    if (u_lightCone.z > 0.0) {  // the range window (1 - (d/range)^4)^2
      float x = length(d) / u_lightCone.z;
      float w = clamp(1.0 - x * x * x * x, 0.0, 1.0);
      falloff *= w * w;
    }
    if (spot) falloff *= smoothstep(u_lightCone.x, u_lightCone.y, dot(-l, u_lightDirection.xyz));
    radiance *= falloff / max(dot(d, d), 1e-4);
  }
  vec3 h = normalize(l + normalize(toCamera));
  float NoL = max(dot(n, l), 0.0);
  float specular = 0.25 * pow(max(dot(n, h), 0.0), 48.0) * step(0.0, NoL);
  vec3 hdr = u_ambient * u_albedo + v * (u_albedo * NoL + specular) * radiance;
  o_color = vec4(srgb(aces(hdr)), 1.0);
}
)";

// The sky behind everything, as a full-screen triangle.
constexpr const char* kSkyVertex = R"(#version 450 core
void main() { gl_Position = vec4(vec2((gl_VertexID << 1) & 2, gl_VertexID & 2) * 2.0 - 1.0, 0.0, 1.0); }
)";
constexpr const char* kSkyFragment = R"(#version 450 core
layout(location = 0) uniform float u_height;
layout(location = 0) out vec4 o_color;
void main() { o_color = vec4(mix(vec3(0.55, 0.6, 0.65), vec3(0.25, 0.4, 0.65), floor(gl_FragCoord.y) / u_height), 1.0); }
)";

GLuint compile(const char* vertex, const char* fragment) {
  const auto stage = [](GLenum type, const char* text) {
    const GLuint s = glCreateShader(type);
    glShaderSource(s, 1, &text, nullptr);
    glCompileShader(s);
    GLint ok = 0;
    glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
    if (!ok) {
      char log[2048];
      glGetShaderInfoLog(s, sizeof(log), nullptr, log);
      throw std::runtime_error(std::string("shader: ") + log);
    }
    return s;
  };
  const GLuint p = glCreateProgram(), vs = stage(GL_VERTEX_SHADER, vertex), fs = stage(GL_FRAGMENT_SHADER, fragment);
  glAttachShader(p, vs);
  glAttachShader(p, fs);
  glLinkProgram(p);
  glDeleteShader(vs);
  glDeleteShader(fs);
  GLint ok = 0;
  glGetProgramiv(p, GL_LINK_STATUS, &ok);
  if (!ok) throw std::runtime_error("program does not link");
  return p;
}

GLuint texture2D(GLenum format, int w, int h) {
  GLuint t = 0;
  glCreateTextures(GL_TEXTURE_2D, 1, &t);
  glTextureStorage2D(t, 1, format, w, h);
  return t;
}

// ---- the engine's scene on the GPU --------------------------------------------------------------
struct EngineVertex {
  glm::vec3 position, normal;
};

struct EngineObject {
  GLuint firstIndex = 0, indexCount = 0;
  GLint baseVertex = 0;
  glm::mat4 worldFromObject{1.0f};
  glm::vec3 albedo{0.8f};
  bool castsShadow = true;
  penumbra::Aabb objectBounds;
};

// ---- Penumbra: everything the engine does for its shadows ------------------------------------
// The technique, the casters (the engine's own buffers) and where shadows may land, then one frame
// against the engine's camera, depth and normals. shadows.visibilityTexture() then holds V.
void shadowLight(penumbra::Shadows& shadows, const Options& o, const penumbra::Scene& scene, const std::vector<EngineObject>& objects,
                 GLuint vbo, GLuint ibo, const glm::mat4& view, const glm::mat4& proj, GLuint depth, GLuint normal,
                 const penumbra::Light& light) {
  penumbra::Technique technique(o.projection.empty() ? scene.shadow.projection : o.projection,
                                o.filter.empty() ? scene.shadow.filter : o.filter, o.params);
  technique.setMapSize(o.mapSize);
  shadows.setTechnique(technique);
  std::vector<penumbra::CasterMesh> casters;
  std::vector<penumbra::Aabb> receivers;
  for (const EngineObject& e : objects) {
    if (!e.castsShadow) {
      receivers.push_back(e.objectBounds.transformed(e.worldFromObject));
      continue;
    }
    penumbra::CasterMesh c;
    c.vertexBuffer = vbo;
    c.stride = sizeof(EngineVertex);
    c.positionOffset = offsetof(EngineVertex, position);
    c.indexBuffer = ibo;
    c.firstIndex = e.firstIndex;
    c.count = e.indexCount;
    c.baseVertex = e.baseVertex;
    c.worldFromObject = e.worldFromObject;
    c.objectBounds = e.objectBounds;
    casters.push_back(c);
  }
  // Every object of the scene is here: the casters and the ground that only receives.
  shadows.setCasters(casters, {.bounds = receivers, .complete = true});
  penumbra::ShadowFrameInputs in;
  in.camera = penumbra::ShadowCamera::fromMatrices(view, proj, penumbra::DepthConvention::NegativeOneToOne);
  in.surfaces = {.width = o.width, .height = o.height, .depth = depth, .normal = normal};
  in.lights = std::span<const penumbra::Light>(&light, 1);
  shadows.render(in);
}

int run(const Options& o) {
  const EglContext egl;
  const penumbra::Scene scene = penumbra::loadScene(o.scene);
  const float aspect = static_cast<float>(o.width) / static_cast<float>(o.height);

  // Geometry: one vertex buffer and one index buffer for every mesh.
  std::vector<EngineVertex> vertices;
  std::vector<uint32_t> indices;
  std::vector<std::pair<GLuint, GLint>> meshStart;  // first index, base vertex
  for (const penumbra::Mesh& m : scene.meshes) {
    meshStart.emplace_back(static_cast<GLuint>(indices.size()), static_cast<GLint>(vertices.size()));
    for (size_t i = 0; i < m.positions.size(); ++i)  // a mesh without normals is shaded flat (a zero normal)
      vertices.push_back({m.positions[i], m.normals.empty() ? glm::vec3(0.0f) : m.normals[i]});
    indices.insert(indices.end(), m.indices.begin(), m.indices.end());
  }
  std::vector<EngineObject> objects;
  for (const penumbra::Object& obj : scene.objects) {
    const penumbra::Mesh& m = scene.meshes[obj.mesh];
    objects.push_back({meshStart[obj.mesh].first, static_cast<GLuint>(m.indices.size()), meshStart[obj.mesh].second,
                       obj.worldFromObject, scene.materials[obj.material].baseColor, obj.castsShadow, m.bounds()});
  }
  GLuint vbo = 0, ibo = 0, vao = 0;
  glCreateBuffers(1, &vbo);
  glNamedBufferStorage(vbo, static_cast<GLsizeiptr>(vertices.size() * sizeof(EngineVertex)), vertices.data(), 0);
  glCreateBuffers(1, &ibo);
  glNamedBufferStorage(ibo, static_cast<GLsizeiptr>(indices.size() * sizeof(uint32_t)), indices.data(), 0);
  glCreateVertexArrays(1, &vao);
  glVertexArrayVertexBuffer(vao, 0, vbo, 0, sizeof(EngineVertex));
  glVertexArrayElementBuffer(vao, ibo);
  for (GLuint a = 0; a < 2; ++a) {
    glEnableVertexArrayAttrib(vao, a);
    glVertexArrayAttribFormat(vao, a, 3, GL_FLOAT, GL_FALSE, a * sizeof(glm::vec3));
    glVertexArrayAttribBinding(vao, a, 0);
  }

  // The camera, as any engine sets it up: GL's default depth range, a finite far plane.
  const penumbra::Camera& cam = scene.camera;
  const glm::mat4 view = glm::lookAt(cam.position, cam.target, cam.up);
  const glm::mat4 proj = glm::perspective(cam.fovYRad, aspect, cam.nearM, cam.farM);
  const glm::mat4 clipFromWorld = proj * view;

  // Depth pre-pass into the engine's own targets.
  const GLuint depth = texture2D(GL_DEPTH_COMPONENT32F, o.width, o.height);
  const GLuint normal = texture2D(GL_RGBA16F, o.width, o.height);
  const GLuint color = texture2D(GL_RGBA8, o.width, o.height);
  GLuint prepassFbo = 0, litFbo = 0;
  glCreateFramebuffers(1, &prepassFbo);
  glNamedFramebufferTexture(prepassFbo, GL_COLOR_ATTACHMENT0, normal, 0);
  glNamedFramebufferTexture(prepassFbo, GL_DEPTH_ATTACHMENT, depth, 0);
  glCreateFramebuffers(1, &litFbo);
  glNamedFramebufferTexture(litFbo, GL_COLOR_ATTACHMENT0, color, 0);
  glNamedFramebufferTexture(litFbo, GL_DEPTH_ATTACHMENT, depth, 0);
  const GLuint prepass = compile(kVertex, kPrepassFragment), lit = compile(kVertex, kLitFragment),
               sky = compile(kSkyVertex, kSkyFragment);
  const auto drawObjects = [&](GLuint program, bool withAlbedo) {
    glProgramUniformMatrix4fv(program, 0, 1, GL_FALSE, glm::value_ptr(clipFromWorld));
    glProgramUniform3fv(program, 3, 1, glm::value_ptr(cam.position));
    for (const EngineObject& e : objects) {
      glProgramUniformMatrix4fv(program, 1, 1, GL_FALSE, glm::value_ptr(e.worldFromObject));
      const glm::mat4 n(glm::inverseTranspose(glm::mat3(e.worldFromObject)));
      glProgramUniformMatrix4fv(program, 2, 1, GL_FALSE, glm::value_ptr(n));
      if (withAlbedo) glProgramUniform3fv(program, 4, 1, glm::value_ptr(e.albedo));
      glDrawElementsBaseVertex(GL_TRIANGLES, static_cast<GLsizei>(e.indexCount), GL_UNSIGNED_INT,
                               reinterpret_cast<const void*>(static_cast<uintptr_t>(e.firstIndex) * sizeof(uint32_t)), e.baseVertex);
    }
  };
  glViewport(0, 0, o.width, o.height);
  glBindVertexArray(vao);
  glBindFramebuffer(GL_FRAMEBUFFER, prepassFbo);
  const float zero[4] = {0, 0, 0, 0}, farDepth = 1.0f;
  glClearNamedFramebufferfv(prepassFbo, GL_COLOR, 0, zero);
  glClearNamedFramebufferfv(prepassFbo, GL_DEPTH, 0, &farDepth);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glUseProgram(prepass);
  drawObjects(prepass, false);

  // Penumbra: the engine's buffers as casters, its textures as the surfaces.
  penumbra::Shadows shadows;
  const penumbra::Light& light = scene.light();
  shadowLight(shadows, o, scene, objects, vbo, ibo, view, proj, depth, normal, light);

  // Forward lit pass over the pre-pass depth, V from Penumbra's texture.
  glBindFramebuffer(GL_FRAMEBUFFER, litFbo);
  glDisable(GL_DEPTH_TEST);
  glUseProgram(sky);
  glProgramUniform1f(sky, 0, static_cast<float>(o.height));
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LEQUAL);
  glDepthMask(GL_FALSE);
  glUseProgram(lit);
  const float kind = light.type == penumbra::LightType::Spot ? 1.0f : light.type == penumbra::LightType::Point ? 2.0f : 0.0f;
  const glm::vec3 dir = glm::normalize(light.direction);
  glProgramUniform4f(lit, 5, dir.x, dir.y, dir.z, kind);
  glProgramUniform4f(lit, 6, light.position.x, light.position.y, light.position.z, 0.0f);
  glProgramUniform4f(lit, 9, std::cos(light.coneAngleRad), std::cos(light.innerConeAngleRad), light.rangeM, 0.0f);
  glProgramUniform3fv(lit, 7, 1, glm::value_ptr(light.color * light.intensity));
  glProgramUniform3fv(lit, 8, 1, glm::value_ptr(scene.ambient));
  glBindTextureUnit(0, shadows.visibilityTexture());
  drawObjects(lit, true);
  glDepthMask(GL_TRUE);

  std::vector<uint8_t> rgba(static_cast<size_t>(o.width) * static_cast<size_t>(o.height) * 4);
  glGetTextureImage(color, 0, GL_RGBA, GL_UNSIGNED_BYTE, static_cast<GLsizei>(rgba.size()), rgba.data());
  if (glGetError() != GL_NO_ERROR) throw std::runtime_error("a GL error in the engine's passes");
  penumbra::writePng(o.out, o.width, o.height, penumbra::flipRows<uint8_t>(rgba, o.width, o.height, 4));
  std::printf("wrote %s (%dx%d, scene %s, shadows: %s x %s by Penumbra, %.2f ms in its passes)\n", o.out.c_str(), o.width,
              o.height, scene.name.c_str(), shadows.technique().projection().c_str(),
              shadows.technique().filter().c_str(), shadows.timings().total());

  const GLuint programs[] = {prepass, lit, sky};
  for (GLuint p : programs) glDeleteProgram(p);
  const GLuint textures[] = {depth, normal, color};
  glDeleteTextures(3, textures);
  const GLuint framebuffers[] = {prepassFbo, litFbo};
  glDeleteFramebuffers(2, framebuffers);
  const GLuint buffers[] = {vbo, ibo};
  glDeleteBuffers(2, buffers);
  glDeleteVertexArrays(1, &vao);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(parse(argc, argv));
  } catch (const penumbra::Error& e) {
    std::fprintf(stderr, "penumbra_example_engine: %s\n", e.what());
    return e.kind() == penumbra::ErrorKind::Usage ? 2 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "penumbra_example_engine: %s\n", e.what());
    return 1;
  }
}
