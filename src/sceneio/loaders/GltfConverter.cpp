// tinygltf::Model → Model: the default scene's node hierarchy, triangle primitives, materials,
// images, KHR_lights_punctual lights and the first perspective camera. Every index, offset,
// count and number is checked before use (tinygltf checks few): a failure is one Error naming
// the glTF field ("accessors[3]: …"). What is read and what is ignored: docs/scenes.md.
#include "sceneio/loaders/GltfConverter.h"

#include "sceneio/loaders/GltfAnimation.h"
#include "sceneio/loaders/GltfTextures.h"

#include "sceneio/loaders/TinyGltf.h"

#include <penumbra/Error.h>

#include <fmt/format.h>
#include <meshoptimizer.h>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <set>

namespace penumbra::loaders {
namespace {

constexpr float kAlwaysHoleCutoff = 2.0f;       // above any alpha: every texel is a hole
constexpr float kMinConeRad = 0.0175f;          // 1°: the scene file's narrowest spot cone
constexpr float kMaxSpotSizeM = 100.0f, kMaxSunSizeRad = 0.5f;  // the scene file's light-size bounds

const std::set<std::string> kSupportedRequiredExtensions = {
    "KHR_lights_punctual", "KHR_mesh_quantization", "KHR_materials_unlit", "KHR_materials_emissive_strength",
    "KHR_texture_transform", "KHR_draco_mesh_compression", "EXT_meshopt_compression", "KHR_materials_transmission"};

/// KHR_materials_transmission's transmissionFactor of `material` (0 without the extension);
/// throws Error naming the field when it is not a number in [0, 1]. Its texture is not read.
float transmissionFactor(const tinygltf::Material& material, const std::string& file, const std::string& field) {
  const auto ext = material.extensions.find("KHR_materials_transmission");
  if (ext == material.extensions.end()) return 0.0f;
  const std::string base = field + ".extensions.KHR_materials_transmission";
  if (!ext->second.IsObject()) fail(file, base, "expected an object");
  if (!ext->second.Has("transmissionFactor")) return 0.0f;
  const tinygltf::Value& v = ext->second.Get("transmissionFactor");
  const double t = v.IsNumber() ? v.GetNumberAsDouble() : NAN;
  if (!(t >= 0.0 && t <= 1.0)) fail(file, base + ".transmissionFactor", "must be a number in [0, 1]");
  return static_cast<float>(t);
}

// --- accessors ---------------------------------------------------------------------------------
int componentBytes(int type) {
  switch (type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT: case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: case TINYGLTF_COMPONENT_TYPE_FLOAT: return 4;
    default: return 0;
  }
}

/// A checked view of an accessor: every element lies inside its buffer.
struct AccessorData {
  const uint8_t* base = nullptr;  ///< nullptr: no bufferView, every component is 0
  size_t stride = 0, count = 0;
  int componentType = 0, components = 0;
  bool normalized = false;

