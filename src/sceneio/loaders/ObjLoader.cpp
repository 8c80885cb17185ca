// Wavefront OBJ → Scene. tinyobjloader tokenises the file; every index it returns is checked
// here (it passes out-of-range ones through). It reads a number it cannot parse ("nan", "inf",
// "1e999", letters) as 0 and an index that overflows as anything, so every number of the
// statements Penumbra uses (v, vn, vt, f; Kd and Ns in .mtl files) is checked first, by line.
// Faces are unshared (three vertices per triangle) so that faces without `vn` get their own flat
// normal.
#define TINYOBJLOADER_IMPLEMENTATION
#include <tiny_obj_loader.h>

#include "sceneio/loaders/ObjLoader.h"

#include <penumbra/Error.h>

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>
#include <map>
#include <span>
#include <sstream>
#include <streambuf>
#include <string_view>
#include <vector>

namespace penumbra::loaders {
namespace {

const glm::vec3 kDefaultColor{0.8f};  // faces without a material: the scene file's default colour
// tinyobjloader keeps indices in an int: any index beyond this cannot mean what the file says.
constexpr int64_t kMaxObjIndex = std::numeric_limits<int>::max();

/// A statement whose numbers are checked: its keyword and how many numbers it takes.
struct NumberRule {
  std::string_view keyword;
  size_t minCount, maxCount;
  const char* what;  // for the message when the count is wrong
};
// v x y z [w | r g b] (tinyobjloader's vertex colours), vn x y z, vt u [v [w]].
constexpr NumberRule kObjRules[] = {{"v", 3, 6, "x y z, optionally w or r g b"}, {"vn", 3, 3, "x y z"},
                                    {"vt", 1, 3, "u [v [w]]"}};
constexpr NumberRule kMtlRules[] = {{"Kd", 3, 3, "r g b"}, {"Ns", 1, 1, "an exponent"}};
// The statements Penumbra reads (docs/scenes.md); tinyobjloader sees no other.
constexpr std::string_view kObjStatements[] = {"v", "vn", "vt", "f", "o", "g", "usemtl", "mtllib"};
constexpr std::string_view kMtlStatements[] = {"newmtl", "Kd", "Ns"};

/// The whitespace-separated words of a line up to a '#' comment.
std::vector<std::string_view> words(std::string_view line) {
  std::vector<std::string_view> out;
  size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r')) ++i;
    if (i >= line.size() || line[i] == '#') break;
    const size_t start = i;
    while (i < line.size() && line[i] != ' ' && line[i] != '\t' && line[i] != '\r') ++i;
    out.push_back(line.substr(start, i - start));
  }
  return out;
}

bool parseFinite(std::string_view s, float& out) {
  if (!s.empty() && s.front() == '+') s.remove_prefix(1);
  double d = 0.0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), d);
  if (s.empty() || ec != std::errc() || end != s.data() + s.size() || !std::isfinite(d) ||
      std::abs(d) > std::numeric_limits<float>::max())
    return false;
  out = static_cast<float>(d);
  return true;
}

/// One corner of an f statement: v, v/vt, v//vn or v/vt/vn; each a non-zero integer.
std::string checkCorner(std::string_view corner) {
  size_t part = 0;
  for (size_t start = 0; part < 3; ++part) {
    const size_t slash = corner.find('/', start);
    const std::string_view n = corner.substr(start, slash == std::string_view::npos ? std::string_view::npos : slash - start);
    const bool optional = part > 0 && n.empty();  // "1//3": no texture coordinate
    if (!optional) {
      int64_t v = 0;
      const auto [end, ec] = std::from_chars(n.data(), n.data() + n.size(), v);
      if (n.empty() || ec != std::errc() || end != n.data() + n.size() || v == 0 || v > kMaxObjIndex || v < -kMaxObjIndex)
        return fmt::format("'{}' is not an index (a non-zero integer within ±{}; OBJ counts from 1)", corner, kMaxObjIndex);
    }
    if (slash == std::string_view::npos) return part == 0 || !n.empty() ? "" : fmt::format("'{}' ends in '/'", corner);
    start = slash + 1;
  }
  return fmt::format("'{}' has more than three parts", corner);
}

