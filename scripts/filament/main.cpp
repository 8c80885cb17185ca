// filament_scene: one of Penumbra's built-in scenes rendered by Google Filament 1.9 (Debian's
// libfilament-dev), for scripts/filament-compare. The scene comes from Penumbra's installed
// package (makeBuiltinScene): the same meshes, materials, camera and first light (a sun, as
// Filament's directional light). Filament's OpenGL backend renders into a headless swap chain
// (a GLX pbuffer: run it under Xvfb), with PCF shadows (Filament's default), VSM, or none, one
// cascade of a --shadow-map² map. Post-processing is off (see run()); so are anti-aliasing and
// dithering (Penumbra has neither).
//
// Usage: filament_scene --material FILE.filamat [--scene boxes] [--size 1280x720]
//                       [--shadow-map 2048] [--shadows pcf|vsm|off] [--frames 1] [--out FILE.ppm]
// Renders --frames frames, each waited for (Engine::flushAndWait), and prints one line:
//   filament: frames N skipped S wall_ms_median W cpu_ms_median C
// wall: steady_clock per frame; cpu: getrusage(RUSAGE_SELF) per frame, every thread of the process
// (Filament's job and driver threads and the GL driver's). The first frame includes Filament's
// shader compilation; the script times whole processes and takes frame costs from their
// differences, these in-process numbers are printed for reference.
#include <filament/Camera.h>
#include <filament/Engine.h>
#include <filament/IndexBuffer.h>
#include <filament/IndirectLight.h>
#include <filament/LightManager.h>
#include <filament/Material.h>
#include <filament/MaterialInstance.h>
#include <filament/RenderableManager.h>
#include <filament/Renderer.h>
#include <filament/Scene.h>
#include <filament/SwapChain.h>
#include <filament/TransformManager.h>
#include <filament/VertexBuffer.h>
#include <filament/View.h>
#include <filament/Viewport.h>
#include <backend/PixelBufferDescriptor.h>
#include <geometry/SurfaceOrientation.h>
#include <utils/EntityManager.h>

#include <penumbra/SceneIO.h>

#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <vector>

using namespace filament;
using namespace filament::math;

namespace {

struct Options {
  std::string material, scene = "boxes", shadows = "pcf", out;
  int width = 1280, height = 720, mapSize = 2048, frames = 1;
};

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (i + 1 >= argc) throw std::runtime_error("missing value after " + a);
    const std::string v = argv[++i];
    if (a == "--material") o.material = v;
    else if (a == "--scene") o.scene = v;
    else if (a == "--shadows") o.shadows = v;
    else if (a == "--out") o.out = v;
    else if (a == "--shadow-map") o.mapSize = std::stoi(v);
    else if (a == "--frames") o.frames = std::stoi(v);
    else if (a == "--size") {
      if (std::sscanf(v.c_str(), "%dx%d", &o.width, &o.height) != 2) throw std::runtime_error("--size WxH");
    } else {
      throw std::runtime_error("unknown option " + a);
    }
  }
  if (o.material.empty()) throw std::runtime_error("--material FILE.filamat is required");
  if (o.shadows != "pcf" && o.shadows != "vsm" && o.shadows != "off") throw std::runtime_error("--shadows pcf|vsm|off");
  if (o.frames < 1 || o.width < 1 || o.height < 1) throw std::runtime_error("--frames, --size must be positive");
  return o;
}

std::vector<char> readFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read " + path);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

float3 f3(const glm::vec3& v) { return {v.x, v.y, v.z}; }

// Buffers handed to Filament are freed by its callback once uploaded.
template <class T> backend::BufferDescriptor descriptor(const std::vector<T>& data) {
  void* copy = std::malloc(data.size() * sizeof(T));
  std::memcpy(copy, data.data(), data.size() * sizeof(T));
  return backend::BufferDescriptor(copy, data.size() * sizeof(T), [](void* p, size_t, void*) { std::free(p); });
}

