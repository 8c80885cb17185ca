// Wavefront OBJ → Scene. tinyobjloader tokenises the file; every index it returns is checked
// here (it passes out-of-range ones through), and every number must be finite. Faces are
// unshared (three vertices per triangle) so that faces without `vn` get their own flat normal.
#define TINYOBJLOADER_IMPLEMENTATION
#include <tiny_obj_loader.h>

#include "scene/loaders/ObjLoader.h"

#include <penumbra/Error.h>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>

namespace penumbra::loaders {
namespace {

const glm::vec3 kDefaultColor{0.8f};  // faces without a material: the scene file's default colour

/// `mtllib` files, read with the same limits as every other file; the first failure is kept and
/// reported as an error (tinyobjloader would only warn and fall back to a default material).
class MtlReader final : public tinyobj::MaterialReader {
public:
  explicit MtlReader(std::filesystem::path dir) : mDir(std::move(dir)) {}
  bool operator()(const std::string& id, std::vector<tinyobj::material_t>* materials, std::map<std::string, int>* names,
                  std::string* warn, std::string* err) override {
    try {
      const std::vector<uint8_t> bytes = readFileLimited(mDir / id, fmt::format("mtllib '{}'", id));
      std::istringstream in(std::string(bytes.begin(), bytes.end()));
      tinyobj::LoadMtl(names, materials, &in, warn, err);
      return true;
    } catch (const Error& e) {
      if (error.empty()) error = e.what();
      return false;
    }
  }
  std::string error;

private:
  std::filesystem::path mDir;
};

bool finite(std::initializer_list<float> v) {
  return std::all_of(v.begin(), v.end(), [](float x) { return std::isfinite(x); });
}

Material convertMaterial(const tinyobj::material_t& m, const std::string& file) {
  const std::string field = fmt::format("material '{}'", m.name);
  if (!finite({m.diffuse[0], m.diffuse[1], m.diffuse[2], m.shininess})) fail(file, field, "Kd or Ns is not finite");
  Material out;
  out.name = m.name;
  // Kd is a reflectance: above 1 it would create energy, so it is clamped like any display colour.
  out.baseColor = glm::clamp(glm::vec3(m.diffuse[0], m.diffuse[1], m.diffuse[2]), 0.0f, 1.0f);
  // Blinn-Phong exponent Ns → roughness, the usual sqrt(2 / (Ns + 2)) mapping.
  out.roughness = std::clamp(std::sqrt(2.0f / (std::max(m.shininess, 0.0f) + 2.0f)), 0.0f, 1.0f);
  return out;
}

}  // namespace

Model loadObjFromMemory(const std::string& text, const std::string& name, const std::filesystem::path& baseDir) {
  tinyobj::attrib_t attrib;
  std::vector<tinyobj::shape_t> shapes;
  std::vector<tinyobj::material_t> materials;
  std::string warn, err;
  std::istringstream in(text);
  MtlReader mtl(baseDir);
  const bool ok = tinyobj::LoadObj(&attrib, &shapes, &materials, &warn, &err, &in, &mtl, true, false);
  if (!mtl.error.empty()) fail(name, "", mtl.error);
  if (!ok) {
    while (!err.empty() && err.back() == '\n') err.pop_back();
    std::replace(err.begin(), err.end(), '\n', ' ');
    fail(name, "", err.empty() ? "tinyobjloader could not parse it" : err);
  }

  const size_t positions = attrib.vertices.size() / 3, normals = attrib.normals.size() / 3, uvs = attrib.texcoords.size() / 2;
  for (size_t i = 0; i < positions; ++i)
    if (!finite({attrib.vertices[3 * i], attrib.vertices[3 * i + 1], attrib.vertices[3 * i + 2]}))
      fail(name, fmt::format("v #{}", i + 1), "a coordinate is not finite");
  for (size_t i = 0; i < normals; ++i)
    if (!finite({attrib.normals[3 * i], attrib.normals[3 * i + 1], attrib.normals[3 * i + 2]}))
      fail(name, fmt::format("vn #{}", i + 1), "a component is not finite");
  for (size_t i = 0; i < uvs; ++i)
    if (!finite({attrib.texcoords[2 * i], attrib.texcoords[2 * i + 1]})) fail(name, fmt::format("vt #{}", i + 1), "a component is not finite");

  // Budget first: every polygon of n corners becomes n - 2 triangles of three unshared vertices.
  uint64_t triangles = 0;
  for (const tinyobj::shape_t& s : shapes)
    for (unsigned char n : s.mesh.num_face_vertices) triangles += n >= 3 ? n - 2u : 0u;
  if (triangles > kMaxTriangles) fail(name, "", fmt::format("{} triangles, more than the limit of {}", triangles, kMaxTriangles));
  if (3 * triangles > kMaxVertices) fail(name, "", fmt::format("{} vertices, more than the limit of {}", 3 * triangles, kMaxVertices));
  if (triangles == 0) fail(name, "", "no faces with three or more vertices (zero triangles)");

  Model model;
  Scene& scene = model.scene;
  scene.name = name;
  for (const tinyobj::material_t& m : materials) scene.materials.push_back(convertMaterial(m, name));
  const auto defaultMaterial = static_cast<int>(scene.materials.size());
  scene.materials.push_back(Material{.name = "default", .baseColor = kDefaultColor});

  auto corner = [&](const tinyobj::index_t& idx, size_t face, const std::string& shape) {
    const std::string field = fmt::format("{} face {}", shape, face + 1);
    if (idx.vertex_index < 0 || static_cast<size_t>(idx.vertex_index) >= positions)
      fail(name, field, fmt::format("vertex index {} is out of range ({} vertices)", idx.vertex_index + 1, positions));
    if (idx.normal_index >= 0 && static_cast<size_t>(idx.normal_index) >= normals)
      fail(name, field, fmt::format("normal index {} is out of range ({} normals)", idx.normal_index + 1, normals));
    if (idx.texcoord_index >= 0 && static_cast<size_t>(idx.texcoord_index) >= uvs)
      fail(name, field, fmt::format("texture coordinate index {} is out of range ({} coordinates)", idx.texcoord_index + 1, uvs));
    if (idx.normal_index < -1 || idx.texcoord_index < -1) fail(name, field, "a negative index points before the first element");
    Vertex v;
    const auto p = static_cast<size_t>(idx.vertex_index);
    v.position = {attrib.vertices[3 * p], attrib.vertices[3 * p + 1], attrib.vertices[3 * p + 2]};
    v.normal = glm::vec3(0.0f);
    if (idx.normal_index >= 0) {
      const auto n = static_cast<size_t>(idx.normal_index);
      v.normal = {attrib.normals[3 * n], attrib.normals[3 * n + 1], attrib.normals[3 * n + 2]};
    }
    if (idx.texcoord_index >= 0) {  // OBJ's v runs up from the bottom row; Penumbra's uv (0,0) is the top
      const auto t = static_cast<size_t>(idx.texcoord_index);
      v.uv = {attrib.texcoords[2 * t], 1.0f - attrib.texcoords[2 * t + 1]};
    }
    return v;
  };

  for (size_t si = 0; si < shapes.size(); ++si) {
    const tinyobj::mesh_t& m = shapes[si].mesh;
    const std::string shape = shapes[si].name.empty() ? fmt::format("shape {}", si) : shapes[si].name;
    if (m.material_ids.size() != m.num_face_vertices.size()) fail(name, shape, "tinyobjloader returned inconsistent face lists");
    std::map<int, Mesh> byMaterial;
    size_t offset = 0;
    for (size_t f = 0; f < m.num_face_vertices.size(); ++f) {
      const size_t n = m.num_face_vertices[f];
      if (offset + n > m.indices.size()) fail(name, shape, "tinyobjloader returned inconsistent face lists");
      const int id = m.material_ids[f];
      const int material = id >= 0 && static_cast<size_t>(id) < materials.size() ? id : defaultMaterial;
      Mesh& mesh = byMaterial[material];
      for (size_t k = 1; k + 1 < n; ++k) {  // fan over the polygon
        Vertex v[3] = {corner(m.indices[offset], f, shape), corner(m.indices[offset + k], f, shape),
                       corner(m.indices[offset + k + 1], f, shape)};
        const glm::vec3 face = glm::cross(v[1].position - v[0].position, v[2].position - v[0].position);
        const float len = glm::length(face);
        for (Vertex& x : v) {
          if (glm::dot(x.normal, x.normal) == 0.0f) x.normal = len > 0.0f && std::isfinite(len) ? face / len : glm::vec3(0, 1, 0);
          mesh.indices.push_back(static_cast<uint32_t>(mesh.vertices.size()));
          mesh.vertices.push_back(x);
        }
      }
      offset += n;
    }
    for (auto& [material, mesh] : byMaterial) {
      if (mesh.indices.empty()) continue;
      mesh.name = byMaterial.size() > 1 ? fmt::format("{}/{}", shape, scene.materials[static_cast<size_t>(material)].name) : shape;
      scene.meshes.push_back(std::move(mesh));
      Object o;
      o.name = scene.meshes.back().name;
      o.mesh = static_cast<uint32_t>(scene.meshes.size() - 1);
      o.material = static_cast<uint32_t>(material);
      scene.objects.push_back(std::move(o));
      if (scene.objects.size() > kMaxObjects) fail(name, "", fmt::format("more than {} shape/material pairs", kMaxObjects));
    }
  }
  return model;
}

Model loadObj(const std::filesystem::path& path) {
  const std::vector<uint8_t> bytes = readFileLimited(path, path.string());
  return loadObjFromMemory(std::string(bytes.begin(), bytes.end()), path.string(), path.parent_path());
}

}  // namespace penumbra::loaders
