// Builds the Embree scene of the shadow casters and answers occlusion queries.
// Alpha-masked materials (Material::alphaMask with a base-colour texture) get an occlusion
// filter that rejects hits on texels with alpha < alphaCutoff; translucent ones (a non-zero
// Material::transmittance) one that multiplies the ray's light by their transmittance and lets
// it go on. Filters are installed only on those geometries, so opaque scenes pay nothing for them.
#include "reference/EmbreeScene.h"

#include "base/Hash.h"

#include <penumbra/Error.h>

#include <embree3/rtcore.h>
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <string>

namespace penumbra::reference {
namespace {

// Embree reports errors through a callback, possibly from its build threads; keep the last
// message so that PN_CHECK can name it.
void onEmbreeError(void* user, RTCError code, const char* message) {
  auto* log = static_cast<EmbreeErrorLog*>(user);
  const std::lock_guard lock(log->mutex);
  log->last = fmt::format("Embree error {}: {}", static_cast<int>(code), message ? message : "");
}

/// Embree's allocations, counted as they happen (from any of its threads).
bool onEmbreeMemory(void* user, ssize_t bytes, bool /*post*/) {
  auto* m = static_cast<EmbreeMemory*>(user);
  const int64_t now = m->current.fetch_add(bytes) + bytes;
  int64_t peak = m->peak.load();
  while (now > peak && !m->peak.compare_exchange_weak(peak, now)) {}
  return true;  // never refuse: the scene's size was checked before loading (--max-memory)
}

void checkDevice(RTCDevice device, EmbreeErrorLog& log, const std::string& what) {
  const RTCError code = rtcGetDeviceError(device);
  const std::lock_guard lock(log.mutex);
  PN_CHECK(code == RTC_ERROR_NONE,
           fmt::format("reference: {} failed ({})", what, log.last.empty() ? "unknown Embree error" : log.last));
}

/// Nearest-texel alpha with repeat wrapping. uv (0,0) is the image's first stored row (the top):
/// the renderer uploads Image rows as stored, so GL's t = 0 reads that row too.
float alphaAt(const Image& image, glm::vec2 uv) {
  const glm::vec2 wrapped = uv - glm::floor(uv);
  const int x = std::min(image.width - 1, static_cast<int>(wrapped.x * static_cast<float>(image.width)));
  const int y = std::min(image.height - 1, static_cast<int>(wrapped.y * static_cast<float>(image.height)));
  const size_t texel = static_cast<size_t>(y) * static_cast<size_t>(image.width) + static_cast<size_t>(x);
  return static_cast<float>(image.rgba[4 * texel + 3]) / 255.0f;
}

/// An intersection context that knows which triangle the ray left: Embree passes the context to
/// the context filter, so the receiver travels with the ray and no state is shared between rays.
struct SkipContext {
  RTCIntersectContext context;  // first: Embree sees a pointer to it
  TriangleId skip;
  /// Per ray (indexed by RTCRay::id): its light through translucent casters; null = the caller
  /// does not follow colour, and a translucent caster blocks like an opaque one.
  RayTransmittance* colour = nullptr;
};

/// Rejects hits on the receiver's own triangle: a flat triangle cannot shadow its own points
/// toward directions above its plane (those below are never traced), so every such hit is a
/// self-intersection caused by the position's rounding.
void skipReceiverFilter(const RTCFilterFunctionNArguments* args) {
  const auto* c = reinterpret_cast<const SkipContext*>(args->context);
  for (unsigned int i = 0; i < args->N; ++i) {
    if (args->valid[i] != -1) continue;
    if (RTCHitN_geomID(args->hit, args->N, i) == c->skip.object &&
        RTCHitN_primID(args->hit, args->N, i) == c->skip.triangle)
      args->valid[i] = 0;
  }
}

/// A translucent caster's hit on one ray: its light is multiplied by the caster's transmittance
/// (once per triangle) and the ray goes on, unless no light is left. The receiver's own triangle
/// is skipped here too: this filter runs before the context's.
bool passesThrough(const FilteredGeometry& g, const SkipContext& c, unsigned int rayId, unsigned int prim) {
  if (g.object == c.skip.object && prim == c.skip.triangle) return true;
  RayTransmittance& ray = c.colour[rayId];
  for (uint32_t k = 0; k < ray.crossings; ++k)
    if (ray.crossed[k].object == g.object && ray.crossed[k].triangle == prim) return true;  // already counted
  if (ray.crossings == kMaxTranslucentCrossings) return false;
  ray.crossed[ray.crossings++] = {g.object, prim};
  ray.product *= g.transmittance;
  return ray.product != glm::vec3(0.0f);
}

void casterOcclusionFilter(const RTCFilterFunctionNArguments* args) {
  const auto* g = static_cast<const FilteredGeometry*>(args->geometryUserPtr);
  const auto* c = reinterpret_cast<const SkipContext*>(args->context);
  for (unsigned int i = 0; i < args->N; ++i) {
    if (args->valid[i] != -1) continue;
    const unsigned int prim = RTCHitN_primID(args->hit, args->N, i);
    if (g->image) {
      const float u = RTCHitN_u(args->hit, args->N, i), v = RTCHitN_v(args->hit, args->N, i);
      const glm::vec2* t = &g->uvs[3 * static_cast<size_t>(prim)];
      const glm::vec2 uv = (1.0f - u - v) * t[0] + u * t[1] + v * t[2];
      if (alphaAt(*g->image, uv) < g->alphaCutoff) {
        args->valid[i] = 0;  // a hole: keep going
        continue;
      }
    }
    if (g->translucent && c->colour && passesThrough(*g, *c, RTCRayN_id(args->ray, args->N, i), prim)) args->valid[i] = 0;
  }
}

/// What Embree would crash on rather than report: bad indices, non-finite vertices. (Not
/// Scene::validate(): the tracer does not need the scene's lights.)
void checkCasters(const Scene& scene) {
  for (const Object& object : scene.objects) {
    PN_CHECK(object.mesh < scene.meshes.size() && object.material < scene.materials.size(),
             fmt::format("reference: object '{}': mesh or material index out of range", object.name));
    if (!object.castsShadow) continue;
    const Mesh& mesh = scene.meshes[object.mesh];
    PN_CHECK(mesh.indices.size() % 3 == 0 &&
                 std::all_of(mesh.indices.begin(), mesh.indices.end(), [&](uint32_t i) { return i < mesh.vertexCount(); }),
             fmt::format("reference: mesh '{}': indices are not triangles within its {} vertices", mesh.name,
                         mesh.vertexCount()));
    PN_CHECK(mesh.uvs.empty() || mesh.uvs.size() == mesh.vertexCount(),
             fmt::format("reference: mesh '{}': {} texture coordinates for {} vertices", mesh.name, mesh.uvs.size(), mesh.vertexCount()));
    for (const glm::vec3& p : mesh.positions)
      PN_CHECK(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z),
                fmt::format("reference: mesh '{}': a vertex is not finite", mesh.name));
  }
  for (const Material& m : scene.materials)
    PN_CHECK(m.baseColorTexture < static_cast<int>(scene.images.size()),
             fmt::format("reference: material '{}': texture index out of range", m.name));
}

}  // namespace