double cpuSeconds() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_utime.tv_sec + u.ru_stime.tv_sec) + 1e-6 * static_cast<double>(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

int run(const Options& o) {
  const penumbra::Scene scene = penumbra::makeBuiltinScene(o.scene);
  Engine* engine = Engine::create(Engine::Backend::OPENGL);
  if (!engine) throw std::runtime_error("Filament: no OpenGL engine (is DISPLAY set? run under xvfb-run)");
  SwapChain* swapChain = engine->createSwapChain(static_cast<uint32_t>(o.width), static_cast<uint32_t>(o.height));
  Renderer* renderer = engine->createRenderer();
  Scene* fScene = engine->createScene();
  View* view = engine->createView();
  utils::EntityManager& em = utils::EntityManager::get();

  const utils::Entity cameraEntity = em.create();
  Camera* camera = engine->createCamera(cameraEntity);
  const penumbra::Camera& c = scene.camera;
  constexpr double kDegreesPerRadian = 57.29577951308232;
  camera->setProjection(c.fovYRad * kDegreesPerRadian, static_cast<double>(o.width) / o.height, c.nearM, c.farM,
                        Camera::Fov::VERTICAL);
  camera->lookAt(f3(c.position), f3(c.target), f3(c.up));
  camera->setExposure(1.0f);  // light intensities taken as they are (no photographic exposure)

  view->setScene(fScene);
  view->setCamera(camera);
  view->setViewport({0, 0, static_cast<uint32_t>(o.width), static_cast<uint32_t>(o.height)});
  view->setAntiAliasing(View::AntiAliasing::NONE);
  view->setDithering(View::Dithering::NONE);
  // Post-processing off: on llvmpipe under Xvfb, Filament 1.9.25's post-processed frames read back
  // as uninitialised tiles (its final pass does not reach the swap chain), without it the image
  // is right. Filament's frame thus has no tone-mapping pass where Penumbra's lit pass tone-maps:
  // one full-screen pass in Filament's favour.
  view->setPostProcessingEnabled(false);
  view->setShadowType(o.shadows == "vsm" ? View::ShadowType::VSM : View::ShadowType::PCF);
  renderer->setClearOptions({.clearColor = {0.25f, 0.4f, 0.65f, 1.0f}, .clear = true, .discard = true});

  const std::vector<char> package = readFile(o.material);
  Material* material = Material::Builder().package(package.data(), package.size()).build(*engine);
  std::vector<MaterialInstance*> instances;
  for (const penumbra::Material& m : scene.materials) {
    MaterialInstance* mi = material->createInstance();
    mi->setParameter("baseColor", RgbType::LINEAR, f3(m.baseColor));
    mi->setParameter("roughness", m.roughness);
    instances.push_back(mi);
  }

  // Meshes: positions and tangent frames (quaternions from the normals, as Filament's lit
  // materials want them), 32-bit indices.
  std::vector<VertexBuffer*> vertexBuffers;
  std::vector<IndexBuffer*> indexBuffers;
  for (const penumbra::Mesh& mesh : scene.meshes) {
    const size_t n = mesh.vertices.size();
    std::vector<float3> positions(n), normals(n);
    for (size_t i = 0; i < n; ++i) {
      positions[i] = f3(mesh.vertices[i].position);
      normals[i] = f3(mesh.vertices[i].normal);
    }
    std::vector<quatf> tangents(n);
    geometry::SurfaceOrientation* orientation =
        geometry::SurfaceOrientation::Builder().vertexCount(n).normals(normals.data()).build();
    orientation->getQuats(tangents.data(), n);
    delete orientation;
    VertexBuffer* vb = VertexBuffer::Builder()
                           .vertexCount(static_cast<uint32_t>(n))
                           .bufferCount(2)
                           .attribute(VertexAttribute::POSITION, 0, VertexBuffer::AttributeType::FLOAT3)
                           .attribute(VertexAttribute::TANGENTS, 1, VertexBuffer::AttributeType::FLOAT4)
                           .build(*engine);
    vb->setBufferAt(*engine, 0, descriptor(positions));
    vb->setBufferAt(*engine, 1, descriptor(tangents));
    IndexBuffer* ib = IndexBuffer::Builder()
                          .indexCount(static_cast<uint32_t>(mesh.indices.size()))
                          .bufferType(IndexBuffer::IndexType::UINT)
                          .build(*engine);
    ib->setBuffer(*engine, descriptor(mesh.indices));
    vertexBuffers.push_back(vb);
    indexBuffers.push_back(ib);
  }

  std::vector<utils::Entity> entities;
  TransformManager& tcm = engine->getTransformManager();
  for (const penumbra::Object& object : scene.objects) {
    const penumbra::Mesh& mesh = scene.meshes[object.mesh];
    const penumbra::Aabb b = mesh.bounds();
    const utils::Entity e = em.create();
    RenderableManager::Builder(1)
        .boundingBox({f3(b.center()), f3(0.5f * b.size())})
        .geometry(0, RenderableManager::PrimitiveType::TRIANGLES, vertexBuffers[object.mesh], indexBuffers[object.mesh])
        .material(0, instances[object.material])
        .castShadows(object.castsShadow && o.shadows != "off")
        .receiveShadows(o.shadows != "off")
        .build(*engine, e);
    tcm.create(e);
    mat4f world;
    for (int col = 0; col < 4; ++col)
      for (int row = 0; row < 4; ++row) world[col][row] = object.worldFromObject[col][row];
    tcm.setTransform(tcm.getInstance(e), world);
    fScene->addEntity(e);
    entities.push_back(e);
  }

  // The sun, and the scene's constant ambient as the first band of an irradiance field.
  const penumbra::Light& light = scene.light();
  if (light.type != penumbra::LightType::Directional) throw std::runtime_error("the scene's light is not a sun");
  LightManager::ShadowOptions shadow;
  shadow.mapSize = static_cast<uint32_t>(o.mapSize);
  shadow.shadowCascades = 1;
  const utils::Entity sun = em.create();
  LightManager::Builder(LightManager::Type::DIRECTIONAL)
      .direction(f3(light.direction))
      .color({light.color.x, light.color.y, light.color.z})
      .intensity(light.intensity)
      .castShadows(o.shadows != "off")
      .shadowOptions(shadow)
      .build(*engine, sun);
  fScene->addEntity(sun);
  const float3 ambient[1] = {f3(scene.ambient)};
  IndirectLight* ibl = IndirectLight::Builder().irradiance(1, ambient).intensity(1.0f).build(*engine);
  fScene->setIndirectLight(ibl);

  std::vector<uint8_t> pixels;
  std::vector<double> wallMs, cpuMs;
  int skipped = 0;
  for (int frame = 0; frame < o.frames;) {
    const double cpu0 = cpuSeconds();
    const auto wall0 = std::chrono::steady_clock::now();
    if (!renderer->beginFrame(swapChain)) {  // frame pacing asked to skip: not a frame
      ++skipped;
      engine->flushAndWait();
      continue;
    }
    renderer->render(view);
    if (frame == o.frames - 1 && !o.out.empty()) {
      pixels.resize(static_cast<size_t>(o.width) * static_cast<size_t>(o.height) * 4);
      renderer->readPixels(0, 0, static_cast<uint32_t>(o.width), static_cast<uint32_t>(o.height),
                           backend::PixelBufferDescriptor(pixels.data(), pixels.size(), backend::PixelDataFormat::RGBA,
                                                          backend::PixelDataType::UBYTE));
    }
    renderer->endFrame();
    engine->flushAndWait();
    wallMs.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - wall0).count());
    cpuMs.push_back(1e3 * (cpuSeconds() - cpu0));
    ++frame;
  }
  std::printf("filament: frames %d skipped %d wall_ms_median %.3f cpu_ms_median %.3f\n", o.frames, skipped, median(wallMs),
              median(cpuMs));

  if (!o.out.empty()) {  // PPM; Filament's read-back has the top row first
    std::ofstream out(o.out, std::ios::binary);
    out << "P6\n" << o.width << " " << o.height << "\n255\n";
    for (int y = 0; y < o.height; ++y)
      for (int x = 0; x < o.width; ++x)
        out.write(reinterpret_cast<const char*>(&pixels[(static_cast<size_t>(y) * o.width + x) * 4]), 3);
  }

  engine->destroy(ibl);
  for (const utils::Entity e : entities) engine->destroy(e);
  engine->destroy(sun);
  for (IndexBuffer* ib : indexBuffers) engine->destroy(ib);
  for (VertexBuffer* vb : vertexBuffers) engine->destroy(vb);
  for (MaterialInstance* mi : instances) engine->destroy(mi);
  engine->destroy(material);
  engine->destroyCameraComponent(cameraEntity);
  engine->destroy(view);
  engine->destroy(fScene);
  engine->destroy(renderer);
  engine->destroy(swapChain);
  Engine::destroy(&engine);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(parse(argc, argv));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "filament_scene: %s\n", e.what());
    return 1;
  }
}