  double component(size_t i, int c) const {
    if (!base) return 0.0;
    const uint8_t* p = base + i * stride + static_cast<size_t>(c * componentBytes(componentType));
    switch (componentType) {
      case TINYGLTF_COMPONENT_TYPE_BYTE: { int8_t v; std::memcpy(&v, p, 1); return normalized ? std::max(v / 127.0, -1.0) : v; }
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: { uint8_t v; std::memcpy(&v, p, 1); return normalized ? v / 255.0 : v; }
      case TINYGLTF_COMPONENT_TYPE_SHORT: { int16_t v; std::memcpy(&v, p, 2); return normalized ? std::max(v / 32767.0, -1.0) : v; }
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: { uint16_t v; std::memcpy(&v, p, 2); return normalized ? v / 65535.0 : v; }
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: { uint32_t v; std::memcpy(&v, p, 4); return v; }
      default: { float v; std::memcpy(&v, p, 4); return v; }
    }
  }
};

/// A primitive without indices lists its triangles' corners: equal corners (every attribute the
/// same) become one vertex, by meshoptimizer's remap.
void shareCorners(Mesh& mesh) {
  std::vector<meshopt_Stream> streams = {{mesh.positions.data(), sizeof(glm::vec3), sizeof(glm::vec3)}};
  if (!mesh.normals.empty()) streams.push_back({mesh.normals.data(), sizeof(glm::vec3), sizeof(glm::vec3)});
  if (!mesh.uvs.empty()) streams.push_back({mesh.uvs.data(), sizeof(glm::vec2), sizeof(glm::vec2)});
  std::vector<unsigned int> remap(mesh.vertexCount());
  const size_t unique = meshopt_generateVertexRemapMulti(remap.data(), mesh.indices.data(), mesh.indices.size(), mesh.vertexCount(),
                                                         streams.data(), streams.size());
  if (unique == mesh.vertexCount()) return;
  meshopt_remapIndexBuffer(mesh.indices.data(), mesh.indices.data(), mesh.indices.size(), remap.data());
  auto shrink = [&](auto& values) {
    if (values.empty()) return;
    meshopt_remapVertexBuffer(values.data(), values.data(), values.size(), sizeof(values[0]), remap.data());
    values.resize(unique);
    values.shrink_to_fit();
  };
  shrink(mesh.positions);
  shrink(mesh.normals);
  shrink(mesh.uvs);
}

class Converter {
public:
  Converter(const tinygltf::Model& model, std::string file, ProgressReport* progress)
      : g(model), mFile(std::move(file)), mProgress(progress) {}
  Model run();

private:
  [[noreturn]] void error(const std::string& field, const std::string& what) const { fail(mFile, field, what); }
  /// `type`: TINYGLTF_TYPE_SCALAR or _VEC2.._VEC4.
  AccessorData accessor(int index, const std::string& use, int type, std::initializer_list<int> componentTypes) const;
  std::vector<uint32_t> readIndices(const tinygltf::Primitive& p, size_t vertexCount, const std::string& field) const;
  int meshFor(int meshIndex, int primIndex);  // -1: the primitive draws nothing
  int materialFor(int gltfMaterial, const std::string& field, bool& invisible);
  int imageFor(int gltfImage, const std::string& field);
  /// `animParent`: the animation node of the nearest ancestor under an animated node, or -1.
  void visit(int node, const glm::mat4& parent, int depth, int animParent);
  int addAnimatedNode(const tinygltf::Node& n, const glm::mat4& parent, int animParent, const std::string& field);
  glm::mat4 localTransform(const tinygltf::Node& n, const std::string& field) const;
  /// `animNode`: the animation node the light or camera hangs in (it moves with it), or -1.
  void addLight(const tinygltf::Node& node, const glm::mat4& world, int animNode, const std::string& field);
  void addCamera(const tinygltf::Camera& c, const glm::mat4& world, int animNode, const std::string& field);
  /// The memory check (checkSceneMemory) from the accessors' counts, before any mesh is built.
  void checkMemory() const;

