// Model files without GL: what the glTF and OBJ loaders read (hierarchy, strips, materials,
// alpha masks, lights from KHR_lights_punctual with extras.size, cameras), the default light and
// camera, the scene-file "file" hook, and one clear error for every file in tests/data/bad/.
#include "CompressedModels.h"
#include "sceneio/loaders/GltfLoader.h"
#include "sceneio/loaders/ModelImport.h"
#include "sceneio/loaders/ObjLoader.h"

#include <penumbra/Error.h>
#include <penumbra/SceneIO.h>

#include <fmt/format.h>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <gtest/gtest.h>

#include <filesystem>
#include <cstring>
#include <fstream>
#include <functional>
#include <map>
#include <set>
#include <string>
#include <vector>

#include <unistd.h>

using namespace penumbra;
namespace fs = std::filesystem;

namespace {

const fs::path kData = PENUMBRA_TEST_DATA;
// The alpha mask written by tests/data/make_test_models.py (row 0 = the image's top row).
const char* const kMask[4] = {"X.XX", "..X.", "X...", "XX.X"};

std::string errorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

std::string gltfError(const std::string& json) {
  return errorOf([&] {
    loaders::loadGltfFromMemory({reinterpret_cast<const uint8_t*>(json.data()), json.size()}, "mem.gltf", "");
  });
}

std::string base64(const std::vector<uint8_t>& bytes) {
  static const char* kAlphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (size_t i = 0; i < bytes.size(); i += 3) {
    uint32_t v = static_cast<uint32_t>(bytes[i]) << 16;
    if (i + 1 < bytes.size()) v |= static_cast<uint32_t>(bytes[i + 1]) << 8;
    if (i + 2 < bytes.size()) v |= bytes[i + 2];
    for (size_t k = 0; k < 4; ++k) out += i + k <= bytes.size() ? kAlphabet[(v >> (18 - 6 * k)) & 63] : '=';
  }
  return out;
}

// A glTF with one mesh of float positions and uint16 indices; `extra` adds to the primitive,
// `nodes`/`roots` give the hierarchy, `top` adds top-level members.
std::string meshGltf(const std::vector<glm::vec3>& positions, const std::vector<uint16_t>& indices, const std::string& extra,
                     const std::string& nodes = R"([{"mesh": 0}])", const std::string& roots = "[0]", const std::string& top = "") {
  std::vector<uint8_t> bytes(positions.size() * 12 + indices.size() * 2);
  std::memcpy(bytes.data(), positions.data(), positions.size() * 12);
  std::memcpy(bytes.data() + positions.size() * 12, indices.data(), indices.size() * 2);
  return fmt::format(R"({{"asset": {{"version": "2.0"}}, {}
    "buffers": [{{"byteLength": {}, "uri": "data:application/octet-stream;base64,{}"}}],
    "bufferViews": [{{"buffer": 0, "byteLength": {}}}, {{"buffer": 0, "byteOffset": {}, "byteLength": {}}}],
    "accessors": [{{"bufferView": 0, "componentType": 5126, "count": {}, "type": "VEC3"}},
                  {{"bufferView": 1, "componentType": 5123, "count": {}, "type": "SCALAR"}}],
    "meshes": [{{"primitives": [{{"attributes": {{"POSITION": 0}}, "indices": 1 {}}}]}}],
    "nodes": {}, "scenes": [{{"nodes": {}}}]}})",
                     top, bytes.size(), base64(bytes), positions.size() * 12, positions.size() * 12, indices.size() * 2,
                     positions.size(), indices.size(), extra, nodes, roots);
}

loaders::Model loadText(const std::string& json) {
  return loaders::loadGltfFromMemory({reinterpret_cast<const uint8_t*>(json.data()), json.size()}, "mem.gltf", "");
}

const std::vector<glm::vec3> kSquare = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}};

}  // namespace

TEST(ModelLoader, AlphaQuadGltf) {
  const loaders::Model m = loaders::loadModelFile(kData / "models/alpha_quad.gltf");
  const Scene& s = m.scene;
  ASSERT_EQ(s.objects.size(), 2u);
  EXPECT_EQ(s.triangleCount(), 4u);
  ASSERT_EQ(s.lights.size(), 1u);
  EXPECT_EQ(s.lights[0].type, LightType::Directional);
  EXPECT_NEAR(s.lights[0].size, 0.005f, 1e-7f);              // extras.size
  EXPECT_NEAR(s.lights[0].direction.y, -1.0f, 1e-5f);        // local -Z turned straight down
  EXPECT_NEAR(s.lights[0].intensity, 2.0f, 1e-6f);
  EXPECT_TRUE(m.hasCamera);
  EXPECT_NEAR(s.camera.fovYRad, 0.9f, 1e-6f);
  EXPECT_NEAR(glm::length(s.camera.forward() - glm::normalize(glm::vec3(0, -5.5f, -4.6f))), 0.0f, 0.01f);
  const Object& quad = s.objects[1];
  const Material& mat = s.materials[quad.material];
  EXPECT_TRUE(mat.alphaMask);
  EXPECT_FLOAT_EQ(mat.alphaCutoff, 0.5f);
  ASSERT_GE(mat.baseColorTexture, 0);
  const Image& im = s.images[static_cast<size_t>(mat.baseColorTexture)];
  ASSERT_EQ(im.width, 4);
  ASSERT_EQ(im.height, 4);
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x)
      EXPECT_EQ(im.rgba[static_cast<size_t>(4 * (4 * y + x) + 3)], kMask[y][x] == 'X' ? 255 : 0) << x << "," << y;
  // uv (0,0) sits at (-1, 1, -1): the image's top-left texel is over the quad's -x, -z corner.
  const Mesh& mesh = s.meshes[quad.mesh];
  ASSERT_EQ(mesh.uvs.size(), mesh.vertexCount());
  for (size_t i = 0; i < mesh.vertexCount(); ++i) {
    EXPECT_NEAR(mesh.uvs[i].x, (mesh.positions[i].x + 1.0f) / 2.0f, 1e-6f);
    EXPECT_NEAR(mesh.uvs[i].y, (mesh.positions[i].z + 1.0f) / 2.0f, 1e-6f);
  }
  EXPECT_FALSE(s.materials[s.objects[0].material].alphaMask);
}