EmbreeScene::EmbreeScene(const Scene& scene, MeshStorage storage) {
  const auto start = std::chrono::steady_clock::now();
  checkCasters(scene);
  mImages = scene.images;

  mDevice.reset(rtcNewDevice(nullptr));
  PN_CHECK(mDevice, fmt::format("reference: cannot create an Embree device ({})",
                                           rtcGetDeviceError(nullptr) == RTC_ERROR_UNSUPPORTED_CPU
                                               ? "this CPU is not supported" : "unknown error"));
  RTCDevice device = mDevice.get();
  rtcSetDeviceErrorFunction(device, onEmbreeError, &mErrors);
  rtcSetDeviceMemoryMonitorFunction(device, onEmbreeMemory, &mMemory);
  mScene.reset(rtcNewScene(device));
  checkDevice(device, mErrors, "creating a scene");
  RTCScene rtcScene = mScene.get();
  // Robust mode: watertight edges, so no shadow ray slips between two triangles of a mesh.
  // Context filters: occluded() skips the receiver's own triangle (skipReceiverFilter).
  rtcSetSceneFlags(rtcScene, RTC_SCENE_FLAG_ROBUST | RTC_SCENE_FLAG_CONTEXT_FILTER_FUNCTION);
  rtcSetSceneBuildQuality(rtcScene, RTC_BUILD_QUALITY_HIGH);

  Hasher hash;
  PN_CHECK(scene.objects.size() < TriangleId::kNoObject, "reference: too many objects for Embree's geometry IDs");
  for (uint32_t objectIndex = 0; objectIndex < scene.objects.size(); ++objectIndex) {
    const Object& object = scene.objects[objectIndex];
    if (!object.castsShadow) continue;
    const Mesh& mesh = scene.meshes[object.mesh];
    const size_t triangles = mesh.triangleCount();
    if (triangles == 0) continue;

    // Attached right away: the scene owns it from here, so an exception cannot leak it. Its ID
    // is the object's index: the G-buffer names receivers that way.
    RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    checkDevice(device, mErrors, fmt::format("creating the geometry of '{}'", object.name));
    rtcAttachGeometryByID(rtcScene, geometry, objectIndex);
    rtcReleaseGeometry(geometry);
    // Borrowed: Embree reads the mesh's indices in place, and its positions too where the object
    // sits at the identity and the array's storage reaches past its last element (Embree loads
    // 16 bytes a vertex). Elsewhere it gets world-space copies.
    const bool borrowed = storage == MeshStorage::Borrowed;
    const bool sharePositions = borrowed && object.worldFromObject == glm::mat4(1.0f) &&
                                mesh.positions.capacity() > mesh.positions.size();
    if (sharePositions)
      rtcSetSharedGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, mesh.positions.data(), 0,
                                 sizeof(glm::vec3), mesh.vertexCount());
    glm::vec3* vertices = sharePositions ? nullptr
                                         : static_cast<glm::vec3*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                                                          sizeof(glm::vec3), mesh.vertexCount()));
    uint32_t* indices = nullptr;
    if (borrowed)
      rtcSetSharedGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, mesh.indices.data(), 0, 3 * sizeof(uint32_t),
                                 triangles);
    else
      indices = static_cast<uint32_t*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                               3 * sizeof(uint32_t), triangles));
    checkDevice(device, mErrors, fmt::format("allocating the geometry of '{}'", object.name));
    const glm::mat4& m = object.worldFromObject;
    if (vertices)
      for (size_t i = 0; i < mesh.vertexCount(); ++i) vertices[i] = glm::vec3(m * glm::vec4(mesh.positions[i], 1.0f));
    if (indices) std::copy(mesh.indices.begin(), mesh.indices.end(), indices);
    // The key sees world-space triangles, not (mesh, matrix) pairs: the same geometry placed by
    // a different route hashes the same, and any change of a transform changes it.
    if (vertices)
      for (uint32_t index : mesh.indices) hash.value(vertices[index]);
    else
      for (uint32_t index : mesh.indices) hash.value(glm::vec3(m * glm::vec4(mesh.positions[index], 1.0f)));

    const Material& material = scene.materials[object.material];
    const bool alphaMask = material.alphaMask && material.baseColorTexture >= 0 && !mesh.uvs.empty();
    if (alphaMask || material.translucent()) {
      auto mask = std::make_unique<FilteredGeometry>();
      mask->object = objectIndex;
      if (material.translucent()) {
        mask->translucent = mTranslucent = true;
        mask->transmittance = material.transmittance;
        hash.value(material.transmittance);  // only translucent casters add to the key: opaque ones keep theirs
      }
      rtcSetGeometryUserData(geometry, mask.get());
      rtcSetGeometryOccludedFilterFunction(geometry, casterOcclusionFilter);
      mFiltered.push_back(std::move(mask));
    }
    if (alphaMask) {
      FilteredGeometry* mask = mFiltered.back().get();
      mask->image = &mImages[static_cast<size_t>(material.baseColorTexture)];
      mask->alphaCutoff = material.alphaCutoff;
      mask->uvs.reserve(mesh.indices.size());
      for (uint32_t index : mesh.indices) mask->uvs.push_back(mesh.uvs[index]);
      PN_CHECK(mask->image->width > 0 && mask->image->height > 0 &&
                   mask->image->rgba.size() == 4 * static_cast<size_t>(mask->image->width) *
                                                   static_cast<size_t>(mask->image->height),
               fmt::format("reference: material '{}': its alpha-mask texture is empty or malformed", material.name));
      hash.value(mask->alphaCutoff);
      hash.array(std::span<const glm::vec2>(mask->uvs));
      hash.value(mask->image->width);
      hash.array(std::span<const uint8_t>(mask->image->rgba));
    }
    rtcCommitGeometry(geometry);
    mCasterTriangles += triangles;
  }
  rtcCommitScene(rtcScene);
  checkDevice(device, mErrors, "building the BVH");
  mMemoryAfterBuild = {static_cast<uint64_t>(std::max<int64_t>(0, mMemory.current.load())),
                       static_cast<uint64_t>(std::max<int64_t>(0, mMemory.peak.load()))};
  mBuildSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  hash.value(mCasterTriangles);
  mGeometryHash = hash.digest();
}