  const tinygltf::Model& g;
  std::string mFile;
  ProgressReport* mProgress;
  size_t mPrimitivesDone = 0, mPrimitivesTotal = 0;
  Model mOut;
  std::map<std::pair<int, int>, int> mMeshes;
  std::map<int, std::pair<int, bool>> mMaterials;  // glTF material → (scene material, invisible)
  std::map<int, int> mImages;
  uint64_t mImageBytes = 0;  // decoded so far
  std::map<int, UvTransform> mUvTransforms;  // glTF material → its base-colour texture's transform
  std::vector<uint8_t> mOnPath, mVisited;
  std::map<int, TransformTrack> mTracks;  // keyed channels by glTF node
};

AccessorData Converter::accessor(int index, const std::string& use, int type, std::initializer_list<int> types) const {
  if (index < 0 || static_cast<size_t>(index) >= g.accessors.size())
    error(use, fmt::format("no accessor {} ({} accessors)", index, g.accessors.size()));
  const tinygltf::Accessor& a = g.accessors[static_cast<size_t>(index)];
  const std::string field = fmt::format("accessors[{}]", index);
  if (a.sparse.isSparse) error(field, "sparse accessors are not supported");
  if (std::find(types.begin(), types.end(), a.componentType) == types.end())
    error(field, fmt::format("componentType {} is not allowed for {}", a.componentType, use));
  const int components = type == TINYGLTF_TYPE_SCALAR ? 1 : type;  // VEC2..VEC4 are 2..4
  if (a.type != type) error(field, fmt::format("type {} is not the {} that {} needs", a.type, type, use));
  if (a.count < 1) error(field + ".count", "must be at least 1");
  if (a.count > UINT32_MAX) error(field + ".count", fmt::format("{} is more than 32-bit indices can number", a.count));
  AccessorData d;
  d.count = a.count;
  d.componentType = a.componentType;
  d.components = components;
  d.normalized = a.normalized;
  const size_t elementBytes = static_cast<size_t>(componentBytes(a.componentType) * components);
  // Without a view an accessor is all zeros, which only makes sense under sparse substitution.
  if (a.bufferView < 0) error(field, "has no bufferView (all zeros; sparse accessors are not supported)");
  if (static_cast<size_t>(a.bufferView) >= g.bufferViews.size())
    error(field + ".bufferView", fmt::format("no buffer view {} ({} views)", a.bufferView, g.bufferViews.size()));
  const tinygltf::BufferView& v = g.bufferViews[static_cast<size_t>(a.bufferView)];
  const std::string viewField = fmt::format("bufferViews[{}]", a.bufferView);
  if (v.buffer < 0 || static_cast<size_t>(v.buffer) >= g.buffers.size())
    error(viewField + ".buffer", fmt::format("no buffer {} ({} buffers)", v.buffer, g.buffers.size()));
  const std::vector<unsigned char>& data = g.buffers[static_cast<size_t>(v.buffer)].data;
  if (v.byteOffset > data.size() || v.byteLength > data.size() - v.byteOffset)
    error(viewField, fmt::format("bytes {}..{} run past the end of its buffer ({} bytes loaded)", v.byteOffset,
                                 static_cast<uint64_t>(v.byteOffset) + v.byteLength, data.size()));
  if (v.byteStride != 0 && (v.byteStride < elementBytes || v.byteStride > 252))
    error(viewField + ".byteStride", fmt::format("{} does not fit elements of {} bytes (4..252)", v.byteStride, elementBytes));
  d.stride = v.byteStride ? v.byteStride : elementBytes;
  // The last element must end inside the view; all sizes are far below 2^64 after the checks above.
  const uint64_t end = static_cast<uint64_t>(a.byteOffset) + static_cast<uint64_t>(d.stride) * (a.count - 1) + elementBytes;
  if (a.byteOffset > v.byteLength || end > v.byteLength)
    error(field, fmt::format("{} elements from byte {} need {} bytes, the view has {}", a.count, a.byteOffset, end, v.byteLength));
  d.base = data.data() + v.byteOffset + a.byteOffset;
  return d;
}

std::vector<uint32_t> Converter::readIndices(const tinygltf::Primitive& p, size_t vertexCount, const std::string& field) const {
  std::vector<uint32_t> indices;
  if (p.indices < 0) {
    indices.resize(vertexCount);
    for (size_t i = 0; i < vertexCount; ++i) indices[i] = static_cast<uint32_t>(i);
    return indices;
  }
  const AccessorData a = accessor(p.indices, field + ".indices", TINYGLTF_TYPE_SCALAR,
                                  {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT,
                                   TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT});
  indices.resize(a.count);
  for (size_t i = 0; i < a.count; ++i) {
    const double v = a.component(i, 0);
    if (v >= static_cast<double>(vertexCount))
      error(fmt::format("accessors[{}]", p.indices), fmt::format("index {} (element {}) is out of range ({} vertices)", v, i, vertexCount));
    indices[i] = static_cast<uint32_t>(v);
  }
  return indices;
}

void Converter::checkMemory() const {
  if (!mProgress) return;
  SceneCounts c;
  for (const tinygltf::Mesh& m : g.meshes)
    for (const tinygltf::Primitive& p : m.primitives) {
      const auto count = [&](int accessor) -> uint64_t {
        return accessor >= 0 && static_cast<size_t>(accessor) < g.accessors.size() ? g.accessors[static_cast<size_t>(accessor)].count : 0;
      };
      const auto position = p.attributes.find("POSITION");
      if (position == p.attributes.end()) continue;
      const uint64_t vertices = count(position->second), corners = p.indices >= 0 ? count(p.indices) : vertices;
      const int mode = p.mode < 0 ? TINYGLTF_MODE_TRIANGLES : p.mode;
      if (mode < TINYGLTF_MODE_TRIANGLES) continue;
      c.vertices += vertices;
      c.triangles += mode == TINYGLTF_MODE_TRIANGLES ? corners / 3 : (corners < 3 ? 0 : corners - 2);
      if (p.attributes.count("NORMAL")) c.normals += vertices;
      if (p.attributes.count("TEXCOORD_0") || p.attributes.count("TEXCOORD_1")) c.uvs += vertices;
    }
  for (const tinygltf::Buffer& b : g.buffers) c.loaderBytes += b.data.size();  // held while the meshes are built
  checkSceneMemory(c, mFile, mProgress->options());
}

int Converter::imageFor(int gi, const std::string& field) {
  if (auto it = mImages.find(gi); it != mImages.end()) return it->second;
  mOut.scene.images.push_back(decodeImage(g.images[static_cast<size_t>(gi)], gi, mFile, field, mImageBytes));
  return mImages[gi] = static_cast<int>(mOut.scene.images.size() - 1);
}

int Converter::materialFor(int gm, const std::string& use, bool& invisible) {
  if (auto it = mMaterials.find(gm); it != mMaterials.end()) {
    invisible = it->second.second;
    return it->second.first;
  }
  Material m;
  invisible = false;
  if (gm < 0) {
    m.name = "default";
    m.baseColor = glm::vec3(1.0f);  // glTF's default material
    m.roughness = 1.0f;
  } else {
    if (static_cast<size_t>(gm) >= g.materials.size()) error(use, fmt::format("no material {} ({} materials)", gm, g.materials.size()));
    const tinygltf::Material& src = g.materials[static_cast<size_t>(gm)];
    const std::string field = fmt::format("materials[{}]", gm);
    const auto& pbr = src.pbrMetallicRoughness;
    if (pbr.baseColorFactor.size() != 4) error(field + ".pbrMetallicRoughness.baseColorFactor", "expected 4 numbers");
    for (double c : pbr.baseColorFactor)
      if (!(c >= 0.0 && c <= 1.0)) error(field + ".pbrMetallicRoughness.baseColorFactor", "each component must be in [0, 1]");
    if (!(pbr.roughnessFactor >= 0.0 && pbr.roughnessFactor <= 1.0))
      error(field + ".pbrMetallicRoughness.roughnessFactor", "must be in [0, 1]");
    m.name = src.name.empty() ? field : src.name;
    m.baseColor = glm::vec3(pbr.baseColorFactor[0], pbr.baseColorFactor[1], pbr.baseColorFactor[2]);
    m.roughness = static_cast<float>(pbr.roughnessFactor);
    const int texture = pbr.baseColorTexture.index;
    if (texture >= 0) {
      if (static_cast<size_t>(texture) >= g.textures.size())
        error(field + ".pbrMetallicRoughness.baseColorTexture.index", fmt::format("no texture {} ({} textures)", texture, g.textures.size()));
      const int source = g.textures[static_cast<size_t>(texture)].source;
      if (source >= 0 && static_cast<size_t>(source) >= g.images.size())
        error(fmt::format("textures[{}].source", texture), fmt::format("no image {} ({} images)", source, g.images.size()));
      if (source >= 0) m.baseColorTexture = imageFor(source, fmt::format("textures[{}]", texture));
      mUvTransforms[gm] = readTextureTransform(pbr.baseColorTexture, mFile, field + ".pbrMetallicRoughness.baseColorTexture");
    }
    const float factorAlpha = static_cast<float>(pbr.baseColorFactor[3]);
    if (src.alphaMode == "MASK") {
      const double cutoff = src.alphaCutoff;
      if (!(cutoff >= 0.0 && cutoff <= 1.0)) error(field + ".alphaCutoff", "must be in [0, 1]");
      // alpha = factor.a × texel.a < cutoff  ⇔  texel.a < cutoff / factor.a
      if (m.baseColorTexture >= 0) {
        m.alphaMask = true;
        m.alphaCutoff = factorAlpha > 0.0f ? static_cast<float>(cutoff) / factorAlpha : kAlwaysHoleCutoff;
      } else {
        invisible = factorAlpha < static_cast<float>(cutoff);  // every fragment is discarded
      }
    } else if (src.alphaMode == "BLEND") {
      // A translucent surface: the factor's alpha is the share of light it covers (below). A
      // texture's alpha cuts holes at 0.5 of its own (leaves cut out of a card); factor alpha 0 is
      // nothing at all.
      if (m.baseColorTexture >= 0) {
        m.alphaMask = true;
        m.alphaCutoff = 0.5f;
      }
      invisible = factorAlpha == 0.0f;
    } else if (src.alphaMode != "OPAQUE") {
      error(field + ".alphaMode", fmt::format("'{}' is not OPAQUE, MASK or BLEND", src.alphaMode));
    }
    // What passes through: the uncovered share (1 − alpha, BLEND only) and, of the covered share,
    // KHR_materials_transmission's factor tinted by the base colour (the glass's colour).
    const float coverage = src.alphaMode == "BLEND" ? factorAlpha : 1.0f;
    m.transmittance = glm::vec3(1.0f - coverage) + coverage * transmissionFactor(src, mFile, field) * m.baseColor;
  }
  mOut.scene.materials.push_back(std::move(m));
  const int index = static_cast<int>(mOut.scene.materials.size() - 1);
  mMaterials[gm] = {index, invisible};
  return index;
}

int Converter::meshFor(int mi, int pi) {
  if (auto it = mMeshes.find({mi, pi}); it != mMeshes.end()) return it->second;
  int& result = mMeshes[{mi, pi}];
  result = -1;
  if (mProgress) mProgress->update(mPrimitivesDone++, mPrimitivesTotal);
  const tinygltf::Primitive& p = g.meshes[static_cast<size_t>(mi)].primitives[static_cast<size_t>(pi)];
  const std::string field = fmt::format("meshes[{}].primitives[{}]", mi, pi);
  const int mode = p.mode < 0 ? TINYGLTF_MODE_TRIANGLES : p.mode;
  if (mode < TINYGLTF_MODE_TRIANGLES) return result;  // points and lines: no surface to cast or receive
  if (mode > TINYGLTF_MODE_TRIANGLE_FAN) error(field + ".mode", fmt::format("{} is not a glTF primitive mode", mode));
  bool invisible = false;
  const int material = materialFor(p.material, field + ".material", invisible);
  if (invisible) return result;
  const auto position = p.attributes.find("POSITION");
  if (position == p.attributes.end()) error(field + ".attributes", "no POSITION");
  const std::initializer_list<int> quantized = {TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_BYTE,
      TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_SHORT, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT};
  const AccessorData pos = accessor(position->second, field + ".attributes.POSITION", TINYGLTF_TYPE_VEC3, quantized);
  std::vector<uint32_t> list = readIndices(p, pos.count, field);
  const size_t n = list.size();
  if (mode == TINYGLTF_MODE_TRIANGLES && n % 3 != 0) error(field, fmt::format("{} triangle-list vertices is not a multiple of 3", n));
  const size_t triangles = mode == TINYGLTF_MODE_TRIANGLES ? n / 3 : (n < 3 ? 0 : n - 2);
  if (triangles == 0) return result;
  const auto normal = p.attributes.find("NORMAL");
  // Strips and fans become triangle lists (glTF 2.0 §3.7.2.1 gives the vertex order).
  std::vector<uint32_t> indices;
  if (mode == TINYGLTF_MODE_TRIANGLES) {
    indices = std::move(list);
  } else {
    indices.reserve(3 * triangles);
    for (size_t i = 0; i + 2 < n; ++i) {
      if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) indices.insert(indices.end(), {list[i], list[i + 1 + i % 2], list[i + 2 - i % 2]});
      else indices.insert(indices.end(), {list[i + 1], list[i + 2], list[0]});
    }
  }
  Mesh mesh;
  mesh.name = g.meshes[static_cast<size_t>(mi)].name.empty() ? field : g.meshes[static_cast<size_t>(mi)].name;
  mesh.positions.resize(pos.count);
  for (size_t i = 0; i < pos.count; ++i) {
    for (int c = 0; c < 3; ++c) mesh.positions[i][c] = static_cast<float>(pos.component(i, c));
    const glm::vec3& x = mesh.positions[i];
    if (!std::isfinite(x.x) || !std::isfinite(x.y) || !std::isfinite(x.z))
      error(fmt::format("accessors[{}]", position->second), fmt::format("position {} is not finite", i));
  }
  bool flat = normal == p.attributes.end();
  if (!flat) {
    const AccessorData nrm = accessor(normal->second, field + ".attributes.NORMAL", TINYGLTF_TYPE_VEC3,
                                      {TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_BYTE, TINYGLTF_COMPONENT_TYPE_SHORT});
    if (nrm.count != pos.count) error(field + ".attributes.NORMAL", fmt::format("{} elements, POSITION has {}", nrm.count, pos.count));
    if (nrm.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT && !nrm.normalized)
      error(fmt::format("accessors[{}]", normal->second), "a BYTE or SHORT NORMAL must be normalized (KHR_mesh_quantization)");
    mesh.normals.resize(nrm.count);
    for (size_t i = 0; i < nrm.count; ++i) {
      glm::vec3& v = mesh.normals[i];
      for (int c = 0; c < 3; ++c) v[c] = static_cast<float>(nrm.component(i, c));
      if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z))
        error(fmt::format("accessors[{}]", normal->second), fmt::format("normal {} is not finite", i));
      if (glm::dot(v, v) == 0.0f) flat = true;  // unusable for shading: use face normals instead
    }
    if (flat) mesh.normals = {};  // shaded by each triangle's plane (the G-buffer's geometric normal)
  }
  const Material& mat = mOut.scene.materials[static_cast<size_t>(material)];
  if (mat.baseColorTexture >= 0) {
    const UvTransform& transform = mUvTransforms[p.material];  // KHR_texture_transform, folded in here
    const int set = transform.texCoord.value_or(g.materials[static_cast<size_t>(p.material)].pbrMetallicRoughness.baseColorTexture.texCoord);
    const std::string name = fmt::format("TEXCOORD_{}", set);
    const auto uv = p.attributes.find(name);
    if (uv == p.attributes.end()) error(field + ".attributes", fmt::format("no {}, which its material's base colour texture uses", name));
    const AccessorData t = accessor(uv->second, field + ".attributes." + name, TINYGLTF_TYPE_VEC2,
        {TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT,
         TINYGLTF_COMPONENT_TYPE_BYTE, TINYGLTF_COMPONENT_TYPE_SHORT});
    if (t.count != pos.count) error(field + ".attributes." + name, fmt::format("{} elements, POSITION has {}", t.count, pos.count));
    mesh.uvs.resize(t.count);
    for (size_t i = 0; i < t.count; ++i) {
      glm::vec2& v = mesh.uvs[i];
      v = transform.apply(glm::vec2(static_cast<float>(t.component(i, 0)), static_cast<float>(t.component(i, 1))));
      if (!std::isfinite(v.x) || !std::isfinite(v.y)) error(fmt::format("accessors[{}]", uv->second), fmt::format("texture coordinate {} is not finite", i));
    }
  }
  mesh.indices = std::move(indices);
  if (p.indices < 0) shareCorners(mesh);
  mOut.scene.meshes.push_back(std::move(mesh));
  result = static_cast<int>(mOut.scene.meshes.size() - 1);
  return result;
}