TEST(ModelLoader, ObjWithMtlColours) {
  const loaders::Model m = loaders::loadModelFile(kData / "models/box.obj");
  EXPECT_EQ(m.scene.triangleCount(), 12u);  // six quads, fan-triangulated
  ASSERT_EQ(m.scene.objects.size(), 1u);
  const Material& mat = m.scene.materials[m.scene.objects[0].material];
  EXPECT_EQ(mat.name, "red");
  EXPECT_NEAR(mat.baseColor.x, 0.8f, 1e-6f);
  EXPECT_NEAR(mat.baseColor.y, 0.1f, 1e-6f);
  const Aabb b = m.scene.bounds();
  EXPECT_NEAR(b.lo.y, 0.0f, 1e-6f);
  EXPECT_NEAR(b.hi.y, 1.0f, 1e-6f);
  // Faces without vn: no normals (each triangle is shaded by its own plane), so the cube's corners
  // are shared by its faces: 8 vertices, not 24 or 36.
  EXPECT_TRUE(m.scene.meshes[0].normals.empty());
  EXPECT_EQ(m.scene.meshes[0].vertexCount(), 8u);
  EXPECT_FALSE(m.hasCamera);
  EXPECT_TRUE(m.scene.lights.empty());
}

TEST(ModelLoader, ModelAsSceneGetsDefaultSunAndFramingCamera) {
  const Scene s = loadScene((kData / "models/box.obj").string());
  ASSERT_EQ(s.lights.size(), 1u);
  EXPECT_EQ(s.lights[0].type, LightType::Directional);
  EXPECT_LT(s.lights[0].direction.y, -0.5f);  // from above
  EXPECT_FLOAT_EQ(s.lights[0].size, loaders::kDefaultSunAngularRadiusRad);
  // Every corner of the model's box lies inside the camera's view at 16:9 and at 1:1.
  const Aabb b = s.bounds();
  for (float aspect : {16.0f / 9.0f, 1.0f}) {
    const glm::mat4 clipFromWorld = s.camera.clipFromView(aspect) * s.camera.viewFromWorld();
    for (const glm::vec3& c : b.corners()) {
      const glm::vec4 clip = clipFromWorld * glm::vec4(c, 1.0f);
      ASSERT_GT(clip.w, s.camera.nearM);
      EXPECT_LE(std::abs(clip.x / clip.w), 1.0f) << aspect;
      EXPECT_LE(std::abs(clip.y / clip.w), 1.0f) << aspect;
    }
  }
}

TEST(ModelLoader, SceneFilePlacesObjAndGltfSideBySide) {
  const Scene s = loadScene((kData / "scenes/obj_and_gltf.json").string());
  ASSERT_EQ(s.objects.size(), 4u);  // floor, box, the glTF's ground and masked quad
  EXPECT_EQ(s.objects[1].name, "box/box");
  EXPECT_EQ(s.objects[3].name, "quad/masked quad");
  ASSERT_EQ(s.lights.size(), 1u);  // the scene file's own light; the glTF's sun is not taken
  EXPECT_NEAR(s.lights[0].size, 0.005f, 1e-7f);
  // The glTF is translated by (2, 0.01, 0) and scaled by 0.5: its masked quad spans x in [1.5, 2.5].
  const Aabb quad = s.meshes[s.objects[3].mesh].bounds().transformed(s.objects[3].worldFromObject);
  EXPECT_NEAR(quad.lo.x, 1.5f, 1e-5f);
  EXPECT_NEAR(quad.hi.x, 2.5f, 1e-5f);
  EXPECT_NEAR(quad.lo.y, 0.51f, 1e-5f);
  const Material& mat = s.materials[s.objects[3].material];
  ASSERT_TRUE(mat.alphaMask);
  ASSERT_GE(mat.baseColorTexture, 0);
  EXPECT_EQ(s.images[static_cast<size_t>(mat.baseColorTexture)].width, 4);
  const Aabb box = s.meshes[s.objects[1].mesh].bounds().transformed(s.objects[1].worldFromObject);
  EXPECT_NEAR(box.center().x, -2.0f, 1e-5f);
}

TEST(ModelLoader, StripsAndFansBecomeTriangleLists) {
  // Strip (0 1 2 3) → (0 1 2) (1 3 2); fan (0 1 3 2) → (1 3 0) (3 2 0) (glTF 2.0 §3.7.2.1).
  // The positions each index names show the order.
  const loaders::Model strip = loadText(meshGltf(kSquare, {0, 1, 2, 3}, R"(, "mode": 5)"));
  const loaders::Model fan = loadText(meshGltf(kSquare, {0, 1, 3, 2}, R"(, "mode": 6)"));
  const int stripOrder[6] = {0, 1, 2, 1, 3, 2}, fanOrder[6] = {1, 3, 0, 3, 2, 0};
  for (const auto& [model, order] : {std::pair{&strip, stripOrder}, std::pair{&fan, fanOrder}}) {
    const Mesh& m = model->scene.meshes.at(0);
    ASSERT_EQ(m.triangleCount(), 2u);
    for (size_t i = 0; i < 6; ++i) EXPECT_EQ(m.positions[m.indices[i]], kSquare[static_cast<size_t>(order[i])]) << i;
    EXPECT_TRUE(m.normals.empty()) << "no NORMAL: flat, no normals kept";
    for (size_t t = 0; t < 6; t += 3) {  // one winding: every face toward +Z
      const glm::vec3 &a = m.positions[m.indices[t]], &b = m.positions[m.indices[t + 1]], &c = m.positions[m.indices[t + 2]];
      EXPECT_GT(glm::cross(b - a, c - a).z, 0.0f) << t / 3;
    }
  }
  // Lines and points draw nothing: a file with only those has zero triangles.
  EXPECT_NE(gltfError(meshGltf(kSquare, {0, 1, 2, 3}, R"(, "mode": 1)")).find("no triangles"), std::string::npos);
}