void EmbreeScene::ReleaseDevice::operator()(RTCDevice device) const { rtcReleaseDevice(device); }
void EmbreeScene::ReleaseScene::operator()(RTCScene scene) const { rtcReleaseScene(scene); }

void EmbreeScene::occluded(Bundle& bundle, TriangleId skip) const {
  if (bundle.rays.empty()) return;
  SkipContext c;
  rtcInitIntersectContext(&c.context);
  c.context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
  c.skip = skip;
  if (skip.object != TriangleId::kNoObject) c.context.filter = skipReceiverFilter;
  rtcOccluded1M(mScene.get(), &c.context, bundle.rays.data(), static_cast<unsigned int>(bundle.rays.size()), sizeof(RTCRay));
}

void EmbreeScene::transmittance(Bundle& bundle, std::vector<glm::vec3>& transmittance, TriangleId skip) const {
  transmittance.resize(bundle.size());
  if (bundle.rays.empty()) return;
  thread_local std::vector<RayTransmittance> rays;
  rays.assign(bundle.size(), RayTransmittance{});
  for (size_t k = 0; k < bundle.size(); ++k) bundle.rays[k].id = static_cast<unsigned int>(k);
  SkipContext c;
  rtcInitIntersectContext(&c.context);
  c.context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
  c.skip = skip;
  c.colour = rays.data();
  if (skip.object != TriangleId::kNoObject) c.context.filter = skipReceiverFilter;
  rtcOccluded1M(mScene.get(), &c.context, bundle.rays.data(), static_cast<unsigned int>(bundle.rays.size()), sizeof(RTCRay));
  for (size_t k = 0; k < bundle.size(); ++k) transmittance[k] = bundle.blocked(k) ? glm::vec3(0.0f) : rays[k].product;
}

