// Wavefront OBJ → Scene, streamed: the file is read a block at a time, each line checked and
// handed to tinyobjloader's callback parser (LoadObjWithCallback), which calls back per statement.
// Neither the text nor tinyobjloader's face arrays are ever held whole: only the positions and
// normals that faces index, and the meshes being built. tinyobjloader reads a number it cannot
// parse ("nan", "inf", "1e999", letters) as 0 and an index that overflows as anything, so every
// number of the statements Penumbra uses (v, vn, vt, f; Kd and Ns in .mtl files) is checked
// first, by line, and every index it returns is checked here. Corners share vertices: each
// distinct (v, vn) pair of a mesh is one vertex (OBJ materials carry no texture here, so `vt` is
// checked but not kept). A mesh whose faces have no `vn` gets no normals: each triangle is shaded
// by its own plane.
#define TINYOBJLOADER_IMPLEMENTATION
#include <tiny_obj_loader.h>

#include "sceneio/loaders/ObjLoader.h"

#include <penumbra/Error.h>

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <deque>
#include <exception>
#include <fstream>
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

/// One line's check (what checkText does for each): false when its keyword is not in `keep` (the
/// line is dropped), true when it is kept; throws Error("name: line N: keyword: problem").
bool checkLine(const std::vector<std::string_view>& w, size_t lineNumber, const std::string& name, std::span<const NumberRule> rules,
               bool faces, std::span<const std::string_view> keep) {
  if (std::find(keep.begin(), keep.end(), w[0]) == keep.end()) return false;
  const std::string where = fmt::format("line {}", lineNumber);
  if (faces && w[0] == "f") {
    for (size_t i = 1; i < w.size(); ++i)
      if (const std::string problem = checkCorner(w[i]); !problem.empty()) fail(name, where, "f: " + problem);
    return true;
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
  return true;
}

/// Splits text into lines as tinyobjloader does ("\n", "\r\n" or a lone "\r"), a block at a
/// time: a line may straddle two blocks, and so may a "\r\n".
class LineSplitter {
public:
  /// Calls `line(text)` for each complete line of `block`; the rest waits for the next block.
  template <class F>
  void feed(std::string_view block, F&& line) {
    for (char c : block) {
      if (mAfterCr && c == '\n') {
        mAfterCr = false;
        continue;
      }
      mAfterCr = c == '\r';
      if (c == '\n' || c == '\r') {
        line(std::string_view(mLine));
        mLine.clear();
      } else {
        mLine.push_back(c);
      }
    }
  }
  /// The last line when the text does not end in a line break.
  template <class F>
  void finish(F&& line) {
    if (!mLine.empty()) line(std::string_view(mLine));
    mLine.clear();
  }

private:
  std::string mLine;
  bool mAfterCr = false;
};

/// The text as tinyobjloader may see it: every statement whose keyword is not in `keep` dropped
/// (Penumbra reads none of those, and tinyobjloader parses some of them with unchecked
/// conversions: `vw` joint ids become an int however large; texture options, tags, exponents near
/// 2^31), each kept line checked (checkLine) and rewritten as its words joined by one space (no
/// comment, no stray whitespace for a name to pick up).
std::string checkText(const std::string& text, const std::string& name, std::span<const NumberRule> rules, bool faces,
                      std::span<const std::string_view> keep) {
  std::string out;
  LineSplitter lines;
  size_t lineNumber = 0;
  auto take = [&](std::string_view line) {
    ++lineNumber;
    const std::vector<std::string_view> w = words(line);
    if (!w.empty() && checkLine(w, lineNumber, name, rules, faces, keep))
      for (size_t i = 0; i < w.size(); ++i) out.append(w[i]).push_back(i + 1 < w.size() ? ' ' : '\n');
  };
  lines.feed(text, take);
  lines.finish(take);
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
      const std::string text = checkText(std::string(bytes.begin(), bytes.end()), fmt::format("mtllib '{}'", id), kMtlRules,
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

// Kd and Ns were checked (checkLine): finite.
Material convertMaterial(const tinyobj::material_t& m) {
  Material out;
  out.name = m.name;
  // Kd is a reflectance: above 1 it would create energy, so it is clamped like any display colour.
  out.baseColor = glm::clamp(glm::vec3(m.diffuse[0], m.diffuse[1], m.diffuse[2]), 0.0f, 1.0f);
  // Blinn-Phong exponent Ns → roughness, the usual sqrt(2 / (Ns + 2)) mapping.
  out.roughness = std::clamp(std::sqrt(2.0f / (std::max(m.shininess, 0.0f) + 2.0f)), 0.0f, 1.0f);
  return out;
}

// Share of an OBJ load spent counting its statements (the memory estimate) before the parse.
constexpr double kObjCountShare = 0.1;
// The file is read this many bytes at a time, each block a progress report.
constexpr size_t kObjBlockBytes = size_t(1) << 16;
constexpr uint32_t kNone = ~0u;

/// What the faces and vertices of an OBJ text add up to, read before anything is built.
struct ObjCounts {
  uint64_t positions = 0, normals = 0, texcoords = 0, triangles = 0;
};

ObjCounts countStatements(std::istream& in) {
  ObjCounts c;
  LineSplitter lines;
  auto take = [&](std::string_view line) {
    size_t i = line.find_first_not_of(" \t");
    if (i == std::string_view::npos || i + 1 >= line.size()) return;
    const char a = line[i], b = line[i + 1];
    if (a == 'v' && (b == ' ' || b == '\t')) ++c.positions;
    else if (a == 'v' && b == 'n') ++c.normals;
    else if (a == 'v' && b == 't') ++c.texcoords;
    else if (a == 'f' && (b == ' ' || b == '\t')) {
      uint64_t corners = 0;
      for (size_t k = i + 1; k < line.size() && line[k] != '#'; ++k)
        if (line[k] != ' ' && line[k] != '\t' && (line[k - 1] == ' ' || line[k - 1] == '\t')) ++corners;
      if (corners >= 3) c.triangles += corners - 2;
    }
  };
  std::string block(kObjBlockBytes, '\0');
  while (in) {
    in.read(block.data(), static_cast<std::streamsize>(block.size()));
    lines.feed(std::string_view(block.data(), static_cast<size_t>(in.gcount())), take);
  }
  lines.finish(take);
  return c;
}

/// An OBJ source, checked line by line (checkLine) as tinyobjloader pulls it: the text it sees
/// (checkText's), a block at a time. A check's error is kept and the text ends there; rethrow()
/// raises it after the parse. Records the source line of every face it passes on (faceLines), so
/// that a face's errors name it.
class CheckedObjStream final : public std::streambuf {
public:
  CheckedObjStream(std::istream& source, uint64_t totalBytes, std::string name, ProgressReport* progress)
      : mSource(source), mTotal(totalBytes), mName(std::move(name)), mProgress(progress), mBlock(kObjBlockBytes, '\0') {}
  std::deque<size_t> faceLines;
  void rethrow() const {
    if (mError) std::rethrow_exception(mError);
  }

protected:
  int_type underflow() override {
    if (gptr() < egptr()) return traits_type::to_int_type(*gptr());
    mOut.clear();
    while (mOut.empty() && !mDone) fill();
    if (mOut.empty()) return traits_type::eof();
    setg(mOut.data(), mOut.data(), mOut.data() + mOut.size());
    return traits_type::to_int_type(*gptr());
  }

private:
  void fill() {
    auto take = [this](std::string_view line) {
      ++mLine;
      const std::vector<std::string_view> w = words(line);
      if (w.empty() || !checkLine(w, mLine, mName, kObjRules, true, kObjStatements)) return;
      if (w[0] == "f") {
        if (w.size() == 1) return;  // no corners: defines nothing (tinyobjloader would not call back)
        faceLines.push_back(mLine);
      }
      for (size_t i = 0; i < w.size(); ++i) mOut.append(w[i]).push_back(i + 1 < w.size() ? ' ' : '\n');
    };
    try {
      mSource.read(mBlock.data(), static_cast<std::streamsize>(mBlock.size()));
      const auto n = static_cast<size_t>(mSource.gcount());
      mRead += n;
      if (n == 0) {
        mLines.finish(take);
        mDone = true;
        return;
      }
      mLines.feed(std::string_view(mBlock.data(), n), take);
      if (mProgress) mProgress->update(mRead, mTotal);
    } catch (...) {
      mError = std::current_exception();
      mOut.clear();
      mDone = true;
    }
  }

  std::istream& mSource;
  uint64_t mTotal, mRead = 0;
  std::string mName;
  ProgressReport* mProgress;
  std::string mBlock, mOut;
  LineSplitter mLines;
  size_t mLine = 0;
  bool mDone = false;
  std::exception_ptr mError;
};

/// A polygon of more than four corners as triangles (corner numbers), by tinyobjloader's own
/// ear clipping: the triangles it made of such faces before the parse was streamed.
std::vector<std::array<int, 3>> clipEars(std::span<const glm::vec3> corners) {
  std::string text;
  for (const glm::vec3& p : corners) text += fmt::format("v {} {} {}\n", p.x, p.y, p.z);
  text += "f";
  for (size_t i = 0; i < corners.size(); ++i) text += fmt::format(" {}", i + 1);
  text += "\n";
  std::istringstream in(text);
  tinyobj::attrib_t attrib;
  std::vector<tinyobj::shape_t> shapes;
  std::vector<tinyobj::material_t> materials;
  std::string warn, err;
  std::vector<std::array<int, 3>> out;
  if (!tinyobj::LoadObj(&attrib, &shapes, &materials, &warn, &err, &in, nullptr, true, false) || shapes.empty()) return out;
  const std::vector<tinyobj::index_t>& idx = shapes.front().mesh.indices;
  for (size_t t = 0; t + 2 < idx.size(); t += 3) out.push_back({idx[t].vertex_index, idx[t + 1].vertex_index, idx[t + 2].vertex_index});
  return out;
}

/// Builds the meshes from tinyobjloader's callbacks: one mesh per (shape, material), a shape
/// being the faces between two `g` or `o` statements, as tinyobjloader's LoadObj groups them.
class ObjBuilder {
public:
  ObjBuilder(std::string name, CheckedObjStream& stream) : mName(std::move(name)), mStream(stream) { mShapes.emplace_back(); }

  void position(float x, float y, float z) { mPositions.push_back({x, y, z}); }
  void normal(float x, float y, float z) { mNormals.push_back({x, y, z}); }
  void texcoord() { ++mTexcoords; }  // OBJ materials have no textures here: only the count is checked
  void useMaterial(int id) { mMaterial = id; }
  void setMaterials(const tinyobj::material_t* m, int n) { mMaterials.assign(m, m + n); }
  void startShape(std::string name) {
    if (!mShapes.back().builders.empty()) mShapes.emplace_back();
    mShapes.back().name = std::move(name);
  }
  void face(const tinyobj::index_t* corners, int n);
  Model finish();

private:
  struct Corner {
    uint32_t v = kNone, vn = kNone;
  };
  struct MeshBuilder {
    Mesh mesh;
    bool flat = false, shaded = false;  // some vertices without a usable normal / some with one
  };
  struct Shape {
    std::string name;
    std::map<int, size_t> builders;  // material → mBuilders index, in material order
  };
  // Corner lookup: every vertex made from position v is an entry in v's list (its builder and
  // normal index), so a repeated (v, vn) pair in a mesh finds its vertex again.
  struct Entry {
    uint32_t builder, vn, vertex, next;
  };
  uint32_t vertexOf(uint32_t builder, const Corner& c);
  Corner resolve(const tinyobj::index_t& idx, size_t line) const;
  static void makeFlatCornersOwnVertices(Mesh& mesh);

  std::string mName;
  CheckedObjStream& mStream;
  std::vector<glm::vec3> mPositions, mNormals;
  size_t mTexcoords = 0;
  std::vector<tinyobj::material_t> mMaterials;
  int mMaterial = -1;
  std::vector<Shape> mShapes;
  std::vector<MeshBuilder> mBuilders;
  std::vector<uint32_t> mHead;  // by position: its first Entry, or kNone
  std::vector<Entry> mEntries;
};

ObjBuilder::Corner ObjBuilder::resolve(const tinyobj::index_t& idx, size_t line) const {
  // tinyobjloader's callback passes the indices as written: from 1, negative from the end of
  // what was defined so far, 0 = absent (checkCorner refused a written 0).
  auto index = [&](int raw, size_t count, const char* what, const char* plural) {
    const int64_t at = raw > 0 ? int64_t{raw} - 1 : static_cast<int64_t>(count) + raw;
    if (at < 0 || at >= static_cast<int64_t>(count))
      fail(mName, fmt::format("line {}", line),
           fmt::format("f: {} index {} is out of range ({} {})", what, raw > 0 ? int64_t{raw} : at + 1, count, plural));
    return static_cast<uint32_t>(at);
  };
  Corner c;
  c.v = index(idx.vertex_index, mPositions.size(), "vertex", "vertices");
  if (idx.normal_index != 0) c.vn = index(idx.normal_index, mNormals.size(), "normal", "normals");
  if (idx.texcoord_index != 0) index(idx.texcoord_index, mTexcoords, "texture coordinate", "coordinates");
  return c;
}

uint32_t ObjBuilder::vertexOf(uint32_t builder, const Corner& c) {
  if (mHead.size() <= c.v) mHead.resize(mPositions.size(), kNone);
  for (uint32_t e = mHead[c.v]; e != kNone; e = mEntries[e].next)
    if (mEntries[e].builder == builder && mEntries[e].vn == c.vn) return mEntries[e].vertex;
  MeshBuilder& b = mBuilders[builder];
  const auto vertex = static_cast<uint32_t>(b.mesh.positions.size());
  if (vertex == kNone) fail(mName, "", fmt::format("mesh '{}' has more than {} vertices", b.mesh.name, kNone - 1));
  b.mesh.positions.push_back(mPositions[c.v]);
  const glm::vec3 n = c.vn == kNone ? glm::vec3(0.0f) : mNormals[c.vn];
  b.mesh.normals.push_back(n);
  (glm::dot(n, n) == 0.0f ? b.flat : b.shaded) = true;  // a zero normal is no normal: the face's plane shades it
  mEntries.push_back({builder, c.vn, vertex, mHead[c.v]});
  mHead[c.v] = static_cast<uint32_t>(mEntries.size() - 1);
  return vertex;
}

void ObjBuilder::face(const tinyobj::index_t* idx, int n) {
  const size_t line = mStream.faceLines.empty() ? 0 : mStream.faceLines.front();
  if (!mStream.faceLines.empty()) mStream.faceLines.pop_front();
  if (n < 3) return;  // a point or a line: no surface (tinyobjloader dropped these too)
  std::vector<Corner> c(static_cast<size_t>(n));
  for (int i = 0; i < n; ++i) c[static_cast<size_t>(i)] = resolve(idx[i], line);
  Shape& shape = mShapes.back();
  const int material = mMaterial >= 0 && static_cast<size_t>(mMaterial) < mMaterials.size() ? mMaterial : -1;
  auto [it, added] = shape.builders.try_emplace(material, mBuilders.size());
  if (added) mBuilders.emplace_back();
  const auto builder = static_cast<uint32_t>(it->second);
  auto triangle = [&](int a, int b, int d) {
    for (int k : {a, b, d}) {
      const uint32_t vertex = vertexOf(builder, c[static_cast<size_t>(k)]);
      mBuilders[builder].mesh.indices.push_back(vertex);
    }
  };
  if (n == 3) {
    triangle(0, 1, 2);
  } else if (n == 4) {
    // tinyobjloader's split of a quad: along the shorter diagonal, in its float arithmetic.
    const glm::vec3 &p0 = mPositions[c[0].v], &p1 = mPositions[c[1].v], &p2 = mPositions[c[2].v], &p3 = mPositions[c[3].v];
    const float e02x = p2.x - p0.x, e02y = p2.y - p0.y, e02z = p2.z - p0.z;
    const float e13x = p3.x - p1.x, e13y = p3.y - p1.y, e13z = p3.z - p1.z;
    const float sqr02 = e02x * e02x + e02y * e02y + e02z * e02z, sqr13 = e13x * e13x + e13y * e13y + e13z * e13z;
    if (sqr02 < sqr13) {
      triangle(0, 1, 2);
      triangle(0, 2, 3);
    } else {
      triangle(0, 1, 3);
      triangle(1, 2, 3);
    }
  } else {
    std::vector<glm::vec3> points;
    for (const Corner& k : c) points.push_back(mPositions[k.v]);
    for (const auto& t : clipEars(points)) triangle(t[0], t[1], t[2]);
  }
}

/// Where a mesh mixes vertices with and without normals, each corner of a vertex without one
/// gets a vertex of its own with its triangle's normal (the flat faces of a shaded mesh).
void ObjBuilder::makeFlatCornersOwnVertices(Mesh& mesh) {
  const size_t shared = mesh.positions.size();
  for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
    const glm::vec3 &a = mesh.positions[mesh.indices[t]], &b = mesh.positions[mesh.indices[t + 1]], &d = mesh.positions[mesh.indices[t + 2]];
    const glm::vec3 face = glm::cross(b - a, d - a);
    const float len = glm::length(face);
    const glm::vec3 unit = len > 0.0f && std::isfinite(len) ? face / len : glm::vec3(0.0f, 1.0f, 0.0f);
    for (size_t k = t; k < t + 3; ++k) {
      const uint32_t v = mesh.indices[k];
      if (v >= shared || glm::dot(mesh.normals[v], mesh.normals[v]) != 0.0f) continue;
      mesh.positions.push_back(mesh.positions[v]);
      mesh.normals.push_back(unit);
      mesh.indices[k] = static_cast<uint32_t>(mesh.positions.size() - 1);
    }
  }
}

Model ObjBuilder::finish() {
  mHead = {};
  mEntries = {};
  mNormals = {};
  Model model;
  Scene& scene = model.scene;
  scene.name = mName;
  for (const tinyobj::material_t& m : mMaterials) scene.materials.push_back(convertMaterial(m));
  const auto defaultMaterial = static_cast<uint32_t>(scene.materials.size());
  scene.materials.push_back(Material{.name = "default", .baseColor = kDefaultColor});
  size_t shapeNumber = 0;
  for (const Shape& s : mShapes) {
    if (s.builders.empty()) continue;
    const std::string shape = s.name.empty() ? fmt::format("shape {}", shapeNumber) : s.name;
    ++shapeNumber;
    for (const auto& [material, index] : s.builders) {
      MeshBuilder& b = mBuilders[index];
      const uint32_t m = material >= 0 ? static_cast<uint32_t>(material) : defaultMaterial;
      if (!b.shaded) b.mesh.normals = {};  // flat: no normals at all
      else if (b.flat) makeFlatCornersOwnVertices(b.mesh);
      b.mesh.name = s.builders.size() > 1 ? fmt::format("{}/{}", shape, scene.materials[m].name) : shape;
      scene.meshes.push_back(std::move(b.mesh));
      Object o;
      o.name = scene.meshes.back().name;
      o.mesh = static_cast<uint32_t>(scene.meshes.size() - 1);
      o.material = m;
      scene.objects.push_back(std::move(o));
      if (scene.objects.size() > kMaxObjects) fail(mName, "", fmt::format("more than {} shape/material pairs", kMaxObjects));
    }
  }
  if (scene.meshes.empty()) fail(mName, "", "no faces with three or more vertices (zero triangles)");
  return model;
}

/// The parse itself, from `source` (`totalBytes` long).
Model parseObj(std::istream& source, uint64_t totalBytes, const std::string& name, const std::filesystem::path& baseDir,
               ProgressReport* progress) {
  CheckedObjStream stream(source, totalBytes, name, progress);
  ObjBuilder builder(name, stream);
  tinyobj::callback_t cb;
  cb.vertex_cb = [](void* b, tinyobj::real_t x, tinyobj::real_t y, tinyobj::real_t z, tinyobj::real_t) {
    static_cast<ObjBuilder*>(b)->position(x, y, z);
  };
  cb.normal_cb = [](void* b, tinyobj::real_t x, tinyobj::real_t y, tinyobj::real_t z) { static_cast<ObjBuilder*>(b)->normal(x, y, z); };
  cb.texcoord_cb = [](void* b, tinyobj::real_t, tinyobj::real_t, tinyobj::real_t) { static_cast<ObjBuilder*>(b)->texcoord(); };
  cb.index_cb = [](void* b, tinyobj::index_t* corners, int n) { static_cast<ObjBuilder*>(b)->face(corners, n); };
  cb.usemtl_cb = [](void* b, const char*, int id) { static_cast<ObjBuilder*>(b)->useMaterial(id); };
  cb.mtllib_cb = [](void* b, const tinyobj::material_t* m, int n) { static_cast<ObjBuilder*>(b)->setMaterials(m, n); };
  // tinyobjloader's LoadObj named a shape by its group names joined with spaces, or by its object.
  cb.group_cb = [](void* b, const char** names, int n) {
    std::string joined;
    for (int i = 0; i < n; ++i) joined += (i ? " " : "") + std::string(names[i]);
    static_cast<ObjBuilder*>(b)->startShape(joined);
  };
  cb.object_cb = [](void* b, const char* n) { static_cast<ObjBuilder*>(b)->startShape(n); };
  std::istream in(&stream);
  MtlReader mtl(baseDir);
  std::string warn, err;
  const bool ok = tinyobj::LoadObjWithCallback(in, cb, &builder, &mtl, &warn, &err);
  stream.rethrow();
  if (!mtl.error.empty()) fail(name, "", mtl.error);
  if (!ok) {
    while (!err.empty() && err.back() == '\n') err.pop_back();
    std::replace(err.begin(), err.end(), '\n', ' ');
    fail(name, "", err.empty() ? "tinyobjloader could not parse it" : err);
  }
  return builder.finish();
}

/// The memory check (ModelImport.h: checkSceneMemory) from the statement counts: each distinct
/// (v, vn) pair of a mesh is one vertex, about as many as the larger of the two lists.
void checkObjMemory(const ObjCounts& c, const std::string& name, ProgressReport* progress) {
  if (!progress) return;
  SceneCounts s;
  s.vertices = std::max(c.positions, c.normals);
  s.normals = c.normals > 0 ? s.vertices : 0;
  s.triangles = c.triangles;
  // While it builds: the lists the faces index, and a 16-byte lookup entry per vertex and 4 bytes
  // per position to find them again.
  s.loaderBytes = c.positions * (sizeof(glm::vec3) + sizeof(uint32_t)) + c.normals * sizeof(glm::vec3) + s.vertices * 16;
  checkSceneMemory(s, name, progress->options());
}

}  // namespace

Model loadObjFromMemory(const std::string& text, const std::string& name, const std::filesystem::path& baseDir,
                        ProgressReport* progress) {
  std::istringstream counting(text);
  checkObjMemory(countStatements(counting), name, progress);
  std::istringstream in(text);
  return parseObj(in, text.size(), name, baseDir, progress);
}

Model loadObj(const std::filesystem::path& path, ProgressReport& progress) {
  // readFileLimited's checks, but no size limit: the file is streamed, never held whole (the
  // memory estimate decides what fits).
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  const std::string name = path.string();
  if (ec || !std::filesystem::exists(status)) fail(name, "", fmt::format("cannot open {} (no such file)", name));
  if (std::filesystem::is_directory(status)) fail(name, "", fmt::format("{} is a folder, not a file", name));
  if (!std::filesystem::is_regular_file(status)) fail(name, "", fmt::format("{} is not a regular file", name));
  const uintmax_t size = std::filesystem::file_size(path, ec);
  if (ec) fail(name, "", fmt::format("cannot read the size of {}", name));
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(name, "", fmt::format("cannot open {} (not readable)", name));
  progress.stage(0.0, kObjCountShare);
  checkObjMemory(countStatements(in), name, &progress);
  in.clear();
  in.seekg(0);
  progress.stage(kObjCountShare, 1.0);
  Model model = parseObj(in, size, name, path.parent_path(), &progress);
  if (in.bad()) fail(name, "", fmt::format("cannot read {} (read error)", name));
  return model;
}

}  // namespace penumbra::loaders