// Corners share vertices: a grid of n × n quads keeps one vertex per grid point, (n + 1)², from OBJ
// (`f` lines over `v`, with and without `vn`) and from glTF (indexed, as the file shares them, and
// as a plain list of corners, which meshoptimizer's remap folds together).
TEST(ModelLoader, GridVerticesAreSharedOncePerPoint) {
  constexpr int n = 6;
  constexpr size_t kPoints = (n + 1) * (n + 1), kTriangles = 2 * n * n;
  std::vector<glm::vec3> points;
  std::string v;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      points.emplace_back(static_cast<float>(i), 0.1f * static_cast<float>(i * j % 3), static_cast<float>(j));
      v += fmt::format("v {} {} {}\n", points.back().x, points.back().y, points.back().z);
    }
  std::vector<uint16_t> indices;
  std::string faces, facesWithNormal;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const int a = j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
      for (int k : {a, c, b, b, c, d}) indices.push_back(static_cast<uint16_t>(k));
      faces += fmt::format("f {} {} {}\nf {} {} {}\n", a + 1, c + 1, b + 1, b + 1, c + 1, d + 1);
      facesWithNormal += fmt::format("f {0}//1 {1}//1 {2}//1\nf {2}//1 {1}//1 {3}//1\n", a + 1, c + 1, b + 1, d + 1);
    }
  const loaders::Model flat = loaders::loadObjFromMemory(v + faces, "grid.obj", "");
  const loaders::Model shaded = loaders::loadObjFromMemory(v + "vn 0 1 0\n" + facesWithNormal, "grid.obj", "");
  std::vector<glm::vec3> corners;  // the same triangles, every corner written out
  for (uint16_t i : indices) corners.push_back(points[i]);
  std::string listed = meshGltf(corners, {0, 1, 2}, "");
  const std::string indexedText = R"("indices": 1 )";
  ASSERT_NE(listed.find(indexedText), std::string::npos);
  listed.replace(listed.find(indexedText) - 2, indexedText.size() + 2, "");  // ", \"indices\": 1 ": no index buffer
  const loaders::Model indexed = loadText(meshGltf(points, indices, ""));
  const loaders::Model remapped = loadText(listed);
  for (const auto& [name, model] : {std::pair{"OBJ", &flat}, {"OBJ with vn", &shaded}, {"glTF", &indexed}, {"glTF without indices", &remapped}}) {
    ASSERT_EQ(model->scene.meshes.size(), 1u) << name;
    const Mesh& m = model->scene.meshes[0];
    EXPECT_EQ(m.triangleCount(), kTriangles) << name;
    EXPECT_EQ(m.vertexCount(), kPoints) << name << ": one vertex per grid point";
    for (size_t t = 0; t < m.indices.size(); ++t)  // every corner still at its point
      EXPECT_EQ(m.positions[m.indices[t]], points[indices[t]]) << name << " corner " << t;
  }
  EXPECT_TRUE(flat.scene.meshes[0].normals.empty());
  EXPECT_EQ(shaded.scene.meshes[0].normals, std::vector<glm::vec3>(kPoints, glm::vec3(0, 1, 0)));
}

TEST(ModelLoader, NodeTransformsCompose) {
  // The root translates by (0, 2, 0), its child scales by 2: the square spans y in [2, 4].
  const loaders::Model m = loadText(meshGltf(kSquare, {0, 1, 2, 1, 3, 2}, "",
                                             R"([{"mesh": 0, "scale": [2, 2, 2]}, {"translation": [0, 2, 0], "children": [0]}])", "[1]"));
  const Aabb b = m.scene.bounds();
  EXPECT_NEAR(b.lo.y, 2.0f, 1e-5f);
  EXPECT_NEAR(b.hi.y, 4.0f, 1e-5f);
  EXPECT_NEAR(b.hi.x, 2.0f, 1e-5f);
  // A node under two parents breaks the tree rule and is refused rather than drawn twice.
  const std::string twice = gltfError(meshGltf(kSquare, {0, 1, 2}, "", R"([{"mesh": 0}, {"children": [0]}, {"children": [0]}])", "[1, 2]"));
  EXPECT_NE(twice.find("more than one parent"), std::string::npos) << twice;
}

