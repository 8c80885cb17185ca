// Shared model-file plumbing: format dispatch, limits, default light and camera, placing a model
// inside a scene file. The format parsers live in GltfLoader.cpp and ObjLoader.cpp.
#include "sceneio/loaders/ModelImport.h"

#include "base/HostMemory.h"

#include "sceneio/loaders/GltfLoader.h"
#include "sceneio/loaders/ObjLoader.h"

#include <penumbra/Error.h>

#include <fmt/format.h>
#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <system_error>

namespace penumbra::loaders {
namespace {

std::string lowerExtension(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

bool finiteMatrix(const glm::mat4& m) {
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      if (!std::isfinite(m[c][r])) return false;
  return true;
}

// Default camera framing: looking down at the model from the front right, its bounding sphere
// inside the vertical field of view with this much room to spare.
constexpr float kFramingMargin = 1.15f;
const glm::vec3 kDefaultViewDirection{0.55f, 0.45f, 1.0f};   // from the model toward the camera
const glm::vec3 kDefaultSunDirection{-0.4f, -1.0f, -0.3f};   // toward the scene
constexpr float kMinFramedRadiusM = 1e-3f;                    // a point-sized model still gets a view
constexpr float kMinNearM = 1e-4f;                            // the scene file's smallest near plane

// A floor of the model's own: an object at most this fraction of the model's larger horizontal
// side tall, within it of the model's lowest point, under at least kFloorCover of its footprint.
constexpr float kFloorFlatness = 0.02f;
constexpr float kFloorCover = 0.5f;
const glm::vec3 kGroundColor{0.6f};  // the built-in scenes' mid grey

}  // namespace

// Reports closer together than a hundredth of the load would only cost time.
constexpr double kProgressStep = 0.01;

ProgressReport::ProgressReport(const LoadOptions& options, std::filesystem::path file)
    : mOptions(options), mFile(std::move(file)) {
  if (mOptions.progress) mOptions.progress(mFile, 0.0);
}

void ProgressReport::update(uint64_t done, uint64_t total) {
  if (!mOptions.progress || total == 0) return;
  const double fraction = mFrom + (mTo - mFrom) * std::min(1.0, static_cast<double>(done) / static_cast<double>(total));
  if (fraction - mLast >= kProgressStep) report(fraction);
}

void ProgressReport::report(double fraction) {
  if (!mOptions.progress || fraction <= mLast) return;
  mLast = fraction;
  mOptions.progress(mFile, fraction);
}

void fail(const std::string& file, const std::string& field, const std::string& problem) {
  if (field.empty()) throw Error(fmt::format("{}: {}", file, problem));
  throw Error(fmt::format("{}: {}: {}", file, field, problem));
}

bool isModelFile(const std::filesystem::path& path) {
  const std::string ext = lowerExtension(path);
  return ext == ".gltf" || ext == ".glb" || ext == ".obj";
}

std::vector<uint8_t> readFileLimited(const std::filesystem::path& path, const std::string& what, uint64_t maxBytes) {
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (ec || !std::filesystem::exists(status)) fail(what, "", fmt::format("cannot open {} (no such file)", path.string()));
  if (std::filesystem::is_directory(status)) fail(what, "", fmt::format("{} is a folder, not a file", path.string()));
  if (!std::filesystem::is_regular_file(status)) fail(what, "", fmt::format("{} is not a regular file", path.string()));
  const uintmax_t size = std::filesystem::file_size(path, ec);
  if (ec) fail(what, "", fmt::format("cannot read the size of {}", path.string()));
  if (size > maxBytes)
    fail(what, "", fmt::format("{} is {} bytes, more than the {} byte limit", path.string(), size, maxBytes));
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(what, "", fmt::format("cannot open {} (not readable)", path.string()));
  std::vector<uint8_t> bytes(static_cast<size_t>(size));
  if (size > 0 && !in.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(size)))
    fail(what, "", fmt::format("cannot read {} (read error)", path.string()));
  return bytes;
}

Model loadModelFile(const std::filesystem::path& path, const LoadOptions& options) {
  const std::string ext = lowerExtension(path);
  ProgressReport progress(options, path);
  Model model;
  if (ext == ".gltf" || ext == ".glb") model = loadGltf(path, progress);
  else if (ext == ".obj") model = loadObj(path, progress);
  else fail(path.string(), "", "not a model file (.gltf, .glb or .obj)");
  model.scene.sourceFile = path;
  checkSceneLimits(model.scene, path.string());
  const bool drawsSomething = std::any_of(model.scene.objects.begin(), model.scene.objects.end(),
                                          [&](const Object& o) { return model.scene.meshes[o.mesh].hasArea(); });
  if (!drawsSomething) fail(path.string(), "", "every triangle has zero area (its corners lie on one line): nothing would be drawn");
  progress.finish();
  return model;
}

Scene loadModelScene(const std::filesystem::path& path, const LoadOptions& options) {
  Model model = loadModelFile(path, options);
  addDefaultLightAndCamera(model.scene, model.hasCamera);  // framed on the model, before any ground
  if (options.groundUnderLoneModel) {
    const std::string what = addGroundUnderModel(model.scene);
    if (options.notice) options.notice(path.filename().string() + ": " + what);
  }
  model.scene.validate();
  return std::move(model.scene);
}

}  // namespace penumbra::loaders

