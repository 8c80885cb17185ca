// Scene files (scenes/*.json). Every key is checked: an unknown key or a bad value is an error
// that names the file and the field ("scenes/x.json: objects[2].size: expected 3 numbers").
#include <penumbra/Error.h>
#include <penumbra/SceneIO.h>

#include "sceneio/AnimationFile.h"
#include "sceneio/JsonProblem.h"
#include "sceneio/loaders/ModelImport.h"

#include <fmt/format.h>
#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <map>
#include <optional>
#include <set>

namespace penumbra {
namespace {

using Json = nlohmann::json;

// A scene file is written by hand or by a small script: 64 MiB holds several times the 65 536
// objects the limits allow, and keeps a wrong path (a disk image) from being parsed as JSON.
constexpr uint64_t kMaxSceneFileBytes = uint64_t(64) << 20;
// The sphere's tessellation (slices around, stacks from pole to pole).
constexpr int kSphereSlices = 48, kSphereStacks = 24;
// Light and map-size limits (kMaxLightSphereM, kMinSpotConeDeg, kMinMapSizeTexels, ...) are
// Scene.h's: the viewer's edits obey them too.
constexpr float kMinMapSize = kMinMapSizeTexels, kMaxMapSize = kMaxMapSizeTexels;

/// A JSON object being read: remembers its path for messages and which keys were used.
class Reader {
public:
  Reader(const Json& j, std::string file, std::string path) : mJ(j), mFile(std::move(file)), mPath(std::move(path)) {
    if (!mJ.is_object()) fail("", "expected an object");
  }
  [[noreturn]] void fail(const std::string& key, const std::string& what) const {
    const std::string field = key.empty() ? mPath : (mPath.empty() ? key : mPath + "." + key);
    throw Error(fmt::format("{}: {}: {}", mFile, field.empty() ? "(top level)" : field, what));
  }
  bool has(const std::string& key) { mAllowed.insert(key); return mJ.contains(key); }
  const Json& raw(const std::string& key) { mAllowed.insert(key); return mJ.at(key); }