TEST(ModelLoader, PunctualLightsAndTheirSize) {
  const std::string lights = R"("extensionsUsed": ["KHR_lights_punctual"], "extensions": {"KHR_lights_punctual": {"lights": [
      {"type": "spot", "intensity": 5, "spot": {"outerConeAngle": 0.5}, "extras": {"size": 0.25}},
      {"type": "point", "range": 12, "extras": {"size": 0.1}}]}},)";
  const std::string nodes = R"([{"mesh": 0},
      {"translation": [0, 4, 0], "rotation": [-0.70710678, 0, 0, 0.70710678], "extensions": {"KHR_lights_punctual": {"light": 0}}},
      {"translation": [3, 0.5, 0], "extensions": {"KHR_lights_punctual": {"light": 1}}}])";
  const loaders::Model m = loadText(meshGltf(kSquare, {0, 1, 2, 1, 3, 2}, "", nodes, "[0, 1, 2]", lights));
  ASSERT_EQ(m.scene.lights.size(), 2u);
  const Light& spot = m.scene.lights[0];
  EXPECT_EQ(spot.type, LightType::Spot);
  EXPECT_NEAR(spot.size, 0.25f, 1e-7f);
  EXPECT_NEAR(spot.coneAngleRad, 0.5f, 1e-6f);
  EXPECT_EQ(spot.innerConeAngleRad, 0.0f);  // KHR_lights_punctual's default inner angle
  EXPECT_EQ(spot.rangeM, 0.0f);             // no range given: unlimited
  EXPECT_NEAR(spot.position.y, 4.0f, 1e-6f);
  EXPECT_NEAR(spot.direction.y, -1.0f, 1e-5f);
  // The point light stays a point light, with its position and range.
  const Light& point = m.scene.lights[1];
  EXPECT_EQ(point.type, LightType::Point);
  EXPECT_NEAR(point.size, 0.1f, 1e-7f);
  EXPECT_EQ(point.position, glm::vec3(3.0f, 0.5f, 0.0f));
  EXPECT_EQ(point.rangeM, 12.0f);
  // A sun's size is an angle: 0.7 rad is refused, naming the field.
  const std::string bigSun = R"("extensions": {"KHR_lights_punctual": {"lights": [{"type": "directional", "extras": {"size": 0.7}}]}},)";
  const std::string e = gltfError(meshGltf(kSquare, {0, 1, 2}, "", R"([{"mesh": 0, "extensions": {"KHR_lights_punctual": {"light": 0}}}])", "[0]", bigSun));
  EXPECT_NE(e.find("lights[0].extras.size"), std::string::npos) << e;
}

TEST(ModelLoader, EveryBadFileGetsOneErrorNamingIt) {
  // These load: their mistake is a technique choice, which the CLI checks against the registry
  // (tests/loaders runs every bad file through the CLI).
  const std::set<std::string> techniqueErrors = {"scene_bad_filter.json", "scene_bad_param.json", "scene_param_out_of_range.json"};
  size_t files = 0;
  for (const fs::directory_entry& f : fs::directory_iterator(kData / "bad")) {
    ++files;
    if (techniqueErrors.count(f.path().filename().string())) {
      EXPECT_NO_THROW(loadScene(f.path().string())) << f.path();
      continue;
    }
    const std::string e = errorOf([&] { loadScene(f.path().string()); });
    ASSERT_FALSE(e.empty()) << f.path() << " was accepted";
    EXPECT_NE(e.find(f.path().filename().string()), std::string::npos) << e;
    // control_chars.gltf quotes a newline from the file; the CLI prints it escaped
    // (RenderCli.MessagesCarryNoControlCharacters).
    if (f.path().filename() != "control_chars.gltf") {
      EXPECT_EQ(e.find('\n'), std::string::npos) << "one line: " << e;
    }
  }
  EXPECT_GE(files, 15u);
}

TEST(ModelLoader, ErrorsNameTheProblem) {
  const fs::path bad = kData / "bad";
  auto err = [&](const char* name) { return errorOf([&] { loadScene((bad / name).string()); }); };
  EXPECT_NE(err("index_out_of_range.gltf").find("index 99"), std::string::npos);
  EXPECT_NE(err("nan_position.gltf").find("not finite"), std::string::npos);
  EXPECT_NE(err("recursive_nodes.gltf").find("cycle"), std::string::npos);
  EXPECT_NE(err("zero_triangles.gltf").find("no triangles"), std::string::npos);
  EXPECT_NE(err("view_past_buffer.gltf").find("run past the end"), std::string::npos);
  EXPECT_NE(err("deep_json.gltf").find("nests deeper"), std::string::npos);
  EXPECT_NE(err("huge_image.gltf").find("10000x10000 texels"), std::string::npos);
  EXPECT_NE(err("huge_coordinates.gltf").find("world-space"), std::string::npos);
  EXPECT_NE(err("index_out_of_range.obj").find("vertex index 99"), std::string::npos);
  EXPECT_NE(err("missing_mtl.obj").find("no_such.mtl"), std::string::npos);
  EXPECT_NE(err("scene_bad_model.json").find("objects[1].file"), std::string::npos);
  EXPECT_NE(err("missing_buffer.gltf").find("no_such_file.bin"), std::string::npos);
  EXPECT_NE(err("bad_light_size.gltf").find("extras.size"), std::string::npos);
  EXPECT_NE(err("empty.glb").find("empty"), std::string::npos);
}

// tinyobjloader reads a number it cannot parse as 0 and an overflowing index as anything: each
// of these loaded silently once (a vertex at 0, a black material, the last vertex).
TEST(ModelLoader, ObjNumbersThatAreNotNumbersNameTheirLine) {
  const fs::path bad = kData / "bad";
  auto err = [&](const char* name) { return errorOf([&] { loadScene((bad / name).string()); }); };
  EXPECT_NE(err("nan_position.obj").find("nan_position.obj: line 1: v: 'nan' is not a finite number"), std::string::npos)
      << err("nan_position.obj");
  EXPECT_NE(err("letters_position.obj").find("line 2: v: 'zero' is not a finite number"), std::string::npos);
  EXPECT_NE(err("inf_position.obj").find("line 2: v: '1e999' is not a finite number"), std::string::npos);
  EXPECT_NE(err("huge_index.obj").find("line 4: f: '99999999999999999999' is not an index"), std::string::npos)
      << err("huge_index.obj");
  EXPECT_NE(err("nan_kd.obj").find("nan_kd.obj: mtllib 'nan_kd.mtl': line 2: Kd: 'nan' is not a finite number"), std::string::npos)
      << err("nan_kd.obj");
  auto objError = [](const std::string& text) {
    return errorOf([&] { loaders::loadObjFromMemory(text, "mem.obj", ""); });
  };
  const std::string triangle = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
  EXPECT_NE(objError(triangle + "vn inf 0 1\nf 1//1 2//1 3//1\n").find("line 4: vn: 'inf'"), std::string::npos);
  EXPECT_NE(objError(triangle + "vt 0.5 x\nf 1/1 2/1 3/1\n").find("line 4: vt: 'x'"), std::string::npos);
  EXPECT_NE(objError(triangle + "f 0 1 2\n").find("line 4: f: '0' is not an index"), std::string::npos);
  EXPECT_NE(objError(triangle + "f 1/ 2 3\n").find("line 4: f: '1/' ends in '/'"), std::string::npos);
  EXPECT_NE(objError("v 0 0\n").find("line 1: v: 2 numbers"), std::string::npos);
  // What real files hold still loads: comments, tabs, CRLF, '+', exponents, relative indices, w.
  EXPECT_EQ(objError("# c\r\nv\t+0 0 0 1\r\nv 1e0 0 0 # x\r\nv 0 1 0\r\nvt 0 0\r\nf -3/1 -2/1 -1/1\r\n"), "");
}

