// Compressed glTF test models (CompressedModels.h).
#include "CompressedModels.h"

#include <draco/compression/decode.h>
#include <draco/compression/encode.h>
#include <draco/mesh/triangle_soup_mesh_builder.h>
#include <meshoptimizer.h>
#include <nlohmann/json.hpp>

#include <cstring>
#include <stdexcept>

namespace penumbra::test {
namespace {

using Json = nlohmann::json;

constexpr float kBoxHalfM = 0.5f, kGroundHalfM = 3.0f;
// Draco's quantisation, as its glTF tools default to (bits per component).
constexpr int kDracoPositionBits = 14, kDracoNormalBits = 10, kDracoUvBits = 12;
constexpr int kOctahedralBits = 10;  // meshopt's normal filter, as gltfpack's default

void quad(BoxGeometry::Part& p, const float c[3], const float u[3], const float v[3], const float n[3]) {
  const auto base = static_cast<uint32_t>(p.positions.size() / 3);
  const float su[4] = {-1, 1, 1, -1}, sv[4] = {-1, -1, 1, 1};
  for (int k = 0; k < 4; ++k) {
    for (int i = 0; i < 3; ++i) p.positions.push_back(c[i] + su[k] * u[i] + sv[k] * v[i]);
    p.normals.insert(p.normals.end(), n, n + 3);
    p.uvs.push_back((su[k] + 1) / 2);
    p.uvs.push_back((1 - sv[k]) / 2);
  }
  for (uint32_t i : {0u, 1u, 2u, 0u, 2u, 3u}) p.indices.push_back(base + i);
}

/// A GLB: the document with buffers[0] = the BIN chunk `bin`.
std::vector<uint8_t> glb(Json doc, std::vector<uint8_t> bin) {
  while (bin.size() % 4) bin.push_back(0);
  doc["buffers"][0]["byteLength"] = bin.size();
  std::string text = doc.dump();
  while (text.size() % 4) text += ' ';
  std::vector<uint8_t> out;
  auto u32 = [&](uint32_t v) { for (int i = 0; i < 4; ++i) out.push_back(static_cast<uint8_t>(v >> (8 * i))); };
  u32(0x46546C67);
  u32(2);
  u32(static_cast<uint32_t>(12 + 8 + text.size() + 8 + bin.size()));
  u32(static_cast<uint32_t>(text.size()));
  u32(0x4E4F534A);
  out.insert(out.end(), text.begin(), text.end());
  u32(static_cast<uint32_t>(bin.size()));
  u32(0x004E4942);
  out.insert(out.end(), bin.begin(), bin.end());
  return out;
}

/// Builds the document around the parts: a light, a camera, a node per part.
struct Builder {
  Json doc = Json::object();
  std::vector<uint8_t> bin;