/// Checks the numbers of every statement that `rules` (and, for an OBJ, `f`) name, and returns
/// the text as tinyobjloader may see it: every statement whose keyword is not in `keep` becomes a
/// comment (line numbers stay). Penumbra reads none of those, and tinyobjloader parses some of
/// them with unchecked conversions (`vw` joint ids become an int however large; texture options,
/// tags, exponents near 2^31). Lines end at "\n", "\r\n" or a lone "\r", as tinyobjloader splits
/// them. Throws Error("name: line N: keyword: problem").
std::string checkStatements(const std::string& text, const std::string& name, std::span<const NumberRule> rules, bool faces,
                            std::span<const std::string_view> keep) {
  std::vector<size_t> ignored;  // offsets of the keywords to turn into comments
  size_t lineNumber = 0;
  for (size_t start = 0; start < text.size();) {
    const size_t end = std::min(text.find_first_of("\r\n", start), text.size());
    const std::string_view line(text.data() + start, end - start);
    const size_t lineStart = start;
    start = end + (text.compare(end, 2, "\r\n") == 0 ? 2 : 1);
    ++lineNumber;
    const std::vector<std::string_view> w = words(line);
    if (w.empty()) continue;
    if (std::find(keep.begin(), keep.end(), w[0]) == keep.end()) {
      ignored.push_back(lineStart + static_cast<size_t>(w[0].data() - line.data()));
      continue;
    }
    const std::string where = fmt::format("line {}", lineNumber);
    if (faces && w[0] == "f") {
      for (size_t i = 1; i < w.size(); ++i)
        if (const std::string problem = checkCorner(w[i]); !problem.empty()) fail(name, where, "f: " + problem);
      continue;
    }
    for (const NumberRule& rule : rules) {
      if (w[0] != rule.keyword) continue;
      const size_t count = w.size() - 1;
      if (count < rule.minCount || count > rule.maxCount)
        fail(name, where, fmt::format("{}: {} numbers; expected {}", rule.keyword, count, rule.what));
      float unused = 0.0f;
      for (size_t i = 1; i < w.size(); ++i)
        if (!parseFinite(w[i], unused)) fail(name, where, fmt::format("{}: '{}' is not a finite number", rule.keyword, w[i]));
    }
  }
  std::string out = text;
  for (size_t at : ignored) out[at] = '#';
  return out;
}