// A 2 M-triangle load took 12 s without a word: the loaders report their progress (the CLI
// shows it for large files), from 0 when a file starts to 1 when it is loaded, increasing.
TEST(ModelLoader, ProgressIsReportedWhileAFileLoads) {
  const fs::path dir = fs::temp_directory_path() / ("penumbra-progress-" + std::to_string(getpid()));
  fs::create_directories(dir);
  constexpr int kGrid = 300;  // 90 000 quads: 180 000 triangles, a 4 MB file
  {
    std::ofstream obj(dir / "grid.obj");
    for (int i = 0; i <= kGrid; ++i)
      for (int j = 0; j <= kGrid; ++j) obj << "v " << i << " 0 " << j << "\n";
    for (int i = 0; i < kGrid; ++i)
      for (int j = 0; j < kGrid; ++j) {
        const int a = i * (kGrid + 1) + j + 1;
        obj << "f " << a << " " << a + kGrid + 1 << " " << a + kGrid + 2 << " " << a + 1 << "\n";
      }
  }
  for (const fs::path& file : {dir / "grid.obj", kData / "models/alpha_quad.gltf"}) {
    std::vector<double> seen;
    const loaders::Model m = loaders::loadModelFile(file, {.progress = [&](const fs::path& f, double x) {
      EXPECT_EQ(f, file);
      seen.push_back(x);
    }});
    ASSERT_GE(seen.size(), 3u) << file;
    EXPECT_EQ(seen.front(), 0.0);
    EXPECT_EQ(seen.back(), 1.0);
    for (size_t i = 1; i < seen.size(); ++i) EXPECT_GT(seen[i], seen[i - 1]) << file << " report " << i;
    if (file.extension() == ".obj") {
      EXPECT_GE(seen.size(), 50u) << "a 4 MB file is reported in steps";
    }
  }
  fs::remove_all(dir);
}

// A file of only degenerate triangles rendered an empty image with exit 0.
TEST(ModelLoader, OnlyDegenerateTrianglesAreRefused) {
  for (const char* name : {"degenerate_triangles.obj", "degenerate_triangles.gltf"}) {
    const std::string e = errorOf([&] { loadScene((kData / "bad" / name).string()); });
    EXPECT_NE(e.find(std::string(name) + ": every triangle has zero area"), std::string::npos) << e;
  }
  // Inside a scene file, placed next to shapes that draw, such a model is still an error.
  const fs::path dir = fs::temp_directory_path() / ("penumbra-degenerate-" + std::to_string(getpid()));
  fs::create_directories(dir);
  std::ofstream(dir / "flat.obj") << "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n";
  std::ofstream(dir / "s.json") << R"({"lights": [{"type": "sun"}], "objects": [{"shape": "box"}, {"file": "flat.obj"}]})";
  const std::string e = errorOf([&] { loadScene((dir / "s.json").string()); });
  EXPECT_NE(e.find("objects[1].file"), std::string::npos) << e;
  EXPECT_NE(e.find("every triangle has zero area"), std::string::npos) << e;
  fs::remove_all(dir);
}