  Builder() {
    doc["asset"] = {{"version", "2.0"}, {"generator", "penumbra tests/support/CompressedModels.cpp"}};
    doc["buffers"] = Json::array({Json::object()});
    doc["bufferViews"] = Json::array();
    doc["accessors"] = Json::array();
    doc["meshes"] = Json::array();
    doc["materials"] = Json::array({{{"name", "box"}, {"pbrMetallicRoughness", {{"baseColorFactor", {0.8, 0.2, 0.1, 1.0}}}}},
                                    {{"name", "ground"}, {"pbrMetallicRoughness", {{"baseColorFactor", {0.7, 0.7, 0.7, 1.0}}}}}});
    doc["extensionsUsed"] = Json::array({"KHR_lights_punctual"});
    doc["extensions"] = {{"KHR_lights_punctual", {{"lights", Json::array({{{"type", "directional"}, {"intensity", 3.0}}})}}}};
    doc["cameras"] = Json::array({{{"type", "perspective"}, {"perspective", {{"yfov", 0.8}, {"znear", 0.1}, {"zfar", 100.0}}}}});
    // The sun shines toward +x, 35° above the horizon (local -Z turned -35° about X, then -90°
    // about Y), so the box's shadow falls to its right; the camera looks down 35° from (0, 4, 7).
    doc["nodes"] = Json::array({{{"mesh", 0}, {"name", "box"}, {"translation", {0.0, kBoxHalfM, 0.0}}},
                                {{"mesh", 1}, {"name", "ground"}},
                                {{"name", "sun"}, {"rotation", {-0.2126311, -0.6743798, -0.2126311, 0.6743798}},
                                 {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}},
                                {{"name", "camera"}, {"camera", 0}, {"translation", {0.0, 4.0, 7.0}},
                                 {"rotation", {-0.3007058, 0.0, 0.0, 0.9537169}}}});
    doc["scenes"] = Json::array({{{"nodes", {0, 1, 2, 3}}}});
    doc["scene"] = 0;
  }
  size_t view(const void* data, size_t bytes, size_t stride = 0) {
    while (bin.size() % 4) bin.push_back(0);
    Json v = {{"buffer", 0}, {"byteOffset", bin.size()}, {"byteLength", bytes}};
    if (stride) v["byteStride"] = stride;
    const auto* p = static_cast<const uint8_t*>(data);
    bin.insert(bin.end(), p, p + bytes);
    doc["bufferViews"].push_back(v);
    return doc["bufferViews"].size() - 1;
  }
  size_t accessor(Json a) {
    doc["accessors"].push_back(std::move(a));
    return doc["accessors"].size() - 1;
  }
  void mesh(const char* name, Json primitive) { doc["meshes"].push_back({{"name", name}, {"primitives", Json::array({primitive})}}); }
};

Json minMax(const std::vector<float>& p) {
  Json lo = {p[0], p[1], p[2]}, hi = lo;
  for (size_t i = 0; i < p.size(); ++i) {
    lo[i % 3] = std::min(lo[i % 3].get<float>(), p[i]);
    hi[i % 3] = std::max(hi[i % 3].get<float>(), p[i]);
  }
  return {{"min", lo}, {"max", hi}};
}

/// Plain float accessors (no bufferView when `views` is false: a Draco primitive's).
Json plainPrimitive(Builder& b, const BoxGeometry::Part& p, int material, bool views) {
  const size_t n = p.positions.size() / 3;
  auto acc = [&](const std::vector<float>& data, const char* type) {
    Json a = {{"componentType", 5126}, {"count", n}, {"type", type}};
    if (views) a["bufferView"] = b.view(data.data(), data.size() * 4);
    return a;
  };
  Json pos = acc(p.positions, "VEC3");
  pos.update(minMax(p.positions));
  Json idx = {{"componentType", 5125}, {"count", p.indices.size()}, {"type", "SCALAR"}};
  if (views) idx["bufferView"] = b.view(p.indices.data(), p.indices.size() * 4);
  return {{"attributes", {{"POSITION", b.accessor(pos)}, {"NORMAL", b.accessor(acc(p.normals, "VEC3"))},
                          {"TEXCOORD_0", b.accessor(acc(p.uvs, "VEC2"))}}},
          {"indices", b.accessor(idx)}, {"material", material}};
}

Json dracoPrimitive(Builder& b, const BoxGeometry::Part& p, int material) {
  const int faces = static_cast<int>(p.indices.size() / 3);
  draco::TriangleSoupMeshBuilder mb;
  mb.Start(faces);
  const int pos = mb.AddAttribute(draco::GeometryAttribute::POSITION, 3, draco::DT_FLOAT32);
  const int nrm = mb.AddAttribute(draco::GeometryAttribute::NORMAL, 3, draco::DT_FLOAT32);
  const int uv = mb.AddAttribute(draco::GeometryAttribute::TEX_COORD, 2, draco::DT_FLOAT32);
  for (int f = 0; f < faces; ++f) {
    const uint32_t* c = &p.indices[3 * static_cast<size_t>(f)];
    const draco::FaceIndex face(static_cast<uint32_t>(f));
    mb.SetAttributeValuesForFace(pos, face, &p.positions[3 * c[0]], &p.positions[3 * c[1]], &p.positions[3 * c[2]]);
    mb.SetAttributeValuesForFace(nrm, face, &p.normals[3 * c[0]], &p.normals[3 * c[1]], &p.normals[3 * c[2]]);
    mb.SetAttributeValuesForFace(uv, face, &p.uvs[2 * c[0]], &p.uvs[2 * c[1]], &p.uvs[2 * c[2]]);
  }
  const std::unique_ptr<draco::Mesh> mesh = mb.Finalize();
  draco::Encoder encoder;
  encoder.SetAttributeQuantization(draco::GeometryAttribute::POSITION, kDracoPositionBits);
  encoder.SetAttributeQuantization(draco::GeometryAttribute::NORMAL, kDracoNormalBits);
  encoder.SetAttributeQuantization(draco::GeometryAttribute::TEX_COORD, kDracoUvBits);
  draco::EncoderBuffer encoded;
  if (!encoder.EncodeMeshToBuffer(*mesh, &encoded).ok()) throw std::runtime_error("Draco could not encode the test mesh");
  // The accessors carry the decoded counts (the encoder may merge and reorder points).
  draco::DecoderBuffer in;
  in.Init(encoded.data(), encoded.size());
  draco::Decoder decoder;
  const std::unique_ptr<draco::Mesh> decoded = decoder.DecodeMeshFromBuffer(&in).value();
  const size_t view = b.view(encoded.data(), encoded.size());
  Json prim = plainPrimitive(b, p, material, false);
  for (const char* name : {"POSITION", "NORMAL", "TEXCOORD_0"}) b.doc["accessors"][prim["attributes"][name].get<size_t>()]["count"] = decoded->num_points();
  prim["extensions"] = {{"KHR_draco_mesh_compression", {{"bufferView", view}, {"attributes", {
      {"POSITION", mesh->attribute(pos)->unique_id()}, {"NORMAL", mesh->attribute(nrm)->unique_id()},
      {"TEXCOORD_0", mesh->attribute(uv)->unique_id()}}}}}};
  return prim;
}

/// A meshopt-compressed view in buffer 0, standing in for `bytes` of `stride`-byte elements in
/// the fallback buffer 1.
size_t meshoptView(Builder& b, const std::vector<uint8_t>& compressed, size_t count, size_t stride, const char* mode,
                   const char* filter, size_t& fallbackBytes) {
  const size_t v = b.view(compressed.data(), compressed.size());
  Json& view = b.doc["bufferViews"][v];
  Json ext = {{"buffer", 0}, {"byteOffset", view["byteOffset"]}, {"byteLength", compressed.size()},
              {"byteStride", stride}, {"count", count}, {"mode", mode}};
  if (std::strcmp(filter, "NONE") != 0) ext["filter"] = filter;
  view = {{"buffer", 1}, {"byteOffset", fallbackBytes}, {"byteLength", count * stride}, {"extensions", {{"EXT_meshopt_compression", ext}}}};
  if (std::strcmp(mode, "ATTRIBUTES") == 0) view["byteStride"] = stride;
  fallbackBytes += (count * stride + 3) / 4 * 4;
  return v;
}

Json meshoptPrimitive(Builder& b, const BoxGeometry::Part& p, int material, size_t& fallbackBytes) {
  const size_t n = p.positions.size() / 3;
  auto vertices = [&](const void* data, size_t stride) {
    std::vector<uint8_t> out(meshopt_encodeVertexBufferBound(n, stride));
    out.resize(meshopt_encodeVertexBuffer(out.data(), out.size(), data, n, stride));
    return out;
  };
  // Positions as floats; normals through the octahedral filter (4 bytes each); uvs as floats.
  std::vector<int8_t> octahedral(n * 4);
  std::vector<float> normals4(n * 4);
  for (size_t i = 0; i < n; ++i) std::memcpy(&normals4[4 * i], &p.normals[3 * i], 12);
  meshopt_encodeFilterOct(octahedral.data(), n, 4, 8, normals4.data());
  std::vector<uint8_t> indices(meshopt_encodeIndexBufferBound(p.indices.size(), n));
  indices.resize(meshopt_encodeIndexBuffer(indices.data(), indices.size(), p.indices.data(), p.indices.size()));
  Json pos = {{"bufferView", meshoptView(b, vertices(p.positions.data(), 12), n, 12, "ATTRIBUTES", "NONE", fallbackBytes)},
              {"componentType", 5126}, {"count", n}, {"type", "VEC3"}};
  pos.update(minMax(p.positions));
  const Json nrm = {{"bufferView", meshoptView(b, vertices(octahedral.data(), 4), n, 4, "ATTRIBUTES", "OCTAHEDRAL", fallbackBytes)},
                    {"componentType", 5120}, {"normalized", true}, {"count", n}, {"type", "VEC3"}};
  const Json uv = {{"bufferView", meshoptView(b, vertices(p.uvs.data(), 8), n, 8, "ATTRIBUTES", "NONE", fallbackBytes)},
                   {"componentType", 5126}, {"count", n}, {"type", "VEC2"}};
  const Json idx = {{"bufferView", meshoptView(b, indices, p.indices.size(), 4, "TRIANGLES", "NONE", fallbackBytes)},
                    {"componentType", 5125}, {"count", p.indices.size()}, {"type", "SCALAR"}};
  return {{"attributes", {{"POSITION", b.accessor(pos)}, {"NORMAL", b.accessor(nrm)}, {"TEXCOORD_0", b.accessor(uv)}}},
          {"indices", b.accessor(idx)}, {"material", material}};
}

/// The Draco and meshopt documents before they become GLB files.
Builder dracoBuilder() {
  const BoxGeometry g = boxGeometry();
  Builder b;
  b.mesh("box", dracoPrimitive(b, g.box, 0));
  b.mesh("ground", dracoPrimitive(b, g.ground, 1));
  b.doc["extensionsUsed"].push_back("KHR_draco_mesh_compression");
  b.doc["extensionsRequired"] = Json::array({"KHR_draco_mesh_compression"});
  return b;
}

Builder meshoptBuilder() {
  const BoxGeometry g = boxGeometry();
  Builder b;
  size_t fallbackBytes = 0;
  b.mesh("box", meshoptPrimitive(b, g.box, 0, fallbackBytes));
  b.mesh("ground", meshoptPrimitive(b, g.ground, 1, fallbackBytes));
  b.doc["buffers"].push_back({{"byteLength", fallbackBytes}, {"extensions", {{"EXT_meshopt_compression", {{"fallback", true}}}}}});
  b.doc["extensionsUsed"].push_back("EXT_meshopt_compression");
  b.doc["extensionsRequired"] = Json::array({"EXT_meshopt_compression"});
  return b;
}

}  // namespace

BoxGeometry boxGeometry() {
  BoxGeometry g;
  const float h = kBoxHalfM;
  const float faces[6][3][3] = {{{0, 0, h}, {h, 0, 0}, {0, h, 0}},   {{0, 0, -h}, {-h, 0, 0}, {0, h, 0}}, {{h, 0, 0}, {0, 0, -h}, {0, h, 0}},
                                {{-h, 0, 0}, {0, 0, h}, {0, h, 0}},  {{0, h, 0}, {h, 0, 0}, {0, 0, -h}}, {{0, -h, 0}, {h, 0, 0}, {0, 0, h}}};
  for (const auto& f : faces) {
    const float n[3] = {f[0][0] / h, f[0][1] / h, f[0][2] / h};
    quad(g.box, f[0], f[1], f[2], n);
  }
  const float c[3] = {0, 0, 0}, u[3] = {kGroundHalfM, 0, 0}, v[3] = {0, 0, -kGroundHalfM}, up[3] = {0, 1, 0};
  quad(g.ground, c, u, v, up);
  return g;
}

std::vector<uint8_t> plainBoxGlb() {
  const BoxGeometry g = boxGeometry();
  Builder b;
  b.mesh("box", plainPrimitive(b, g.box, 0, true));
  b.mesh("ground", plainPrimitive(b, g.ground, 1, true));
  return glb(b.doc, b.bin);
}

std::vector<uint8_t> dracoBoxGlb() {
  Builder b = dracoBuilder();
  return glb(b.doc, b.bin);
}

std::vector<uint8_t> meshoptBoxGlb() {
  Builder b = meshoptBuilder();
  return glb(b.doc, b.bin);
}

std::map<std::string, std::vector<uint8_t>> brokenCompressedFiles() {
  std::map<std::string, std::vector<uint8_t>> out;
  {  // The Draco bitstream cut short: the decoder must refuse it, not read past it.
    Builder b = dracoBuilder();
    Json& view = b.doc["bufferViews"][b.doc["meshes"][0]["primitives"][0]["extensions"]["KHR_draco_mesh_compression"]["bufferView"].get<size_t>()];
    view["byteLength"] = view["byteLength"].get<size_t>() / 3;
    out["draco_truncated.glb"] = glb(b.doc, b.bin);
  }
  {  // An attribute id the Draco data does not have.
    Builder b = dracoBuilder();
    b.doc["meshes"][0]["primitives"][0]["extensions"]["KHR_draco_mesh_compression"]["attributes"]["NORMAL"] = 77;
    out["draco_missing_attribute.glb"] = glb(b.doc, b.bin);
  }
  {  // Accessor counts that do not match what the Draco data decodes to.
    Builder b = dracoBuilder();
    b.doc["accessors"][b.doc["meshes"][0]["primitives"][0]["attributes"]["POSITION"].get<size_t>()]["count"] = 3;
    out["draco_count_mismatch.glb"] = glb(b.doc, b.bin);
  }
  {  // Compressed vertex data overwritten with noise.
    Builder b = meshoptBuilder();
    const Json& ext = b.doc["bufferViews"][0]["extensions"]["EXT_meshopt_compression"];
    for (size_t i = 0; i < ext["byteLength"].get<size_t>(); ++i) b.bin[ext["byteOffset"].get<size_t>() + i] = static_cast<uint8_t>(i * 151 + 7);
    out["meshopt_corrupt.glb"] = glb(b.doc, b.bin);
  }
  {  // A count whose decompressed size is not the view's byteLength.
    Builder b = meshoptBuilder();
    b.doc["bufferViews"][0]["extensions"]["EXT_meshopt_compression"]["count"] = 1000;
    out["meshopt_count_mismatch.glb"] = glb(b.doc, b.bin);
  }
  return out;
}

}  // namespace penumbra::test