/// `mtllib` files, read with the same limits as every other file; the first failure is kept and
/// reported as an error (tinyobjloader would only warn and fall back to a default material).
class MtlReader final : public tinyobj::MaterialReader {
public:
  explicit MtlReader(std::filesystem::path dir) : mDir(std::move(dir)) {}
  bool operator()(const std::string& id, std::vector<tinyobj::material_t>* materials, std::map<std::string, int>* names,
                  std::string* warn, std::string* err) override {
    try {
      const std::vector<uint8_t> bytes = readFileLimited(mDir / id, fmt::format("mtllib '{}'", id));
      const std::string text = checkStatements(std::string(bytes.begin(), bytes.end()), fmt::format("mtllib '{}'", id), kMtlRules,
                                               false, kMtlStatements);
      std::istringstream in(text);
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

// Share of an OBJ load spent in tinyobjloader's parse (the rest: the triangle lists); measured
// on a 2 M-triangle file.
constexpr double kObjParseShare = 0.5;
// tinyobjloader pulls the text through this many bytes at a time, each step a progress report.
constexpr size_t kObjChunkBytes = size_t(1) << 20;

/// The text as a stream that reports how much of it tinyobjloader has read.
class ProgressStreamBuf final : public std::streambuf {
public:
  ProgressStreamBuf(const std::string& text, ProgressReport* progress) : mText(text), mProgress(progress) {}

protected:
  int_type underflow() override {
    if (gptr() < egptr()) return traits_type::to_int_type(*gptr());
    if (mNext >= mText.size()) return traits_type::eof();
    char* begin = const_cast<char*>(mText.data()) + mNext;  // read only: std::streambuf wants char*
    const size_t n = std::min(kObjChunkBytes, mText.size() - mNext);
    setg(begin, begin, begin + n);
    mNext += n;
    if (mProgress) mProgress->update(mNext, mText.size());
    return traits_type::to_int_type(*gptr());
  }

private:
  const std::string& mText;
  ProgressReport* mProgress;
  size_t mNext = 0;
};

// Kd and Ns were checked (checkStatements): finite.
Material convertMaterial(const tinyobj::material_t& m) {
  Material out;
  out.name = m.name;
  // Kd is a reflectance: above 1 it would create energy, so it is clamped like any display colour.
  out.baseColor = glm::clamp(glm::vec3(m.diffuse[0], m.diffuse[1], m.diffuse[2]), 0.0f, 1.0f);
  // Blinn-Phong exponent Ns → roughness, the usual sqrt(2 / (Ns + 2)) mapping.
  out.roughness = std::clamp(std::sqrt(2.0f / (std::max(m.shininess, 0.0f) + 2.0f)), 0.0f, 1.0f);
  return out;
}

}  // namespace

Model loadObjFromMemory(const std::string& text, const std::string& name, const std::filesystem::path& baseDir,
                        ProgressReport* progress) {
  tinyobj::attrib_t attrib;
  std::vector<tinyobj::shape_t> shapes;
  std::vector<tinyobj::material_t> materials;
  std::string warn, err;
  const std::string checked = checkStatements(text, name, kObjRules, true, kObjStatements);
  if (progress) progress->stage(0.0, kObjParseShare);
  ProgressStreamBuf buffer(checked, progress);
  std::istream in(&buffer);
  MtlReader mtl(baseDir);
  const bool ok = tinyobj::LoadObj(&attrib, &shapes, &materials, &warn, &err, &in, &mtl, true, false);
  if (!mtl.error.empty()) fail(name, "", mtl.error);
  if (!ok) {
    while (!err.empty() && err.back() == '\n') err.pop_back();
    std::replace(err.begin(), err.end(), '\n', ' ');
    fail(name, "", err.empty() ? "tinyobjloader could not parse it" : err);
  }

  const size_t positions = attrib.vertices.size() / 3, normals = attrib.normals.size() / 3, uvs = attrib.texcoords.size() / 2;

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
  for (const tinyobj::material_t& m : materials) scene.materials.push_back(convertMaterial(m));
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

  if (progress) progress->stage(kObjParseShare, 1.0);
  size_t facesDone = 0, facesTotal = 0;
  for (const tinyobj::shape_t& s : shapes) facesTotal += s.mesh.num_face_vertices.size();
  for (size_t si = 0; si < shapes.size(); ++si) {
    const tinyobj::mesh_t& m = shapes[si].mesh;
    const std::string shape = shapes[si].name.empty() ? fmt::format("shape {}", si) : shapes[si].name;
    if (m.material_ids.size() != m.num_face_vertices.size()) fail(name, shape, "tinyobjloader returned inconsistent face lists");
    std::map<int, Mesh> byMaterial;
    size_t offset = 0;
    for (size_t f = 0; f < m.num_face_vertices.size(); ++f) {
      if (progress) progress->update(++facesDone, facesTotal);
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

Model loadObj(const std::filesystem::path& path, ProgressReport& progress) {
  const std::vector<uint8_t> bytes = readFileLimited(path, path.string());
  return loadObjFromMemory(std::string(bytes.begin(), bytes.end()), path.string(), path.parent_path(), &progress);
}

}  // namespace penumbra::loaders
