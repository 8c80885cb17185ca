#include "viewer/SceneWriter.h"

#include <penumbra/Error.h>
#include <penumbra/Files.h>
#include <penumbra/SceneIO.h>

#include <fmt/format.h>
#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>

namespace penumbra::viewer {
namespace {

using Json = nlohmann::json;

// Relative tolerance on the orthogonality of a transform's columns: above it the matrix has a
// shear, which translate/rotate/scale cannot express.
constexpr float kShearTolerance = 1e-3f;
// Below this |cos(pitch)| the Y-X-Z Euler split is at gimbal lock: roll is folded into yaw.
constexpr float kGimbalEpsilon = 1e-6f;

// Rounds to 7 significant digits so that the file shows 0.45, not 0.449999988.
double tidy(float v) {
  if (v == 0.0f || !std::isfinite(v)) return 0.0;
  return std::stod(fmt::format("{:.7g}", v));
}
Json tidyVec(const glm::vec3& v) { return Json::array({tidy(v.x), tidy(v.y), tidy(v.z)}); }

Json objectJson(const Scene& scene, const Object& o) {
  const Mesh& mesh = scene.meshes.at(o.mesh);
  const Aabb b = mesh.bounds();
  Json j;
  j["name"] = o.name;
  j["shape"] = mesh.name;
  const float radius = std::max({b.hi.x, -b.lo.x, b.hi.z, -b.lo.z});
  if (mesh.name == "plane") {
    j["size"] = Json::array({tidy(b.size().x), tidy(b.size().z)});
  } else if (mesh.name == "box") {
    j["size"] = tidyVec(b.size());
  } else if (mesh.name == "sphere") {
    j["radius"] = tidy(b.hi.y);
  } else if (mesh.name == "cylinder" || mesh.name == "cone") {
    j["radius"] = tidy(radius);
    j["height"] = tidy(b.hi.y);
  } else {
    throw Error(fmt::format("object '{}': its mesh '{}' has no scene-file form (plane, box, sphere, cylinder or cone); "
                            "save a scene that was loaded from a file instead",
                            o.name, mesh.name));
  }
  const Trs t = decomposeTransform(o.worldFromObject);
  j["translate"] = tidyVec(t.translate);
  j["rotateDeg"] = tidyVec(t.rotateDeg);
  j["scale"] = tidyVec(t.scale);
  j["color"] = tidyVec(scene.materials.at(o.material).baseColor);
  if (scene.materials.at(o.material).translucent()) j["transmittance"] = tidyVec(scene.materials.at(o.material).transmittance);
  j["castsShadow"] = o.castsShadow;
  if (o.dynamic) j["dynamic"] = true;
  return j;
}

Json lightJson(const Light& l) {
  Json j;
  j["type"] = lightTypeName(l.type);
  if (l.type != LightType::Point) j["direction"] = tidyVec(glm::normalize(l.direction));
  if (isPositional(l)) {
    j["position"] = tidyVec(l.position);
    if (l.rangeM > 0.0f) j["range"] = tidy(l.rangeM);
  }
  if (l.type == LightType::Spot) {
    j["outerConeDeg"] = tidy(glm::degrees(l.coneAngleRad));
    j["innerConeDeg"] = tidy(glm::degrees(l.innerConeAngleRad));
  }
  j["size"] = tidy(l.size);
  j["color"] = tidyVec(l.color);
  j["intensity"] = tidy(l.intensity);
  if (!l.castsShadow) j["castsShadow"] = false;
  if (!l.shadow.projection.empty() || !l.shadow.filter.empty() || l.shadow.mapSize > 0 || !l.shadow.params.empty() ||
      l.shadow.updates) {
    Json s;
    if (!l.shadow.projection.empty()) s["projection"] = l.shadow.projection;
    if (!l.shadow.filter.empty()) s["filter"] = l.shadow.filter;
    if (l.shadow.mapSize > 0) s["mapSize"] = l.shadow.mapSize;
    for (const auto& [key, value] : l.shadow.params) s["params"][key] = value;
    if (const auto& u = l.shadow.updates; u) {  // the text a scene file reads back
      if (u->policy == MapUpdates::Policy::Budget) s["updates"] = u->budgetMaps;
      else s["updates"] = mapUpdatesText(*u);
    }
    j["shadow"] = s;
  }
  return j;
}

Json paramsJson(const Parameterized& p, Json params) {
  for (const ParamDesc& d : p.paramDescs()) {
    const std::string text = formatParamValue(d, p.param(d.key));
    if (d.isChoice()) params[std::string(d.key)] = text;
    else params[std::string(d.key)] = std::stod(text);
  }
  return params;
}

}  // namespace

Trs decomposeTransform(const glm::mat4& m) {
  Trs t;
  t.translate = glm::vec3(m[3]);
  glm::vec3 col[3] = {glm::vec3(m[0]), glm::vec3(m[1]), glm::vec3(m[2])};
  for (int i = 0; i < 3; ++i) {
    t.scale[i] = glm::length(col[i]);
    if (!(t.scale[i] > 0.0f)) throw Error("a transform with a zero scale cannot be written to a scene file");
    col[i] /= t.scale[i];
  }
  for (int i = 0; i < 3; ++i)
    if (std::abs(glm::dot(col[i], col[(i + 1) % 3])) > kShearTolerance)
      throw Error("a transform with a shear cannot be written to a scene file");
  if (glm::dot(glm::cross(col[0], col[1]), col[2]) < 0.0f) {  // a mirror: fold it into scale x
    t.scale.x = -t.scale.x;
    col[0] = -col[0];
  }
  // R = Ry(a)·Rx(b)·Rz(c); r(row, column) = col[column][row]:
  //   r(1,2) = −sin b, r(0,2) = sin a·cos b, r(2,2) = cos a·cos b, r(1,0) = cos b·sin c, r(1,1) = cos b·cos c
  auto r = [&](int row, int column) { return col[column][row]; };
  const float b = std::asin(std::clamp(-r(1, 2), -1.0f, 1.0f));
  float a = 0.0f, c = 0.0f;
  if (std::abs(std::cos(b)) > kGimbalEpsilon) {
    a = std::atan2(r(0, 2), r(2, 2));
    c = std::atan2(r(1, 0), r(1, 1));
  } else {  // c = 0: r(0,0) = cos a, r(2,0) = −sin a
    a = std::atan2(-r(2, 0), r(0, 0));
  }
  t.rotateDeg = glm::degrees(glm::vec3(b, a, c));  // file order: x, y, z
  return t;
}

std::string sceneFileText(const Scene& scene, const Technique& technique) {
  Json j = Json::object();
  if (!scene.sourceFile.empty()) {
    std::ifstream in(scene.sourceFile, std::ios::binary);
    if (!in) throw Error(fmt::format("{}: cannot re-read the scene file to save it", scene.sourceFile.string()));
    try {
      j = Json::parse(in);
    } catch (const Json::parse_error& e) {
      throw Error(fmt::format("{}: no longer valid JSON: {}", scene.sourceFile.string(), e.what()));
    }
  } else {
    j["objects"] = Json::array();
    for (const Object& o : scene.objects) j["objects"].push_back(objectJson(scene, o));
  }
  j["name"] = scene.name;
  j["ambient"] = tidyVec(scene.ambient);
  const Camera& c = scene.camera;
  j["camera"] = {{"position", tidyVec(c.position)}, {"target", tidyVec(c.target)}, {"up", tidyVec(c.up)},
                 {"fovYDeg", tidy(glm::degrees(c.fovYRad))}, {"near", tidy(c.nearM)}, {"far", tidy(c.farM)}};
  j["lights"] = Json::array();
  for (const Light& l : scene.lights) j["lights"].push_back(lightJson(l));
  Json params = paramsJson(technique.filterValues(), paramsJson(technique.projectionValues(), Json::object()));
  j["shadow"] = {{"projection", technique.projection()}, {"filter", technique.filter()}, {"mapSize", technique.mapSize()}, {"params", params}};
  return j.dump(2) + "\n";
}

void saveSceneFile(const std::filesystem::path& path, const Scene& scene, const Technique& technique) {
  writeTextFile(path, sceneFileText(scene, technique));
  try {
    loadSceneFile(path);
  } catch (const Error& e) {
    throw Error(fmt::format("saved {}, but it does not load back: {}", path.string(), e.what()));
  }
}

}  // namespace penumbra::viewer