namespace penumbra {

std::string addGroundUnderModel(Scene& scene) {
  const Aabb b = scene.bounds();
  if (b.empty()) return "nothing to stand on a ground: no ground added";
  const glm::vec3 size = b.hi - b.lo;
  const float side = std::max({size.x, size.z, loaders::kMinFramedRadiusM});
  const float footprint = std::max(size.x, loaders::kMinFramedRadiusM) * std::max(size.z, loaders::kMinFramedRadiusM);
  for (const Object& o : scene.objects) {
    if (o.mesh >= scene.meshes.size()) continue;
    const Aabb ob = scene.meshes[o.mesh].bounds().transformed(o.worldFromObject);
    if (ob.empty()) continue;
    const glm::vec3 os = ob.hi - ob.lo;
    if (os.y <= loaders::kFloorFlatness * side && ob.lo.y - b.lo.y <= loaders::kFloorFlatness * side && os.x * os.z >= loaders::kFloorCover * footprint)
      return fmt::format("its own '{}' is the floor: no ground added", o.name);
  }
  const float ground = kGroundSpanFactor * side;
  const glm::vec3 centre{0.5f * (b.lo.x + b.hi.x), b.lo.y, 0.5f * (b.lo.z + b.hi.z)};
  addObject(scene, "ground (added)", makePlane(ground, ground), loaders::kGroundColor, glm::translate(glm::mat4(1.0f), centre), false);
  return fmt::format("no floor in the model, so a {:.3g} m ground is added under it at y = {:.3g} m (its lowest point), where "
                     "its shadow can fall; a scene file places a model on a ground of its choice (docs/scenes.md)",
                     ground, centre.y);
}

}  // namespace penumbra