glm::mat4 Converter::localTransform(const tinygltf::Node& n, const std::string& field) const {
  auto finite = [&](const std::vector<double>& v, size_t size, const char* key) {
    if (!v.empty() && v.size() != size) error(field + "." + key, fmt::format("expected {} numbers", size));
    for (double x : v)
      if (!std::isfinite(x) || std::abs(x) > 1e30) error(field + "." + key, "a component is not finite");
    return !v.empty();
  };
  if (finite(n.matrix, 16, "matrix")) {
    glm::mat4 m;
    for (int i = 0; i < 16; ++i) glm::value_ptr(m)[i] = static_cast<float>(n.matrix[static_cast<size_t>(i)]);  // column-major
    return m;
  }
  glm::mat4 m(1.0f);
  if (finite(n.translation, 3, "translation")) m[3] = glm::vec4(n.translation[0], n.translation[1], n.translation[2], 1.0);
  if (finite(n.rotation, 4, "rotation")) {
    glm::quat q(static_cast<float>(n.rotation[3]), static_cast<float>(n.rotation[0]), static_cast<float>(n.rotation[1]),
                static_cast<float>(n.rotation[2]));
    const float len = glm::length(q);
    if (!(len > 1e-6f)) error(field + ".rotation", "is not a rotation (zero quaternion)");
    m *= glm::mat4_cast(q / len);
  }
  if (finite(n.scale, 3, "scale")) m = glm::scale(m, glm::vec3(n.scale[0], n.scale[1], n.scale[2]));
  return m;
}