  float number(const std::string& key, float def, float lo = -1e30f, float hi = 1e30f) {
    if (!has(key)) return def;
    const Json& v = mJ.at(key);
    if (!v.is_number()) fail(key, "expected a number");
    const double d = v.get<double>();
    if (!std::isfinite(d) || d < lo || d > hi) fail(key, fmt::format("{} is outside [{}, {}]", d, lo, hi));
    return static_cast<float>(d);
  }
  /// A whole number in [lo, hi]: a count such as a map's texels per side (1000.5 is refused, not
  /// truncated).
  int whole(const std::string& key, int def, float lo, float hi) {
    const float v = number(key, static_cast<float>(def), lo, hi);
    if (v != std::floor(v)) fail(key, fmt::format("{} is not a whole number", v));
    return static_cast<int>(v);
  }
  std::string string(const std::string& key, const std::string& def) {
    if (!has(key)) return def;
    if (!mJ.at(key).is_string()) fail(key, "expected a string");
    return mJ.at(key).get<std::string>();
  }
  bool boolean(const std::string& key, bool def) {
    if (!has(key)) return def;
    if (!mJ.at(key).is_boolean()) fail(key, "expected true or false");
    return mJ.at(key).get<bool>();
  }
  template <int N>
  glm::vec<N, float> vec(const std::string& key, glm::vec<N, float> def) {
    if (!has(key)) return def;
    const Json& v = mJ.at(key);
    if (!v.is_array() || v.size() != N) fail(key, fmt::format("expected an array of {} numbers", N));
    glm::vec<N, float> r;
    for (int i = 0; i < N; ++i) {
      // Checked as a float: 1e300 is a finite double but no float.
      if (!v[i].is_number() || !std::isfinite(v[i].get<float>())) fail(key, fmt::format("expected an array of {} numbers", N));
      r[i] = v[i].get<float>();
    }
    return r;
  }
  /// An array of N numbers, each in [lo, hi].
  template <int N>
  glm::vec<N, float> vec(const std::string& key, glm::vec<N, float> def, float lo, float hi) {
    const glm::vec<N, float> v = vec<N>(key, def);
    for (int i = 0; i < N; ++i)
      if (!(v[i] >= lo && v[i] <= hi)) fail(key, fmt::format("{} is outside [{}, {}]", v[i], lo, hi));
    return v;
  }
  Reader child(const std::string& key) { return Reader(raw(key), mFile, mPath.empty() ? key : mPath + "." + key); }
  /// Call last: any key not read is an error.
  void finish() const {
    for (const auto& [k, v] : mJ.items())
      if (!mAllowed.count(k)) fail(k, "unknown key");
  }
  const std::string& file() const { return mFile; }
  const std::string& path() const { return mPath; }

private:
  const Json& mJ;
  std::string mFile, mPath;
  std::set<std::string> mAllowed;
};

Mesh readShape(Reader& r) {
  const std::string shape = r.string("shape", "");
  constexpr float kMaxSizeM = 1e6f;  // keeps the float math of every pass meaningful
  if (shape == "plane") {
    const glm::vec2 size = r.vec<2>("size", {10, 10});
    if (size.x <= 0 || size.y <= 0 || size.x > kMaxSizeM || size.y > kMaxSizeM) r.fail("size", "must be positive and at most 1e6");
    return makePlane(size.x, size.y);
  }
  if (shape == "box") {
    const glm::vec3 size = r.vec<3>("size", {1, 1, 1});
    if (glm::any(glm::lessThanEqual(size, glm::vec3(0))) || glm::any(glm::greaterThan(size, glm::vec3(kMaxSizeM))))
      r.fail("size", "must be positive and at most 1e6");
    return makeBox(size);
  }
  if (shape == "sphere") return makeSphere(r.number("radius", 0.5f, 1e-6f, kMaxSizeM), kSphereSlices, kSphereStacks);
  if (shape == "cylinder") return makeCylinder(r.number("radius", 0.5f, 1e-6f, kMaxSizeM), r.number("height", 1.0f, 1e-6f, kMaxSizeM));
  if (shape == "cone") return makeCone(r.number("radius", 0.5f, 1e-6f, kMaxSizeM), r.number("height", 1.0f, 1e-6f, kMaxSizeM));
  if (shape.empty()) r.fail("shape", "missing (plane, box, sphere, cylinder or cone)");
  r.fail("shape", fmt::format("unknown shape '{}' (plane, box, sphere, cylinder or cone)", shape));
}

glm::mat4 readTransform(Reader& r) {
  const glm::vec3 t = r.vec<3>("translate", glm::vec3(0));
  const glm::vec3 rotDeg = r.vec<3>("rotateDeg", glm::vec3(0));
  const glm::vec3 s = r.vec<3>("scale", glm::vec3(1));
  if (glm::any(glm::equal(s, glm::vec3(0)))) r.fail("scale", "must not be zero");
  glm::mat4 m = glm::translate(glm::mat4(1.0f), t);
  m = glm::rotate(m, glm::radians(rotDeg.y), {0, 1, 0});
  m = glm::rotate(m, glm::radians(rotDeg.x), {1, 0, 0});
  m = glm::rotate(m, glm::radians(rotDeg.z), {0, 0, 1});
  return glm::scale(m, s);
}

/// "params": {"technique.key": number or name, …} of a shadow block, in file order.
void readParams(Reader& parent, std::vector<std::pair<std::string, std::string>>& out) {
  if (!parent.has("params")) return;
  Reader p = parent.child("params");
  for (const auto& [key, value] : parent.raw("params").items()) {
    p.has(key);
    if (value.is_number()) out.emplace_back(key, fmt::format("{}", value.get<double>()));
    else if (value.is_string()) out.emplace_back(key, value.get<std::string>());
    else p.fail(key, "expected a number or a name");
  }
}

Light readLight(Reader& r) {
  Light l;
  const std::string type = r.string("type", "sun");
  if (type == "sun") l.type = LightType::Directional;
  else if (type == "spot") l.type = LightType::Spot;
  else if (type == "point") l.type = LightType::Point;
  else r.fail("type", fmt::format("unknown light type '{}' (sun, spot or point)", type));
  if (l.type != LightType::Point) {
    l.direction = r.vec<3>("direction", l.direction);
    if (glm::length(l.direction) < 1e-6f) r.fail("direction", "must not be zero");
    l.direction = glm::normalize(l.direction);
  }
  if (isPositional(l)) {
    l.position = r.vec<3>("position", l.position, -kMaxCoordinateM, kMaxCoordinateM);
    l.size = r.number("size", 0.0f, 0.0f, kMaxLightSphereM);
    l.rangeM = r.number("range", 0.0f, 0.0f, kMaxCoordinateM);
    if (l.rangeM > 0.0f && l.rangeM <= l.size) r.fail("range", fmt::format("{} m must exceed the light's size {} m", l.rangeM, l.size));
  } else {
    l.size = r.number("size", 0.0f, 0.0f, kMaxSunAngularRadiusRad);
  }
  if (l.type == LightType::Spot) {
    if (r.has("target")) {
      if (r.has("direction")) r.fail("target", "give target or direction, not both (the target sets the direction)");
      const glm::vec3 target = r.vec<3>("target", glm::vec3(0));
      if (glm::length(target - l.position) < 1e-6f) r.fail("target", "equals the position");
      l.direction = glm::normalize(target - l.position);
    }
    // coneAngleDeg: the older name of the outer angle.
    if (r.has("coneAngleDeg") && r.has("outerConeDeg")) r.fail("coneAngleDeg", "give outerConeDeg or coneAngleDeg, not both");
    const char* outerKey = r.has("coneAngleDeg") ? "coneAngleDeg" : "outerConeDeg";
    const float outerDeg = r.number(outerKey, glm::degrees(l.coneAngleRad), kMinSpotConeDeg, glm::degrees(kMaxSpotConeRad));
    l.coneAngleRad = glm::radians(outerDeg);
    // Without an inner angle the light fades over the cone's last kDefaultSpotFadeDeg degrees.
    const float innerDeg = r.number("innerConeDeg", std::max(0.0f, outerDeg - kDefaultSpotFadeDeg), 0.0f, outerDeg);
    l.innerConeAngleRad = glm::radians(innerDeg);
  }
  l.castsShadow = r.boolean("castsShadow", true);
  if (r.has("shadow")) {
    Reader s = r.child("shadow");
    l.shadow.projection = s.string("projection", "");  // the light's own technique; checked where techniques are known
    l.shadow.filter = s.string("filter", "");
    l.shadow.mapSize = s.whole("mapSize", 0, kMinMapSize, kMaxMapSize);
    readParams(s, l.shadow.params);
    if (s.has("updates")) {  // "every", "invalid" or a whole number of maps a frame
      const Json& u = s.raw("updates");
      if (u.is_number()) {
        l.shadow.updates = MapUpdates{MapUpdates::Policy::Budget, s.whole("updates", 1, 1.0f, static_cast<float>(kMaxBudgetMaps))};
      } else if (u.is_string()) {
        try {
          l.shadow.updates = parseMapUpdates(u.get<std::string>());
        } catch (const Error& e) {
          s.fail("updates", e.what());
        }
      } else {
        s.fail("updates", "expected \"every\", \"invalid\" or a number of maps per frame");
      }
    }
    s.finish();
  }
  l.color = r.vec<3>("color", l.color, 0.0f, kMaxRadiance);
  l.intensity = r.number("intensity", l.intensity, 0.0f, kMaxLightIntensity);
  r.finish();
  return l;
}

/// Vertices and triangles of a shape: fixed by its kind (the tessellation does not depend on the
/// size), measured once on a unit instance.
std::pair<uint64_t, uint64_t> shapeSize(const std::string& kind) {
  static const std::map<std::string, std::pair<uint64_t, uint64_t>> kSizes = [] {
    std::map<std::string, std::pair<uint64_t, uint64_t>> sizes;
    for (const auto& [name, mesh] : {std::pair{"plane", makePlane(1, 1)}, {"box", makeBox(glm::vec3(1))},
                                     {"sphere", makeSphere(1, kSphereSlices, kSphereStacks)}, {"cylinder", makeCylinder(1, 1)},
                                     {"cone", makeCone(1, 1)}})
      sizes[name] = {mesh.vertexCount(), mesh.triangleCount()};
    return sizes;
  }();
  const auto it = kSizes.find(kind);
  return it == kSizes.end() ? std::pair<uint64_t, uint64_t>{0, 0} : it->second;  // an unknown shape fails later, by name
}

// Fail fast (docs/scenes.md): the object count and the memory the shapes will take are checked
// before any shape is built (a file of 30 000 spheres once grew to 2.26 GB first). Model files
// are checked as each one is loaded.
void checkShapeTotals(const Json& objects, const Reader& top, const LoadOptions& options) {
  if (objects.size() > loaders::kMaxObjects)
    top.fail("objects", fmt::format("{} objects, more than the limit of {}", objects.size(), loaders::kMaxObjects));
  uint64_t vertices = 0, triangles = 0;
  for (const Json& o : objects) {
    if (!o.is_object() || !o.contains("shape") || !o["shape"].is_string()) continue;
    const auto [v, t] = shapeSize(o["shape"].get<std::string>());
    vertices += v;
    triangles += t;
  }
  try {
    loaders::checkSceneMemory({.vertices = vertices, .triangles = triangles, .normals = vertices, .uvs = vertices, .loaderBytes = 0},
                              "the shapes", options);
  } catch (const Error& e) {
    top.fail("objects", e.what());
  }
}

/// An object's "animation", over its own translate/rotateDeg/scale; none without the key.
std::optional<TransformTrack> readAnimation(Reader& r) {
  if (!r.has("animation")) return std::nullopt;
  return sceneio::readObjectAnimation(r.raw("animation"), {r.file(), r.path() + ".animation"}, r.vec<3>("translate", glm::vec3(0)),
                                      r.vec<3>("rotateDeg", glm::vec3(0)), r.vec<3>("scale", glm::vec3(1)));
}

/// Adds `track` as a node and makes the objects from `firstObject` on follow it; a model's own
/// animation roots (nodes from `firstNode` on, placed by `rest`) are hung below it.
void followNode(Scene& s, const TransformTrack& track, const std::string& name, const glm::mat4& rest, size_t firstObject, size_t firstNode) {
  std::vector<AnimatedNode>& nodes = s.animation.nodes;
  const glm::mat4 modelFromWorld = glm::inverse(rest);
  const auto node = static_cast<int>(firstNode);
  // The new node goes before the model's nodes (a parent comes before its children).
  nodes.insert(nodes.begin() + node, AnimatedNode{name, -1, glm::mat4(1.0f), track});
  for (size_t n = firstNode + 1; n < nodes.size(); ++n) {
    if (nodes[n].parent >= node) ++nodes[n].parent;
    else if (nodes[n].parent < 0) {
      nodes[n].parent = node;
      nodes[n].offset = modelFromWorld * nodes[n].offset;
    }
  }
  std::vector<bool> bound(s.objects.size(), false);
  for (ObjectAnimation& a : s.animation.objects)
    if (a.node >= firstNode) {
      ++a.node;
      bound[a.object] = true;
    }
  for (size_t o = firstObject; o < s.objects.size(); ++o)
    if (!bound[o]) s.animation.objects.push_back({static_cast<uint32_t>(o), static_cast<uint32_t>(node), modelFromWorld * s.objects[o].worldFromObject});
}

/// An object's "dynamic" flag, when given.
std::optional<bool> readDynamic(Reader& r) {
  if (!r.has("dynamic")) return std::nullopt;
  return r.boolean("dynamic", false);
}

/// Applies an object's "dynamic" flag to the objects it made (from `firstObject` on): true marks
/// them dynamic casters; false is refused when one of them is animated (by its own "animation" or
/// its model's), since a moving caster cannot stay in a cached map's static layer.
void applyDynamic(Scene& s, const Reader& r, std::optional<bool> declared, const std::string& name, size_t firstObject) {
  if (!declared) return;
  const std::vector<bool> moving = s.animation.movingObjects(s.objects.size());
  for (size_t o = firstObject; o < s.objects.size(); ++o) {
    if (!*declared && moving[o])
      r.fail("dynamic", fmt::format("'{}' is animated, so it cannot be static (drop \"dynamic\": false; animated objects are dynamic)", name));
    s.objects[o].dynamic = *declared;
  }
}

}  // namespace

Scene loadSceneFile(const std::filesystem::path& path, const LoadOptions& options) {
  const std::string file = path.string();
  const std::vector<uint8_t> bytes = loaders::readFileLimited(path, file, kMaxSceneFileBytes);
  // Parse errors (and numbers like 1e999, NaN, Infinity) name the field where parsing stopped.
  if (const std::string problem = sceneio::jsonParseProblem(bytes); !problem.empty())
    throw Error(fmt::format("{}: not valid JSON: {}", file, problem));
  const Json j = Json::parse(bytes.begin(), bytes.end());
  Reader top(j, file, "");
  Scene s;
  s.sourceFile = path;
  s.name = top.string("name", path.stem().string());
  s.ambient = top.vec<3>("ambient", s.ambient, 0.0f, kMaxRadiance);

  if (top.has("camera")) {
    Reader c = top.child("camera");
    s.camera.position = c.vec<3>("position", s.camera.position);
    s.camera.target = c.vec<3>("target", s.camera.target);
    s.camera.up = c.vec<3>("up", s.camera.up);
    s.camera.fovYRad = glm::radians(c.number("fovYDeg", glm::degrees(s.camera.fovYRad), 1.0f, 170.0f));
    s.camera.nearM = c.number("near", s.camera.nearM, 1e-4f, 1e4f);
    s.camera.farM = c.number("far", s.camera.farM, 1e-3f, 1e7f);
    if (s.camera.farM <= s.camera.nearM) c.fail("far", "must be larger than near");
    for (const auto& [key, p] : {std::pair{"position", s.camera.position}, std::pair{"target", s.camera.target}})
      if (glm::any(glm::greaterThan(glm::abs(p), glm::vec3(kMaxCoordinateM)))) c.fail(key, "beyond ±1e6 m");
    if (glm::length(s.camera.target - s.camera.position) < 1e-6f) c.fail("target", "equals the position");
    if (const std::string problem = s.camera.viewProblem(); !problem.empty())
      c.fail("up", problem + (c.has("up") ? "" : " (the default; set camera.up)"));
    if (c.has("animation")) s.animation.camera = sceneio::readCameraAnimation(c.raw("animation"), {file, "camera.animation"});
    c.finish();
  }

  if (!top.has("lights")) top.fail("lights", "missing (at least one light)");
  const Json& lights = top.raw("lights");
  if (!lights.is_array() || lights.empty()) top.fail("lights", "expected a non-empty array");
  if (lights.size() > kMaxLights) top.fail("lights", fmt::format("{} lights, more than the limit of {}", lights.size(), kMaxLights));
  for (size_t i = 0; i < lights.size(); ++i) {
    Reader r(lights[i], file, fmt::format("lights[{}]", i));
    const bool animated = r.has("animation"), sunPath = r.has("sunPath");  // read below, after the light
    s.lights.push_back(readLight(r));
    const auto index = static_cast<uint32_t>(i);
    if (animated)
      s.animation.lights.push_back(sceneio::readLightAnimation(r.raw("animation"), {file, r.path() + ".animation"}, s.lights.back(), index));
    if (sunPath) {
      if (s.lights.back().type != LightType::Directional) r.fail("sunPath", "only a sun has a sun path");
      if (animated) r.fail("sunPath", "give animation or sunPath, not both");
      s.animation.suns.push_back(sceneio::readSunPath(r.raw("sunPath"), {file, r.path() + ".sunPath"}, index));
    }
  }

  if (!top.has("objects")) top.fail("objects", "missing");
  const Json& objects = top.raw("objects");
  if (!objects.is_array() || objects.empty()) top.fail("objects", "expected a non-empty array");
  checkShapeTotals(objects, top, options);
  for (size_t i = 0; i < objects.size(); ++i) {
    Reader r(objects[i], file, fmt::format("objects[{}]", i));
    const std::string name = r.string("name", fmt::format("object {}", i));
    if (r.has("file")) {  // a glTF/OBJ model, path relative to this file, in place of a shape (docs/scenes.md)
      const std::string model = r.string("file", "");
      if (model.empty()) r.fail("file", "must name a .gltf, .glb or .obj file");
      for (const char* key : {"shape", "color", "transmittance"})
        if (r.has(key)) r.fail(key, "not allowed with 'file' (the model brings its own meshes and materials)");
      const glm::mat4 m = readTransform(r);
      const bool casts = r.boolean("castsShadow", true);
      const size_t firstObject = s.objects.size(), firstNode = s.animation.nodes.size();
      const std::optional<TransformTrack> track = readAnimation(r);
      const std::optional<bool> dynamic = readDynamic(r);
      r.finish();
      const std::filesystem::path modelPath = path.parent_path() / model;
      if (!loaders::isModelFile(modelPath)) r.fail("file", fmt::format("'{}' is not a .gltf, .glb or .obj file", model));
      try {
        loaders::appendModel(s, loaders::loadModelFile(modelPath, options).scene, m, casts, name, modelPath.string());
      } catch (const Error& e) {
        r.fail("file", e.what());
      }
      if (track) followNode(s, *track, name, m, firstObject, firstNode);
      applyDynamic(s, r, dynamic, name, firstObject);
      continue;
    }
    Mesh mesh = readShape(r);
    const glm::vec3 color = r.vec<3>("color", glm::vec3(0.8f));
    if (glm::any(glm::lessThan(color, glm::vec3(0))) || glm::any(glm::greaterThan(color, glm::vec3(1))))
      r.fail("color", "each component must be in [0, 1]");
    // The light that passes through it, per colour: a translucent caster (0 = opaque).
    const glm::vec3 transmittance = r.vec<3>("transmittance", glm::vec3(0.0f));
    if (glm::any(glm::lessThan(transmittance, glm::vec3(0))) || glm::any(glm::greaterThan(transmittance, glm::vec3(1))))
      r.fail("transmittance", "each component must be in [0, 1]");
    const glm::mat4 m = readTransform(r);
    const bool casts = r.boolean("castsShadow", true);
    const std::optional<TransformTrack> track = readAnimation(r);
    const std::optional<bool> dynamic = readDynamic(r);
    r.finish();
    const size_t object = s.objects.size(), node = s.animation.nodes.size();
    addObject(s, name, std::move(mesh), color, m, casts);
    s.materials[s.objects[object].material].transmittance = transmittance;
    if (track) followNode(s, *track, name, m, object, node);
    applyDynamic(s, r, dynamic, name, object);
  }

  if (top.has("shadow")) {
    Reader sh = top.child("shadow");
    s.shadow.projection = sh.string("projection", s.shadow.projection);
    s.shadow.filter = sh.string("filter", s.shadow.filter);
    s.shadow.mapSize = sh.whole("mapSize", s.shadow.mapSize, kMinMapSize, kMaxMapSize);
    readParams(sh, s.shadow.params);
    sh.finish();
  }
  top.finish();
  loaders::checkSceneLimits(s, file);  // totals and world coordinates, as for model files
  s.validate();
  return s;
}

Scene loadScene(const std::string& nameOrPath, const LoadOptions& options) {
  const bool looksLikeFile = nameOrPath.find('/') != std::string::npos || nameOrPath.find('.') != std::string::npos;
  if (!looksLikeFile) return makeBuiltinScene(nameOrPath);
  std::error_code ec;
  if (std::filesystem::is_directory(nameOrPath, ec)) throw Error(fmt::format("{}: is a folder, not a scene or model file", nameOrPath));
  if (loaders::isModelFile(nameOrPath)) return loaders::loadModelScene(nameOrPath, options);
  std::string ext = std::filesystem::path(nameOrPath).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext != ".json" && std::filesystem::exists(nameOrPath, ec))
    throw Error(fmt::format("{}: not a scene file (.json) or a model file (.gltf, .glb, .obj)", nameOrPath));
  return loadSceneFile(nameOrPath, options);
}

}  // namespace penumbra