// JPEG base-colour textures decode (they were refused), KHR_texture_transform is folded into the
// texture coordinates, and an image no material's base colour uses (a WebP normal map) is never
// decoded. tests/data/make_test_models.py writes the file.
TEST(ModelLoader, JpegTextureTransformAndUnusedImages) {
  const loaders::Model m = loaders::loadModelFile(kData / "models/textured_quads.gltf");
  const Scene& s = m.scene;
  ASSERT_EQ(s.images.size(), 2u) << "the mask and the JPEG; the WebP normal map is never decoded";
  const Object& ground = s.objects[0];
  const Material& mat = s.materials[ground.material];
  ASSERT_GE(mat.baseColorTexture, 0);
  const Image& jpeg = s.images[static_cast<size_t>(mat.baseColorTexture)];
  ASSERT_EQ(jpeg.width, 32);
  ASSERT_EQ(jpeg.height, 32);
  const char* const checker[4] = {"ABAA", "BBAB", "ABBB", "AABA"};
  const glm::ivec3 colours[2] = {{230, 200, 40}, {30, 60, 190}};
  constexpr int kJpegTolerance = 2;  // YCbCr rounding
  for (int by = 0; by < 4; ++by)
    for (int bx = 0; bx < 4; ++bx) {
      const glm::ivec3 want = colours[checker[by][bx] == 'A' ? 0 : 1];
      const size_t texel = static_cast<size_t>(4 * ((8 * by + 4) * 32 + 8 * bx + 4));
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(jpeg.rgba[texel + static_cast<size_t>(c)], want[c], kJpegTolerance) << bx << "," << by;
    }
  // uv (0,0) at (-3, 0, -3) across the 6 m ground; the transform: scale 2, a quarter turn.
  const Mesh& groundMesh = s.meshes[ground.mesh];
  ASSERT_EQ(groundMesh.uvs.size(), groundMesh.vertexCount());
  for (size_t i = 0; i < groundMesh.vertexCount(); ++i) {
    const glm::vec3& p = groundMesh.positions[i];
    const glm::vec2 uv((p.x + 3.0f) / 6.0f, (p.z + 3.0f) / 6.0f);
    EXPECT_NEAR(groundMesh.uvs[i].x, 2.0f * uv.y, 1e-5f) << p.x << "," << p.z;
    EXPECT_NEAR(groundMesh.uvs[i].y, -2.0f * uv.x, 1e-5f) << p.x << "," << p.z;
  }
  const fs::path bad = kData / "bad";
  auto err = [&](const char* name) { return errorOf([&] { loadScene((bad / name).string()); }); };
  EXPECT_NE(err("webp_base_colour.gltf").find("textures[0] (images[0]): WebP is not an image format Penumbra decodes (PNG, JPEG)"),
            std::string::npos) << err("webp_base_colour.gltf");
  EXPECT_NE(err("bad_texture_transform.gltf")
                .find("materials[0].pbrMetallicRoughness.baseColorTexture.extensions.KHR_texture_transform.rotation: expected a finite number"),
            std::string::npos) << err("bad_texture_transform.gltf");
}

// glTF 1.0 was not named; tinygltf's own messages carried no field ("{}" gave "JSON string too
// short."): the members it requires are checked first, naming the field.
TEST(ModelLoader, GltfStructureErrorsNameTheField) {
  const fs::path bad = kData / "bad";
  auto err = [&](const char* name) { return errorOf([&] { loadScene((bad / name).string()); }); };
  EXPECT_NE(err("gltf1.gltf").find("gltf1.gltf: asset.version: '1.0': a glTF 1.0 file: Penumbra reads glTF 2.0 only"), std::string::npos)
      << err("gltf1.gltf");
  EXPECT_NE(err("glb_version1.glb").find("a binary glTF 1.0 file (GLB version 1)"), std::string::npos) << err("glb_version1.glb");
  EXPECT_NE(err("empty_object.gltf").find("empty_object.gltf: asset: missing"), std::string::npos) << err("empty_object.gltf");
  EXPECT_NE(err("missing_byte_length.gltf").find("bufferViews[0].byteLength: missing"), std::string::npos) << err("missing_byte_length.gltf");
  EXPECT_NE(err("primitive_without_attributes.gltf").find("meshes[0].primitives[1].attributes: missing"), std::string::npos)
      << err("primitive_without_attributes.gltf");
  EXPECT_NE(gltfError(R"({"asset": {"version": "2.0"}, "accessors": [{"count": 3, "type": "VEC3"}]})").find("accessors[0].componentType: missing"),
            std::string::npos);
  EXPECT_NE(gltfError(R"({"asset": {"version": "2.0"}, "nodes": {"a": {}}})").find("collections keyed by name are glTF 1.0"), std::string::npos);
  EXPECT_NE(gltfError(R"({"asset": {"version": 2}})").find("asset.version: expected a string"), std::string::npos);
}

// KHR_mesh_quantization as gltfpack writes it: SHORT positions (normalised, 8-byte stride) that
// the node scales back, BYTE normals (4-byte stride), USHORT texture coordinates that
// KHR_texture_transform scales back. tests/data/make_test_models.py writes the file.
TEST(ModelLoader, QuantizedMeshesReadBackTheirValues) {
  const Scene s = loadScene((kData / "models/quantized_box.gltf").string());
  ASSERT_EQ(s.objects.size(), 1u);
  const Aabb b = s.bounds();
  EXPECT_NEAR(b.lo.y, 0.0f, 1e-4f);  // SHORT ±32767 → ±1, × 0.5 m, lifted by 0.5 m
  EXPECT_NEAR(b.hi.y, 1.0f, 1e-4f);
  EXPECT_NEAR(b.lo.x, -0.5f, 1e-4f);
  const Mesh& m = s.meshes[s.objects[0].mesh];
  ASSERT_EQ(m.vertexCount(), 24u);
  ASSERT_EQ(m.normals.size(), 24u);
  ASSERT_EQ(m.uvs.size(), 24u);
  constexpr float kByteNormalStep = 1.0f / 127.0f;
  for (size_t i = 0; i < m.vertexCount(); ++i) {
    const glm::vec3 &n = m.normals[i], &p = m.positions[i];
    // Each face's normal is its position's one coordinate at ±1 (before the node's scale).
    const glm::vec3 face = glm::round(n);
    EXPECT_NEAR(glm::length(n), 1.0f, kByteNormalStep);
    EXPECT_NEAR(glm::dot(face, p), 1.0f, 1e-4f) << "normal (" << n.x << "," << n.y << "," << n.z << ")";
    // USHORT 0 or 65535 → 0 or 1, scaled by 2 by the texture transform.
    for (float c : {m.uvs[i].x, m.uvs[i].y}) EXPECT_TRUE(std::abs(c) < 1e-6f || std::abs(c - 2.0f) < 1e-6f) << c;
  }
  // An integer NORMAL must be normalised (the extension allows only normalised BYTE and SHORT).
  std::ifstream in(kData / "models/quantized_box.gltf");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string normalAccessor = R"("componentType": 5120,
   "normalized": true)";
  const size_t at = text.find(normalAccessor);
  ASSERT_NE(at, std::string::npos);
  text.replace(at, normalAccessor.size(), R"("componentType": 5120,
   "normalized": false)");
  const std::string e = gltfError(text);
  EXPECT_NE(e.find("accessors[1]: a BYTE or SHORT NORMAL must be normalized (KHR_mesh_quantization)"), std::string::npos) << e;
}