void Converter::addLight(const tinygltf::Node& node, const glm::mat4& world, int animNode, const std::string& field) {
  const auto ext = node.extensions.find("KHR_lights_punctual");
  if (ext == node.extensions.end()) return;
  const std::string lf = field + ".extensions.KHR_lights_punctual.light";
  if (!ext->second.IsObject() || !ext->second.Has("light") || !ext->second.Get("light").IsInt()) error(lf, "expected a light index");
  const int index = ext->second.Get("light").GetNumberAsInt();
  if (index < 0 || static_cast<size_t>(index) >= g.lights.size()) error(lf, fmt::format("no light {} ({} lights)", index, g.lights.size()));
  const tinygltf::Light& src = g.lights[static_cast<size_t>(index)];
  const std::string sf = fmt::format("extensions.KHR_lights_punctual.lights[{}]", index);
  Light l;
  if (!src.color.empty()) {
    if (src.color.size() != 3) error(sf + ".color", "expected 3 numbers");
    for (double c : src.color)
      if (!(c >= 0.0 && c <= kMaxRadiance)) error(sf + ".color", fmt::format("each component must be in [0, {}]", kMaxRadiance));
    l.color = glm::vec3(src.color[0], src.color[1], src.color[2]);
  }
  if (!(src.intensity >= 0.0 && src.intensity <= 1e9)) error(sf + ".intensity", "must be in [0, 1e9]");
  l.intensity = static_cast<float>(src.intensity);
  l.position = glm::vec3(world[3]);
  const glm::vec3 dir = glm::mat3(world) * glm::vec3(0.0f, 0.0f, -1.0f);  // lights shine down local -Z
  if (!(glm::length(dir) > 1e-12f) || !std::isfinite(glm::length(dir))) error(field, "the light's transform has no direction");
  l.direction = glm::normalize(dir);
  if (src.type == "directional") {
    l.type = LightType::Directional;
  } else if (src.type == "spot") {
    l.type = LightType::Spot;
    // KHR_lights_punctual: 0 <= innerConeAngle < outerConeAngle <= pi/2 (defaults 0 and pi/4).
    if (!(src.spot.outerConeAngle > 0.0 && src.spot.outerConeAngle <= 1.5707964))
      error(sf + ".spot.outerConeAngle", "must be in (0, pi/2]");
    if (!(src.spot.innerConeAngle >= 0.0 && src.spot.innerConeAngle < src.spot.outerConeAngle))
      error(sf + ".spot.innerConeAngle", "must be in [0, outerConeAngle)");
    // A cone wider than kMaxSpotConeRad keeps the light's falloff but frames the map narrower.
    l.coneAngleRad = std::clamp(static_cast<float>(src.spot.outerConeAngle), kMinConeRad, kMaxSpotConeRad);
    l.innerConeAngleRad = std::min(static_cast<float>(src.spot.innerConeAngle), l.coneAngleRad);
  } else if (src.type == "point") {
    l.type = LightType::Point;
  } else {
    error(sf + ".type", fmt::format("'{}' is not directional, spot or point", src.type));
  }
  // KHR_lights_punctual: range > 0 when given (tinygltf reads an absent one as 0: unlimited).
  if (src.type != "directional" && src.range != 0.0) {
    if (!(src.range > 0.0 && src.range <= kMaxCoordinateM)) error(sf + ".range", fmt::format("must be in (0, {}] m", kMaxCoordinateM));
    l.rangeM = static_cast<float>(src.range);
  }
  if (src.extras.IsObject() && src.extras.Has("size")) {
    const tinygltf::Value& v = src.extras.Get("size");
    const double size = v.IsNumber() ? v.GetNumberAsDouble() : -1.0;
    const double hi = l.type == LightType::Directional ? kMaxSunSizeRad : kMaxSpotSizeM;
    if (!(size >= 0.0 && size <= hi))
      error(sf + ".extras.size", fmt::format("must be a number in [0, {}] ({})", hi,
                                             l.type == LightType::Directional ? "angular radius, rad" : "sphere radius, m"));
    l.size = static_cast<float>(size);
  }
  // As scene files: the range ends outside the light's sphere (a smaller one lights nothing).
  if (l.rangeM > 0.0f && l.rangeM <= l.size)
    error(sf + ".range", fmt::format("{} m must exceed the light's size {} m (extras.size)", l.rangeM, l.size));
  if (animNode >= 0) {  // at the node's origin, shining down its -Z, wherever the node goes
    LightAnimation a;
    a.light = static_cast<uint32_t>(mOut.scene.lights.size());
    a.node = animNode;
    a.restPosition = glm::vec3(0.0f);
    a.restDirection = glm::vec3(0.0f, 0.0f, -1.0f);
    mOut.scene.animation.lights.push_back(a);
  }
  mOut.scene.lights.push_back(l);
}