glm::vec3 EmbreeScene::transmittance(const glm::vec3& origin, const glm::vec3& direction, float tNear, float tFar,
                                     TriangleId skip) const {
  thread_local Bundle bundle;
  thread_local std::vector<glm::vec3> out;
  bundle.clear();
  bundle.add(origin, direction, tNear, tFar);
  transmittance(bundle, out, skip);
  return out[0];
}

bool EmbreeScene::occluded(const glm::vec3& origin, const glm::vec3& direction, float tNear, float tFar,
                           TriangleId skip) const {
  SkipContext c;
  rtcInitIntersectContext(&c.context);
  c.skip = skip;
  if (skip.object != TriangleId::kNoObject) c.context.filter = skipReceiverFilter;
  RTCRay ray{};
  ray.org_x = origin.x; ray.org_y = origin.y; ray.org_z = origin.z;
  ray.dir_x = direction.x; ray.dir_y = direction.y; ray.dir_z = direction.z;
  ray.tnear = tNear;
  ray.tfar = tFar;
  ray.mask = std::numeric_limits<unsigned int>::max();
  rtcOccluded1(mScene.get(), &c.context, &ray);
  return ray.tfar == -std::numeric_limits<float>::infinity();  // Embree's "hit something"
}

}  // namespace penumbra::reference