namespace penumbra::loaders {

void addDefaultLightAndCamera(Scene& scene, bool hasCamera) {
  const Aabb bounds = scene.bounds();
  if (scene.lights.empty()) {
    Light sun;
    sun.type = LightType::Directional;
    sun.direction = glm::normalize(kDefaultSunDirection);
    sun.size = kDefaultSunAngularRadiusRad;
    scene.lights.push_back(sun);
  }
  if (hasCamera || bounds.empty()) return;
  Camera& cam = scene.camera;
  const float radius = std::max(bounds.radius(), kMinFramedRadiusM);
  const float distance = kFramingMargin * radius / std::sin(0.5f * cam.fovYRad);
  cam.target = bounds.center();
  cam.position = cam.target + glm::normalize(kDefaultViewDirection) * distance;
  cam.up = {0.0f, 1.0f, 0.0f};
  cam.nearM = std::max(kMinNearM, 0.5f * (distance - radius));
  cam.farM = 2.0f * (distance + radius);
}

void appendModel(Scene& scene, const Scene& model, const glm::mat4& worldFromModel, bool castsShadow,
                 const std::string& name, const std::string& where) {
  const auto meshBase = static_cast<uint32_t>(scene.meshes.size());
  const auto materialBase = static_cast<uint32_t>(scene.materials.size());
  const int imageBase = static_cast<int>(scene.images.size());
  scene.meshes.insert(scene.meshes.end(), model.meshes.begin(), model.meshes.end());
  scene.images.insert(scene.images.end(), model.images.begin(), model.images.end());
  for (Material m : model.materials) {
    if (m.baseColorTexture >= 0) m.baseColorTexture += imageBase;
    scene.materials.push_back(std::move(m));
  }
  // The model's animation nodes follow it: roots are placed by worldFromModel.
  const auto objectBase = static_cast<uint32_t>(scene.objects.size());
  const auto nodeBase = static_cast<int>(scene.animation.nodes.size());
  for (AnimatedNode n : model.animation.nodes) {
    n.name = name + "/" + n.name;
    if (n.parent < 0) n.offset = worldFromModel * n.offset;
    else n.parent += nodeBase;
    scene.animation.nodes.push_back(std::move(n));
  }
  for (ObjectAnimation a : model.animation.objects) {
    a.object += objectBase;
    a.node += static_cast<uint32_t>(nodeBase);
    scene.animation.objects.push_back(a);
  }
  for (Object o : model.objects) {
    o.name = name + "/" + o.name;
    o.mesh += meshBase;
    o.material += materialBase;
    o.worldFromObject = worldFromModel * o.worldFromObject;
    o.castsShadow = o.castsShadow && castsShadow;
    scene.objects.push_back(std::move(o));
  }
  checkSceneLimits(scene, where);
}

void checkSceneLimits(const Scene& scene, const std::string& file) {
  if (scene.objects.size() > kMaxObjects)
    fail(file, "", fmt::format("{} placed meshes, more than the limit of {}", scene.objects.size(), kMaxObjects));
  if (scene.images.size() > kMaxImages)
    fail(file, "", fmt::format("{} images, more than the limit of {}", scene.images.size(), kMaxImages));
  uint64_t imageBytes = 0;
  for (const Image& im : scene.images) imageBytes += im.rgba.size();
  if (imageBytes > kMaxImageBytes)
    fail(file, "", fmt::format("{} bytes of decoded images, more than the limit of {}", imageBytes, kMaxImageBytes));
  // World coordinates: the corners of each mesh's box under its transform. A box within the
  // limit bounds every vertex of an affine transform of the mesh.
  std::vector<Aabb> meshBounds;
  meshBounds.reserve(scene.meshes.size());
  for (const Mesh& m : scene.meshes) meshBounds.push_back(m.bounds());
  for (const Object& o : scene.objects) {
    if (!finiteMatrix(o.worldFromObject)) fail(file, o.name, "its world transform is not finite");
    if (o.mesh >= meshBounds.size()) continue;  // Scene::validate names this one
    const Aabb b = meshBounds[o.mesh].transformed(o.worldFromObject);
    if (b.empty()) continue;
    for (const glm::vec3& c : {b.lo, b.hi})
      for (int i = 0; i < 3; ++i)
        if (!(std::abs(c[i]) <= kMaxCoordinateM))
          fail(file, o.name, fmt::format("world-space coordinate {} is not finite or beyond ±{} m", c[i], kMaxCoordinateM));
  }
}

uint64_t MemoryEstimate::peakBytes() const { return std::max(loaderBytes + meshBytes, meshBytes + glBytes + bvhBytes); }

MemoryEstimate estimateSceneMemory(const SceneCounts& c, const LoadOptions& options) {
  MemoryEstimate e;
  e.meshBytes = c.vertices * sizeof(glm::vec3) + c.normals * sizeof(glm::vec3) + c.uvs * sizeof(glm::vec2) + c.triangles * 3 * sizeof(uint32_t);
  if (options.glBuffersInHostMemory) e.glBytes = e.meshBytes;  // the same attributes, interleaved (GpuScene)
  // The BVH, and the world-space positions and per-triangle receiver planes the reference keeps.
  if (options.referenceBvh) e.bvhBytes = c.triangles * kBvhBytesPerTriangle + c.vertices * sizeof(glm::vec3) + c.triangles * 16;
  e.loaderBytes = c.loaderBytes;
  return e;
}

namespace {

/// "256 KiB", "820 MiB", "1.37 GiB".
std::string memoryText(uint64_t bytes) {
  constexpr double kKiB = 1024.0, kMiB = 1024.0 * kKiB, kGiB = 1024.0 * kMiB;
  if (bytes < (uint64_t(1) << 20)) return fmt::format("{:.0f} KiB", bytes / kKiB);
  return bytes < (uint64_t(1) << 30) ? fmt::format("{:.0f} MiB", bytes / kMiB) : fmt::format("{:.2f} GiB", bytes / kGiB);
}

}  // namespace

void checkSceneMemory(const SceneCounts& c, const std::string& file, const LoadOptions& options) {
  const MemoryEstimate e = estimateSceneMemory(c, options);
  const uint64_t available = availableHostBytes(), limit = options.maxMemoryBytes ? options.maxMemoryBytes : available;
  if (e.peakBytes() <= limit) return;
  std::string parts = "meshes " + memoryText(e.meshBytes);
  if (e.glBytes) parts += ", GL buffers in host memory " + memoryText(e.glBytes);
  if (e.bvhBytes) parts += ", reference BVH " + memoryText(e.bvhBytes);
  if (e.loaderBytes) parts += ", loading " + memoryText(e.loaderBytes);
  const uint64_t total = totalHostBytes();
  const std::string machine = fmt::format("this machine has {} available of {} RAM", memoryText(available), memoryText(total));
  const std::string against = options.maxMemoryBytes ? fmt::format("more than the --max-memory limit of {} ({})", memoryText(limit), machine)
                                                     : fmt::format("more than the {} available ({}; --max-memory sets another limit)",
                                                                   memoryText(limit), machine);
  fail(file, "", fmt::format("{} triangles and about {} vertices need about {} at the peak ({}), {}", c.triangles, c.vertices,
                             memoryText(e.peakBytes()), parts, against));
}

}  // namespace penumbra::loaders