void Converter::addCamera(const tinygltf::Camera& c, const glm::mat4& world, int animNode, const std::string& field) {
  if (mOut.hasCamera || c.type != "perspective") return;  // orthographic cameras are not supported: skipped
  const auto& p = c.perspective;
  if (!(p.yfov > 0.0 && p.yfov < 3.14)) error(field + ".perspective.yfov", "must be in (0, pi)");
  if (!(p.znear > 0.0 && p.znear < 1e4)) error(field + ".perspective.znear", "must be in (0, 1e4)");
  if (!(p.zfar == 0.0 || (p.zfar > p.znear && p.zfar < 1e7))) error(field + ".perspective.zfar", "must be above znear and below 1e7");
  Camera& cam = mOut.scene.camera;
  cam.position = glm::vec3(world[3]);
  const glm::vec3 forward = glm::mat3(world) * glm::vec3(0.0f, 0.0f, -1.0f);
  const glm::vec3 up = glm::mat3(world) * glm::vec3(0.0f, 1.0f, 0.0f);
  if (!(glm::length(forward) > 1e-12f && glm::length(up) > 1e-12f) || !std::isfinite(glm::length(forward) + glm::length(up)))
    error(field, "the camera's transform has no direction");
  cam.target = cam.position + glm::normalize(forward);
  cam.up = glm::normalize(up);
  cam.fovYRad = std::clamp(static_cast<float>(p.yfov), glm::radians(1.0f), glm::radians(170.0f));
  cam.nearM = static_cast<float>(p.znear);
  cam.farM = p.zfar > 0.0 ? static_cast<float>(p.zfar) : 1e6f;
  mOut.scene.animation.camera.node = animNode;
  mOut.hasCamera = true;
}