namespace {

loaders::Model loadGlb(const std::vector<uint8_t>& bytes) { return loaders::loadGltfFromMemory(bytes, "mem.glb", ""); }

std::vector<uint8_t> readBytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

}  // namespace

// EXT_meshopt_compression (what gltfpack -c writes): vertex and index codecs, the octahedral
// normal filter and the fallback buffer without data. The decoded mesh is the original, vertex
// for vertex (the codecs are lossless; the 8-bit normal filter is not). Texture coordinates are
// decoded too but only read under a base-colour texture, which these materials do not have.
TEST(ModelLoader, MeshoptDecodesToTheOriginalGeometry) {
  const test::BoxGeometry g = test::boxGeometry();
  const loaders::Model m = loadGlb(test::meshoptBoxGlb());
  ASSERT_EQ(m.scene.meshes.size(), 2u);
  for (const auto& [mesh, part] : {std::pair{&m.scene.meshes[0], &g.box}, std::pair{&m.scene.meshes[1], &g.ground}}) {
    ASSERT_EQ(mesh->vertexCount(), part->positions.size() / 3);
    ASSERT_EQ(mesh->normals.size(), mesh->vertexCount());
    EXPECT_EQ(mesh->indices, part->indices);
    for (size_t i = 0; i < mesh->vertexCount(); ++i) {
      EXPECT_EQ(mesh->positions[i], glm::make_vec3(&part->positions[3 * i])) << i;
      EXPECT_NEAR(glm::distance(mesh->normals[i], glm::make_vec3(&part->normals[3 * i])), 0.0f, 2.0f / 127.0f) << i;
    }
  }
  EXPECT_EQ(readBytes(kData / "models/meshopt_box.glb"), test::meshoptBoxGlb()) << "rerun penumbra_make_compressed_models tests/data";
}

// KHR_draco_mesh_compression through Google's Draco decoder (it was refused: "accessor[0] invalid
// bufferView"). Draco reorders and quantises (14-bit positions, 10-bit normals, 12-bit texture
// coordinates): every original triangle is found again within the quantisation step.
TEST(ModelLoader, DracoDecodesToTheOriginalGeometry) {
  const test::BoxGeometry g = test::boxGeometry();
  const loaders::Model m = loadGlb(test::dracoBoxGlb());
  ASSERT_EQ(m.scene.meshes.size(), 2u);
  constexpr float kPositionToleranceM = 1e-3f, kNormalTolerance = 1e-2f;
  for (const auto& [mesh, part] : {std::pair{&m.scene.meshes[0], &g.box}, std::pair{&m.scene.meshes[1], &g.ground}}) {
    ASSERT_EQ(mesh->triangleCount(), part->indices.size() / 3);
    for (size_t t = 0; t < part->indices.size(); t += 3) {
      bool found = false;
      for (size_t u = 0; u < mesh->indices.size() && !found; u += 3)
        for (int rotation = 0; rotation < 3 && !found; ++rotation) {
          bool same = true;
          for (size_t c = 0; c < 3 && same; ++c) {
            const uint32_t original = part->indices[t + c];
            const uint32_t v = mesh->indices[u + (c + static_cast<size_t>(rotation)) % 3];
            same = glm::distance(mesh->positions[v], glm::make_vec3(&part->positions[3 * original])) < kPositionToleranceM &&
                   glm::distance(mesh->normals[v], glm::make_vec3(&part->normals[3 * original])) < kNormalTolerance;
          }
          found = same;
        }
      EXPECT_TRUE(found) << "original triangle " << t / 3 << " not found after decoding";
    }
  }
  EXPECT_EQ(readBytes(kData / "models/draco_box.glb"), test::dracoBoxGlb()) << "rerun penumbra_make_compressed_models tests/data";
}

// Broken compressed data is refused naming the extension's field (tests/data/bad, written by
// penumbra_make_compressed_models from the same code).
TEST(ModelLoader, BrokenCompressedDataNamesTheField) {
  const std::map<std::string, std::string> expected = {
      {"draco_truncated.glb", "primitives[0].extensions.KHR_draco_mesh_compression: Draco cannot decode it"},
      {"draco_missing_attribute.glb", "KHR_draco_mesh_compression.attributes.NORMAL: the Draco data has no attribute 77"},
      {"draco_count_mismatch.glb", "accessors[0].count: 3, the Draco mesh has 24 points"},
      {"meshopt_corrupt.glb", "bufferViews[0].extensions.EXT_meshopt_compression: meshoptimizer cannot decode it"},
      {"meshopt_count_mismatch.glb", "bufferViews[0].byteLength: 288, but 1000 elements of 12 bytes"}};
  const auto files = test::brokenCompressedFiles();
  ASSERT_EQ(files.size(), expected.size());
  for (const auto& [name, bytes] : files) {
    EXPECT_EQ(readBytes(kData / "bad" / name), bytes) << name << ": rerun penumbra_make_compressed_models tests/data";
    const std::string e = errorOf([&] { loadGlb(bytes); });
    EXPECT_NE(e.find(expected.at(name)), std::string::npos) << name << ": " << e;
  }
}

