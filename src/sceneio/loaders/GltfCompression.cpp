// KHR_draco_mesh_compression and EXT_meshopt_compression (GltfCompression.h). The decoders are
// the reference ones (Draco, meshoptimizer; both fuzzed upstream); everything they are handed
// and everything they return is checked here first: buffer ranges, counts against the limits
// and the accessors, Draco's attribute and face indices before any is read.
#include "sceneio/loaders/GltfCompression.h"

#include "sceneio/loaders/ModelImport.h"

#include "sceneio/loaders/TinyGltf.h"

#include <draco/compression/decode.h>
#include <fmt/format.h>
#include <meshoptimizer.h>

#include <cstring>
#include <new>
#include <optional>
#include <set>

namespace penumbra::loaders {
namespace {

using Json = nlohmann::json;

const char* const kDraco = "KHR_draco_mesh_compression";
const char* const kMeshopt = "EXT_meshopt_compression";
// A buffer tinygltf can load in place of meshopt's fallback buffer, which has no data: one byte.
const char* const kPlaceholderUri = "data:application/octet-stream;base64,AA==";
// meshoptimizer's vertex codec works on elements of 4..256 bytes in steps of 4; indices are 2 or
// 4 bytes (EXT_meshopt_compression).
constexpr uint64_t kMaxMeshoptStride = 256;

const Json* extension(const Json& o, const char* name) {
  if (!o.is_object() || !o.contains("extensions") || !o["extensions"].is_object() || !o["extensions"].contains(name)) return nullptr;
  return &o["extensions"][name];
}

uint64_t unsignedMember(const Json& o, const char* key, const std::string& field, const std::string& file,
                        std::optional<uint64_t> def = std::nullopt) {
  if (!o.contains(key)) {
    if (def) return *def;
    fail(file, field + "." + key, "missing (a non-negative integer)");
  }
  if (!o[key].is_number_unsigned()) fail(file, field + "." + key, "expected a non-negative integer");
  return o[key].get<uint64_t>();
}

void prepareDraco(Json& doc, const std::string& file, CompressedParts& parts) {
  if (!doc.contains("meshes")) return;
  for (size_t m = 0; m < doc["meshes"].size(); ++m) {
    Json& prims = doc["meshes"][m]["primitives"];
    for (size_t p = 0; p < prims.size(); ++p) {
      Json& prim = prims[p];
      const Json* e = extension(prim, kDraco);
      if (!e) continue;
      const std::string pf = fmt::format("meshes[{}].primitives[{}]", m, p), field = pf + ".extensions." + kDraco;
      if (!e->is_object()) fail(file, field, "expected an object");
      DracoPrimitive d;
      d.mesh = m;
      d.primitive = p;
      d.bufferView = unsignedMember(*e, "bufferView", field, file);
      if (!e->contains("attributes") || !(*e)["attributes"].is_object()) fail(file, field + ".attributes", "expected an object");
      for (const auto& [name, id] : (*e)["attributes"].items())
        d.attributes.emplace_back(name, unsignedMember((*e)["attributes"], name.c_str(), field + ".attributes", file));
      // The indices accessor of a compressed primitive has no buffer view, which tinygltf refuses.
      if (prim.contains("indices")) {
        d.indices = static_cast<int64_t>(prim["indices"].get<uint64_t>());  // checked by GltfDocument.cpp
        const size_t accessors = doc.contains("accessors") ? doc["accessors"].size() : 0;
        if (static_cast<size_t>(d.indices) >= accessors)
          fail(file, pf + ".indices", fmt::format("no accessor {} ({} accessors)", d.indices, accessors));
        if (!doc["accessors"][static_cast<size_t>(d.indices)].contains("bufferView")) {
          prim.erase("indices");
          parts.rewritten = true;
        }
      }
      const uint64_t mode = prim.contains("mode") ? prim["mode"].get<uint64_t>() : TINYGLTF_MODE_TRIANGLES;
      if (mode < TINYGLTF_MODE_TRIANGLES) continue;  // points and lines draw nothing: not decoded
      if (mode != TINYGLTF_MODE_TRIANGLES) fail(file, pf + ".mode", fmt::format("{}: a Draco primitive is a triangle list (mode 4)", mode));
      parts.draco.push_back(std::move(d));
    }
  }
}

void prepareMeshopt(Json& doc, const std::string& file, CompressedParts& parts) {
  std::set<size_t> fallbacks;  // buffers that exist only as meshopt's uncompressed stand-ins
  if (doc.contains("buffers"))
    for (size_t b = 0; b < doc["buffers"].size(); ++b) {
      Json& buffer = doc["buffers"][b];
      const Json* e = extension(buffer, kMeshopt);
      if (!e || !e->is_object() || !e->contains("fallback") || (*e)["fallback"] != true) continue;
      fallbacks.insert(b);
      if (buffer.contains("uri")) continue;  // it has data of its own: tinygltf loads it
      buffer["uri"] = kPlaceholderUri;
      buffer["byteLength"] = 1;
      parts.rewritten = true;
    }
  if (!doc.contains("bufferViews")) return;
  const size_t buffers = doc.contains("buffers") ? doc["buffers"].size() : 0;
  for (size_t i = 0; i < doc["bufferViews"].size(); ++i) {
    const Json& view = doc["bufferViews"][i];
    const std::string vf = fmt::format("bufferViews[{}]", i);
    const Json* e = extension(view, kMeshopt);
    if (!e) {
      if (fallbacks.count(view["buffer"].get<uint64_t>()))
        fail(file, vf, fmt::format("its buffer is {}'s fallback, which holds no data, and the view is not compressed", kMeshopt));
      continue;
    }
    const std::string field = vf + ".extensions." + kMeshopt;
    if (!e->is_object()) fail(file, field, "expected an object");
    MeshoptView m;
    m.view = i;
    m.buffer = unsignedMember(*e, "buffer", field, file);
    m.byteOffset = unsignedMember(*e, "byteOffset", field, file, 0);
    m.byteLength = unsignedMember(*e, "byteLength", field, file);
    m.byteStride = unsignedMember(*e, "byteStride", field, file);
    m.count = unsignedMember(*e, "count", field, file);
    if (!e->contains("mode") || !(*e)["mode"].is_string()) fail(file, field + ".mode", "expected ATTRIBUTES, TRIANGLES or INDICES");
    m.mode = (*e)["mode"].get<std::string>();
    m.filter = e->contains("filter") && (*e)["filter"].is_string() ? (*e)["filter"].get<std::string>() : "NONE";
    if (e->contains("filter") && !(*e)["filter"].is_string()) fail(file, field + ".filter", "expected a name");
    if (m.buffer >= buffers) fail(file, field + ".buffer", fmt::format("no buffer {} ({} buffers)", m.buffer, buffers));
    if (m.mode == "ATTRIBUTES") {
      if (m.byteStride == 0 || m.byteStride % 4 != 0 || m.byteStride > kMaxMeshoptStride)
        fail(file, field + ".byteStride", fmt::format("{}: vertex data needs a multiple of 4 up to {}", m.byteStride, kMaxMeshoptStride));
    } else if (m.mode == "TRIANGLES" || m.mode == "INDICES") {
      if (m.byteStride != 2 && m.byteStride != 4) fail(file, field + ".byteStride", fmt::format("{}: indices are 2 or 4 bytes", m.byteStride));
      if (m.mode == "TRIANGLES" && m.count % 3 != 0) fail(file, field + ".count", fmt::format("{} is not a multiple of 3", m.count));
      if (m.filter != "NONE") fail(file, field + ".filter", fmt::format("'{}': only vertex data is filtered", m.filter));
    } else {
      fail(file, field + ".mode", fmt::format("'{}' is not ATTRIBUTES, TRIANGLES or INDICES", m.mode));
    }
    if (m.filter != "NONE" && m.filter != "OCTAHEDRAL" && m.filter != "QUATERNION" && m.filter != "EXPONENTIAL")
      fail(file, field + ".filter", fmt::format("'{}' is not NONE, OCTAHEDRAL, QUATERNION or EXPONENTIAL", m.filter));
    if ((m.filter == "OCTAHEDRAL" && m.byteStride != 4 && m.byteStride != 8) || (m.filter == "QUATERNION" && m.byteStride != 8))
      fail(file, field + ".byteStride", fmt::format("{} does not fit the {} filter", m.byteStride, m.filter));
    if (m.count > kMaxDecompressedBytes / m.byteStride)
      fail(file, field + ".count", fmt::format("{} elements of {} bytes: more than the {} bytes decompressed data may take", m.count,
                                               m.byteStride, kMaxDecompressedBytes));
    if (view["byteLength"].get<uint64_t>() != m.count * m.byteStride)
      fail(file, vf + ".byteLength", fmt::format("{}, but {} elements of {} bytes decompress to {}", view["byteLength"].get<uint64_t>(),
                                                 m.count, m.byteStride, m.count * m.byteStride));
    if (m.mode == "ATTRIBUTES" && view.contains("byteStride") && view["byteStride"].get<uint64_t>() != m.byteStride)
      fail(file, vf + ".byteStride", fmt::format("{}, the compressed data's is {}", view["byteStride"].get<uint64_t>(), m.byteStride));
    parts.meshopt.push_back(std::move(m));
  }
}

/// Appends `data` as a new buffer and a view of all of it; returns the view's index.
int addView(tinygltf::Model& model, std::vector<unsigned char> data, size_t stride) {
  tinygltf::Buffer buffer;
  buffer.data = std::move(data);
  tinygltf::BufferView view;
  view.buffer = static_cast<int>(model.buffers.size());
  view.byteOffset = 0;
  view.byteLength = buffer.data.size();
  view.byteStride = stride;
  model.buffers.push_back(std::move(buffer));
  model.bufferViews.push_back(std::move(view));
  return static_cast<int>(model.bufferViews.size() - 1);
}

int addAccessor(tinygltf::Model& model, int view, int componentType, int type, size_t count) {
  tinygltf::Accessor a;
  a.bufferView = view;
  a.byteOffset = 0;
  a.componentType = componentType;
  a.type = type;
  a.count = count;
  a.normalized = false;
  model.accessors.push_back(std::move(a));
  return static_cast<int>(model.accessors.size() - 1);
}

/// The bytes [offset, offset + length) of buffer `index`, checked against what tinygltf loaded.
const unsigned char* bufferBytes(const tinygltf::Model& model, uint64_t index, uint64_t offset, uint64_t length,
                                 const std::string& file, const std::string& field) {
  if (index >= model.buffers.size()) fail(file, field, fmt::format("no buffer {} ({} buffers)", index, model.buffers.size()));
  const std::vector<unsigned char>& data = model.buffers[index].data;
  if (offset > data.size() || length > data.size() - offset)
    fail(file, field, fmt::format("bytes {}..{} run past the end of buffers[{}] ({} bytes loaded)", offset, offset + length, index, data.size()));
  return data.data() + offset;
}

void decodeMeshopt(tinygltf::Model& model, const MeshoptView& m, const std::string& file, uint64_t& total) {
  const std::string field = fmt::format("bufferViews[{}].extensions.{}", m.view, kMeshopt);
  const unsigned char* src = bufferBytes(model, m.buffer, m.byteOffset, m.byteLength, file, field);
  const size_t size = m.count * m.byteStride;  // bounded by kMaxDecompressedBytes (prepareMeshopt)
  total += size;
  if (total > kMaxDecompressedBytes) fail(file, field, fmt::format("decompressed data would take more than {} bytes", kMaxDecompressedBytes));
  std::vector<unsigned char> out(size);
  int status = 0;
  if (m.mode == "ATTRIBUTES") status = meshopt_decodeVertexBuffer(out.data(), m.count, m.byteStride, src, m.byteLength);
  else if (m.mode == "TRIANGLES") status = meshopt_decodeIndexBuffer(out.data(), m.count, m.byteStride, src, m.byteLength);
  else status = meshopt_decodeIndexSequence(out.data(), m.count, m.byteStride, src, m.byteLength);
  if (status != 0) fail(file, field, fmt::format("meshoptimizer cannot decode it as {} (error {})", m.mode, status));
  if (m.filter == "OCTAHEDRAL") meshopt_decodeFilterOct(out.data(), m.count, m.byteStride);
  else if (m.filter == "QUATERNION") meshopt_decodeFilterQuat(out.data(), m.count, m.byteStride);
  else if (m.filter == "EXPONENTIAL") meshopt_decodeFilterExp(out.data(), m.count, m.byteStride);
  // The view now reads the decoded bytes (its stride, if any, is the compressed data's).
  tinygltf::Buffer decoded;
  decoded.data = std::move(out);
  model.buffers.push_back(std::move(decoded));
  tinygltf::BufferView& view = model.bufferViews[m.view];
  view.buffer = static_cast<int>(model.buffers.size() - 1);
  view.byteOffset = 0;
  view.byteLength = size;
}

/// Components Penumbra reads of a decoded attribute; 0: an attribute it does not read.
int componentsOf(const std::string& name) {
  if (name == "POSITION" || name == "NORMAL") return 3;
  if (name.rfind("TEXCOORD_", 0) == 0) return 2;
  return 0;
}

void decodeDraco(tinygltf::Model& model, const DracoPrimitive& d, const std::string& file, uint64_t& total) {
  const std::string pf = fmt::format("meshes[{}].primitives[{}]", d.mesh, d.primitive), field = pf + ".extensions." + kDraco;
  if (d.mesh >= model.meshes.size() || d.primitive >= model.meshes[d.mesh].primitives.size()) fail(file, pf, "not loaded");
  tinygltf::Primitive& prim = model.meshes[d.mesh].primitives[d.primitive];
  if (d.bufferView >= model.bufferViews.size())
    fail(file, field + ".bufferView", fmt::format("no buffer view {} ({} views)", d.bufferView, model.bufferViews.size()));
  const tinygltf::BufferView& view = model.bufferViews[d.bufferView];
  const uint64_t buffer = view.buffer < 0 ? UINT64_MAX : static_cast<uint64_t>(view.buffer);
  const unsigned char* bytes = bufferBytes(model, buffer, view.byteOffset, view.byteLength, file, fmt::format("bufferViews[{}]", d.bufferView));
  draco::DecoderBuffer in;
  in.Init(reinterpret_cast<const char*>(bytes), view.byteLength);
  std::unique_ptr<draco::Mesh> mesh;
  try {
    const draco::StatusOr<draco::EncodedGeometryType> type = draco::Decoder::GetEncodedGeometryType(&in);
    if (!type.ok() || type.value() != draco::TRIANGULAR_MESH)
      fail(file, field, type.ok() ? "the Draco data is not a triangle mesh" : "not Draco data (" + type.status().error_msg_string() + ")");
    draco::Decoder decoder;
    draco::StatusOr<std::unique_ptr<draco::Mesh>> result = decoder.DecodeMeshFromBuffer(&in);
    if (!result.ok()) fail(file, field, "Draco cannot decode it (" + result.status().error_msg_string() + ")");
    mesh = std::move(result).value();
  } catch (const std::bad_alloc&) {
    fail(file, field, "the Draco data asks for more memory than there is");
  }
  const size_t points = mesh->num_points(), faces = mesh->num_faces();
  if (points > UINT32_MAX || 3 * faces > UINT32_MAX)
    fail(file, field, fmt::format("{} points and {} triangles: more than 32-bit indices can number", points, faces));
  total += faces * 12 + points * 4 * 8;  // at most: the indices and 8 floats of attributes per point
  if (total > kMaxDecompressedBytes) fail(file, field, fmt::format("decompressed data would take more than {} bytes", kMaxDecompressedBytes));

  std::vector<unsigned char> indices(faces * 3 * sizeof(uint32_t));
  for (size_t f = 0; f < faces; ++f) {
    const draco::Mesh::Face& face = mesh->face(draco::FaceIndex(static_cast<uint32_t>(f)));
    for (int c = 0; c < 3; ++c) {
      const uint32_t v = face[c].value();
      if (v >= points) fail(file, field, fmt::format("triangle {} uses point {} ({} points)", f, v, points));
      std::memcpy(indices.data() + (3 * f + static_cast<size_t>(c)) * sizeof(uint32_t), &v, sizeof v);
    }
  }
  if (d.indices >= 0 && model.accessors[static_cast<size_t>(d.indices)].count != 3 * faces)
    fail(file, fmt::format("accessors[{}].count", d.indices), fmt::format("{}, the Draco mesh has {} triangles ({} indices)",
                                                                           model.accessors[static_cast<size_t>(d.indices)].count, faces, 3 * faces));
  prim.indices = addAccessor(model, addView(model, std::move(indices), 0), TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, TINYGLTF_TYPE_SCALAR, 3 * faces);

  for (const auto& [name, id] : d.attributes) {
    const std::string af = field + ".attributes." + name;
    const auto it = prim.attributes.find(name);
    if (it == prim.attributes.end()) fail(file, af, "the primitive has no such attribute");
    const int components = componentsOf(name);
    if (components == 0) {  // colours, joints, weights, tangents: Penumbra reads none, so none is decoded
      prim.attributes.erase(it);
      continue;
    }
    if (it->second < 0 || static_cast<size_t>(it->second) >= model.accessors.size())
      fail(file, pf + ".attributes." + name, fmt::format("no accessor {} ({} accessors)", it->second, model.accessors.size()));
    const tinygltf::Accessor& accessor = model.accessors[static_cast<size_t>(it->second)];
    const std::string accessorField = fmt::format("accessors[{}]", it->second);
    if (accessor.type != components) fail(file, accessorField + ".type", fmt::format("{} needs VEC{}", name, components));
    if (accessor.count != points) fail(file, accessorField + ".count", fmt::format("{}, the Draco mesh has {} points", accessor.count, points));
    const draco::PointAttribute* att = id <= UINT32_MAX ? mesh->GetAttributeByUniqueId(static_cast<uint32_t>(id)) : nullptr;
    if (!att) fail(file, af, fmt::format("the Draco data has no attribute {}", id));
    if (!att->is_mapping_identity() && att->indices_map_size() < points)
      fail(file, af, fmt::format("the Draco attribute maps {} of {} points", att->indices_map_size(), points));
    std::vector<unsigned char> values(points * static_cast<size_t>(components) * sizeof(float));
    float value[4] = {0, 0, 0, 0};
    for (size_t i = 0; i < points; ++i) {
      const draco::AttributeValueIndex index = att->mapped_index(draco::PointIndex(static_cast<uint32_t>(i)));
      if (index.value() >= att->size() || !att->ConvertValue<float>(index, static_cast<int8_t>(components), value))
        fail(file, af, fmt::format("point {} has no value", i));
      std::memcpy(values.data() + i * static_cast<size_t>(components) * sizeof(float), value, static_cast<size_t>(components) * sizeof(float));
    }
    it->second = addAccessor(model, addView(model, std::move(values), 0), TINYGLTF_COMPONENT_TYPE_FLOAT, components, points);
  }
  prim.mode = TINYGLTF_MODE_TRIANGLES;
}

}  // namespace

CompressedParts prepareCompressed(Json& doc, const std::string& file) {
  CompressedParts parts;
  prepareDraco(doc, file, parts);
  prepareMeshopt(doc, file, parts);
  return parts;
}

void decompress(tinygltf::Model& model, const CompressedParts& parts, const std::string& file) {
  uint64_t total = 0;
  // Views first: a Draco primitive's data could itself sit in a meshopt-compressed view.
  for (const MeshoptView& m : parts.meshopt) decodeMeshopt(model, m, file, total);
  for (const DracoPrimitive& d : parts.draco) decodeDraco(model, d, file, total);
}

}  // namespace penumbra::loaders