// A node at or below an animated node becomes an animation node: its objects follow it.
int Converter::addAnimatedNode(const tinygltf::Node& n, const glm::mat4& parent, int animParent, const std::string& field) {
  const auto keyed = mTracks.find(static_cast<int>(&n - g.nodes.data()));
  AnimatedNode a = makeAnimatedNode(n, keyed == mTracks.end() ? nullptr : &keyed->second, localTransform(n, field), mFile, field);
  a.parent = animParent;
  if (animParent < 0) a.offset = parent;
  mOut.scene.animation.nodes.push_back(std::move(a));
  return static_cast<int>(mOut.scene.animation.nodes.size() - 1);
}

void Converter::visit(int ni, const glm::mat4& parent, int depth, int animParent) {
  const std::string field = fmt::format("nodes[{}]", ni);
  if (ni < 0 || static_cast<size_t>(ni) >= g.nodes.size()) error(field, fmt::format("no such node ({} nodes)", g.nodes.size()));
  const auto i = static_cast<size_t>(ni);
  if (mOnPath[i]) error(field, "is its own ancestor (the node hierarchy has a cycle)");
  if (mVisited[i]) error(field, "has more than one parent (glTF nodes form trees)");
  if (depth > kMaxNodeDepth) error(field, fmt::format("the node hierarchy is deeper than {} levels", kMaxNodeDepth));
  mOnPath[i] = mVisited[i] = 1;
  const tinygltf::Node& n = g.nodes[i];
  const glm::mat4 world = parent * localTransform(n, field);
  const int animNode = animParent >= 0 || mTracks.count(ni) ? addAnimatedNode(n, parent, animParent, field) : -1;
  if (n.mesh >= 0) {
    if (static_cast<size_t>(n.mesh) >= g.meshes.size()) error(field + ".mesh", fmt::format("no mesh {} ({} meshes)", n.mesh, g.meshes.size()));
    const auto& prims = g.meshes[static_cast<size_t>(n.mesh)].primitives;
    for (size_t p = 0; p < prims.size(); ++p) {
      const int mesh = meshFor(n.mesh, static_cast<int>(p));
      if (mesh < 0) continue;
      if (mOut.scene.objects.size() >= kMaxObjects) error(field, fmt::format("more than {} placed meshes", kMaxObjects));
      bool invisible = false;
      Object o;
      o.name = (n.name.empty() ? field : n.name) + (prims.size() > 1 ? fmt::format("#{}", p) : "");
      o.mesh = static_cast<uint32_t>(mesh);
      o.material = static_cast<uint32_t>(materialFor(prims[p].material, field, invisible));
      o.worldFromObject = world;
      // A singular transform (scale 0 hides a node in glTF) draws nothing and has no normal matrix.
      if (!(std::abs(glm::determinant(glm::mat3(world))) > 0.0f)) continue;
      if (animNode >= 0)
        mOut.scene.animation.objects.push_back({static_cast<uint32_t>(mOut.scene.objects.size()), static_cast<uint32_t>(animNode), glm::mat4(1.0f)});
      mOut.scene.objects.push_back(std::move(o));
    }
  }
  if (n.camera >= 0) {
    if (static_cast<size_t>(n.camera) >= g.cameras.size()) error(field + ".camera", fmt::format("no camera {} ({} cameras)", n.camera, g.cameras.size()));
    addCamera(g.cameras[static_cast<size_t>(n.camera)], world, animNode, fmt::format("cameras[{}]", n.camera));
  }
  addLight(n, world, animNode, field);
  for (int child : n.children) visit(child, world, depth + 1, animNode);
  mOnPath[i] = 0;
}