// Statements Penumbra ignores never reach tinyobjloader, which parses some of them with unchecked
// conversions (a `vw` joint id of 1e40 became an int: undefined behaviour, found by fuzzing), and
// lines end where tinyobjloader ends them (a lone CR too), so a statement cannot hide there.
TEST(ModelLoader, ObjStatementsPenumbraIgnoresAreNotParsed) {
  auto objError = [](const std::string& text) { return errorOf([&] { loaders::loadObjFromMemory(text, "mem.obj", ""); }); };
  const std::string triangle = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
  EXPECT_EQ(objError(triangle + "vw 0 1e40 0.5\nt tag 1/0/0 99999999999\ns 99999999999999999999\nl 1 2\nf 1 2 3\n"), "");
  EXPECT_NE(objError("v 0 0 0\rv nan 0 0\rv 0 1 0\rf 1 2 3\r").find("line 2: v: 'nan'"), std::string::npos);
  EXPECT_NE(objError("# a comment\rv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 99999999999\n").find("line 5: f: '99999999999'"),
            std::string::npos);
  const std::string e = errorOf([&] { loadScene((kData / "bad" / "skin_weight_overflow.obj").string()); });
  EXPECT_NE(e.find("vertex index 4 is out of range (3 vertices)"), std::string::npos) << e;
}

// A model given alone gets a ground under it at its lowest point, said in one sentence; one whose
// meshes hold a floor keeps its own and adds none; without the option nothing is added.
TEST(ModelLoader, ALoneModelGetsAGroundUnlessItHasAFloorOfItsOwn) {
  const fs::path box = kData / "models/box.obj";
  const Scene plain = loadScene(box.string());
  std::vector<std::string> notices;
  LoadOptions options;
  options.groundUnderLoneModel = true;
  options.notice = [&](const std::string& s) { notices.push_back(s); };
  const Scene grounded = loadScene(box.string(), options);
  ASSERT_EQ(grounded.objects.size(), plain.objects.size() + 1);
  const Object& ground = grounded.objects.back();
  EXPECT_EQ(ground.name, "ground (added)");
  EXPECT_FALSE(ground.castsShadow);
  const Aabb model = plain.bounds(), g = grounded.meshes[ground.mesh].bounds().transformed(ground.worldFromObject);
  EXPECT_FLOAT_EQ(g.lo.y, model.lo.y) << "at the model's lowest point";
  EXPECT_FLOAT_EQ(g.hi.x - g.lo.x, kGroundSpanFactor * std::max(model.hi.x - model.lo.x, model.hi.z - model.lo.z));
  ASSERT_EQ(notices.size(), 1u);
  EXPECT_EQ(notices[0].rfind("box.obj: no floor in the model, so a ", 0), 0u) << notices[0];

  // A floor of its own: a flat object under the whole footprint at the bottom.
  Scene floored = plain;
  addObject(floored, "floor", makePlane(20.0f, 20.0f), glm::vec3(0.5f), glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, model.lo.y, 0.0f)), true);
  const size_t objects = floored.objects.size();
  EXPECT_EQ(addGroundUnderModel(floored), "its own 'floor' is the floor: no ground added");
  EXPECT_EQ(floored.objects.size(), objects);
}

// BLEND's factor alpha is the share of light a surface covers; KHR_materials_transmission passes
// its factor of the covered share, tinted by the base colour. Both make a translucent caster.
TEST(ModelLoader, BlendAlphaAndTransmissionMakeTranslucentCasters) {
  const auto transmittanceOf = [](const std::string& material) {
    const std::string top = fmt::format(R"("extensionsUsed": ["KHR_materials_transmission"], "materials": [{}],)", material);
    const loaders::Model m = loadText(meshGltf(kSquare, {0, 1, 2}, R"(, "material": 0)", R"([{"mesh": 0}])", "[0]", top));
    return m.scene.materials.at(m.scene.objects.at(0).material).transmittance;
  };
  const std::string colour = R"("pbrMetallicRoughness": {"baseColorFactor": [1, 0.5, 0.25, ALPHA]})";
  const auto with = [&](const std::string& alpha, const std::string& rest) {
    std::string c = colour;
    c.replace(c.find("ALPHA"), 5, alpha);
    return "{" + c + rest + "}";
  };
  const glm::vec3 tint(1.0f, 0.5f, 0.25f);
  EXPECT_EQ(transmittanceOf(with("1", "")), glm::vec3(0.0f)) << "OPAQUE without transmission is opaque";
  EXPECT_EQ(transmittanceOf(with("0.6", R"(, "alphaMode": "MASK")")), glm::vec3(0.0f)) << "MASK is alpha-tested, not translucent";
  const glm::vec3 blend = transmittanceOf(with("0.4", R"(, "alphaMode": "BLEND")"));
  EXPECT_NEAR(blend.x, 0.6f, 1e-6f);
  EXPECT_EQ(blend.x, blend.y);
  EXPECT_EQ(blend.y, blend.z);
  const glm::vec3 glass = transmittanceOf(with("1", R"(, "extensions": {"KHR_materials_transmission": {"transmissionFactor": 0.8}})"));
  EXPECT_NEAR(glass.x, 0.8f * tint.x, 1e-6f);
  EXPECT_NEAR(glass.y, 0.8f * tint.y, 1e-6f);
  EXPECT_NEAR(glass.z, 0.8f * tint.z, 1e-6f);
  const glm::vec3 both = transmittanceOf(
      with("0.5", R"(, "alphaMode": "BLEND", "extensions": {"KHR_materials_transmission": {"transmissionFactor": 1}})"));
  EXPECT_NEAR(both.x, 0.5f + 0.5f * tint.x, 1e-6f);
  EXPECT_NEAR(both.y, 0.5f + 0.5f * tint.y, 1e-6f);
  EXPECT_NEAR(both.z, 0.5f + 0.5f * tint.z, 1e-6f);
  const std::string bad = errorOf([&] {
    transmittanceOf(with("1", R"(, "extensions": {"KHR_materials_transmission": {"transmissionFactor": 1.5}})"));
  });
  EXPECT_NE(bad.find("materials[0].extensions.KHR_materials_transmission.transmissionFactor"), std::string::npos) << bad;
}