Model Converter::run() {
  for (const std::string& ext : g.extensionsRequired)
    if (!kSupportedRequiredExtensions.count(ext)) error("extensionsRequired", fmt::format("{} is not supported", ext));
  for (const tinygltf::Mesh& m : g.meshes) mPrimitivesTotal += m.primitives.size();
  mOnPath.assign(g.nodes.size(), 0);
  mVisited.assign(g.nodes.size(), 0);
  std::vector<int> roots;
  if (!g.scenes.empty()) {
    const int s = g.defaultScene < 0 ? 0 : g.defaultScene;
    if (static_cast<size_t>(s) >= g.scenes.size()) error("scene", fmt::format("no scene {} ({} scenes)", s, g.scenes.size()));
    roots = g.scenes[static_cast<size_t>(s)].nodes;
  } else {  // no scenes: every node without a parent is a root
    std::vector<uint8_t> child(g.nodes.size(), 0);
    for (const tinygltf::Node& n : g.nodes)
      for (int c : n.children)
        if (c >= 0 && static_cast<size_t>(c) < child.size()) child[static_cast<size_t>(c)] = 1;
    for (size_t i = 0; i < g.nodes.size(); ++i)
      if (!child[i]) roots.push_back(static_cast<int>(i));
  }
  mTracks = readGltfAnimations(g, mFile, [this](int index, int type, const std::string& use) {
    // Key times (the SCALAR input) are floats (glTF 2.0 §3.11); rotations may be normalized integers.
    const AccessorData a = type == TINYGLTF_TYPE_SCALAR
                               ? accessor(index, use, type, {TINYGLTF_COMPONENT_TYPE_FLOAT})
                               : accessor(index, use, type,
                                          {TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE,
                                           TINYGLTF_COMPONENT_TYPE_SHORT, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT});
    std::vector<float> out;
    out.reserve(a.count * static_cast<size_t>(a.components));
    for (size_t i = 0; i < a.count; ++i)
      for (int c = 0; c < a.components; ++c) out.push_back(static_cast<float>(a.component(i, c)));
    return out;
  });
  checkMemory();
  for (int r : roots) visit(r, glm::mat4(1.0f), 0, -1);
  if (mOut.scene.objects.empty() || mOut.scene.triangleCount() == 0)
    error("", "the scene places no triangles (no mesh node with triangle primitives)");
  mOut.scene.name = mFile;
  return std::move(mOut);
}

}  // namespace

Model convertGltf(const tinygltf::Model& model, const std::string& file, ProgressReport* progress) {
  return Converter(model, file, progress).run();
}

}  // namespace penumbra::loaders
