#include "viewer/LightEdit.h"

#include "viewer/Cameras.h"

#include <penumbra/Error.h>

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <optional>

namespace penumbra::viewer {
namespace {

// Placement of a new light (makeLight). Distances are in units of the scene's reach: the smaller
// of its bounds' radius and the camera's distance to its target (a floor 20 m wide must not push
// the light out of a view that looks at one pencil).
constexpr float kMinReachM = 0.5f;              // a tiny scene still gets a light some way off
constexpr float kSpotDistanceReach = 1.5f;      // far enough for a 35° cone to cover the reach
constexpr float kPointDistanceReach = 0.75f;    // close: a point light lights its surroundings
constexpr float kNewSpotOuterDeg = 35.0f;
constexpr float kNewElevationDeg = 50.0f;       // shadows about as long as their casters are tall
constexpr float kAzimuthStepDeg = 70.0f;        // each new light from another side
constexpr float kNewSunSizeRad = 0.01f;         // a little soft (about twice the real sun's 0.0047)
constexpr float kNewSphereSizeReach = 0.02f;    // sphere radius of a new spot or point light
// Tints by index, so that the lights' contributions can be told apart on screen.
constexpr std::array<glm::vec3, 5> kTints = {glm::vec3(1.0f), {1.0f, 0.85f, 0.7f}, {0.7f, 0.85f, 1.0f},
                                             {1.0f, 0.75f, 0.9f}, {0.8f, 1.0f, 0.75f}};
constexpr const char* kFaceNames[kCubeFaces] = {"+X", "-X", "+Y", "-Y", "+Z", "-Z"};
// Below this length a direction has none.
constexpr float kMinDirectionLength = 1e-6f;

bool finite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

float reachOf(const Aabb& bounds, const glm::vec3& aim, const Camera& camera) {
  const float radius = bounds.empty() ? kMinReachM : bounds.radius();
  return std::max(std::min(radius, glm::length(camera.position - aim)), kMinReachM);
}

glm::vec3 centreOf(const Aabb& bounds) { return bounds.empty() ? glm::vec3(0.0f) : bounds.center(); }

// The distance from a sun's aim point at which changeLightType() places a positional light.
float stand(const Aabb& bounds) { return kSpotDistanceReach * std::max(bounds.empty() ? 0.0f : bounds.radius(), kMinReachM); }

float parseNumber(std::string_view key, std::string_view text) {
  float v = 0.0f;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (text.empty() || ec != std::errc() || end != text.data() + text.size() || !std::isfinite(v))
    throw usageError(fmt::format("{}={}: '{}' is not a number", key, text, text));
  return v;
}

glm::vec3 parseVector(std::string_view key, std::string_view text) {
  glm::vec3 v(0.0f);
  size_t start = 0;
  for (int i = 0; i < 3; ++i) {
    const size_t comma = text.find(',', start);
    if ((i < 2) != (comma != std::string_view::npos))
      throw usageError(fmt::format("{}={}: expected three numbers X,Y,Z", key, text));
    const std::string_view part = text.substr(start, comma == std::string_view::npos ? std::string_view::npos : comma - start);
    v[i] = parseNumber(key, part);
    start = comma + 1;
  }
  return v;
}

bool parseSwitch(std::string_view key, std::string_view text) {
  if (text == "on" || text == "true") return true;
  if (text == "off" || text == "false") return false;
  throw usageError(fmt::format("{}={}: expected on or off", key, text));
}

enum class Form { Type, Number, Vector, Switch, Texels, Updates };

struct Key {
  std::string_view name;
  Form form;
};

constexpr Key kKeys[] = {
    {"type", Form::Type},          {"position", Form::Vector},     {"direction", Form::Vector},
    {"target", Form::Vector},      {"size", Form::Number},         {"color", Form::Vector},
    {"intensity", Form::Number},   {"outerConeDeg", Form::Number}, {"innerConeDeg", Form::Number},
    {"range", Form::Number},       {"castsShadow", Form::Switch},  {"mapSize", Form::Texels},
    {"updates", Form::Updates},
};

const Key& findKey(std::string_view name) {
  for (const Key& k : kKeys)
    if (k.name == name) return k;
  std::string known;
  for (const Key& k : kKeys) known += (known.empty() ? "" : ", ") + std::string(k.name);
  throw usageError(fmt::format("unknown light key '{}' (known: {})", name, known));
}

/// A light's own map updates: "every", "invalid", N maps a frame, or "default" (Shadows' policy).
std::optional<MapUpdates> parseLightUpdates(std::string_view text) {
  if (text == "default") return std::nullopt;
  return parseMapUpdates(text);
}

int parseTexels(std::string_view key, std::string_view text) {
  const float v = parseNumber(key, text);
  if (v != std::floor(v) || !(v == 0.0f || (v >= kMinMapSizeTexels && v <= kMaxMapSizeTexels)))
    throw usageError(fmt::format("{}={}: expected 0 (the technique's size) or a whole number of texels in [{}, {}]", key, text,
                                 kMinMapSizeTexels, kMaxMapSizeTexels));
  return static_cast<int>(v);
}

// The value words of `light set N KEY VALUE...` as one text: a vector's X Y Z joined as X,Y,Z.
std::string valueText(const Key& k, std::span<const std::string> value) {
  if (k.form == Form::Vector && value.size() == 3) return value[0] + "," + value[1] + "," + value[2];
  if (value.size() != 1)
    throw usageError(fmt::format("{}: expected {}", k.name, k.form == Form::Vector ? "X Y Z or X,Y,Z" : "one value"));
  return value[0];
}

std::string checkForm(const Key& k, std::span<const std::string> value) {
  const std::string text = valueText(k, value);
  switch (k.form) {
    case Form::Type: parseLightType(text); break;
    case Form::Number: parseNumber(k.name, text); break;
    case Form::Vector: parseVector(k.name, text); break;
    case Form::Switch: parseSwitch(k.name, text); break;
    case Form::Texels: parseTexels(k.name, text); break;
    case Form::Updates: parseLightUpdates(text); break;
  }
  return text;
}

}  // namespace

LightType parseLightType(std::string_view name) {
  for (LightType t : {LightType::Directional, LightType::Spot, LightType::Point})
    if (name == lightTypeName(t)) return t;
  throw usageError(fmt::format("unknown light type '{}' (sun, spot or point)", name));
}

std::string lightLabel(const Light& light, size_t index) { return fmt::format("light {} ({})", index, lightTypeName(light.type)); }

const char* cubeFaceName(int face) { return face >= 0 && face < kCubeFaces ? kFaceNames[face] : "?"; }

std::string lightProblem(const Light& l) {
  if (l.shadow.mapSize != 0 && (l.shadow.mapSize < kMinMapSizeTexels || l.shadow.mapSize > kMaxMapSizeTexels))
    return fmt::format("the map size must be 0 (the technique's) or in [{}, {}] texels", kMinMapSizeTexels, kMaxMapSizeTexels);
  if (!finite(l.color) || glm::any(glm::lessThan(l.color, glm::vec3(0.0f))) || glm::any(glm::greaterThan(l.color, glm::vec3(kMaxRadiance))))
    return fmt::format("the colour must be in [0, {}]", kMaxRadiance);
  if (!std::isfinite(l.intensity) || l.intensity < 0.0f || l.intensity > kMaxLightIntensity)
    return fmt::format("the intensity must be in [0, {}]", kMaxLightIntensity);
  if (l.type != LightType::Point && (!finite(l.direction) || glm::length(l.direction) < kMinDirectionLength))
    return "the direction must not be zero";
  if (!isPositional(l)) {
    if (!std::isfinite(l.size) || l.size < 0.0f || l.size > kMaxSunAngularRadiusRad)
      return fmt::format("a sun's size is its angular radius in rad, in [0, {}]", kMaxSunAngularRadiusRad);
    return {};
  }
  if (!finite(l.position) || glm::any(glm::greaterThan(glm::abs(l.position), glm::vec3(kMaxCoordinateM))))
    return fmt::format("the position must be within ±{} m", kMaxCoordinateM);
  if (!std::isfinite(l.size) || l.size < 0.0f || l.size > kMaxLightSphereM)
    return fmt::format("the size (sphere radius) must be in [0, {}] m", kMaxLightSphereM);
  if (!std::isfinite(l.rangeM) || l.rangeM < 0.0f || l.rangeM > kMaxCoordinateM)
    return fmt::format("the range must be in [0, {}] m (0 = unlimited)", kMaxCoordinateM);
  if (l.rangeM > 0.0f && l.rangeM <= l.size)
    return fmt::format("the range {} m must exceed the light's size {} m (or be 0 = unlimited)", l.rangeM, l.size);
  if (l.type == LightType::Spot) {
    const float outerDeg = glm::degrees(l.coneAngleRad), innerDeg = glm::degrees(l.innerConeAngleRad);
    if (!(outerDeg >= kMinSpotConeDeg && l.coneAngleRad <= kMaxSpotConeRad))
      return fmt::format("the outer cone angle {:.4g}° must be in [{}, {:.4g}]°", outerDeg, kMinSpotConeDeg, glm::degrees(kMaxSpotConeRad));
    if (!(l.innerConeAngleRad >= 0.0f && l.innerConeAngleRad <= l.coneAngleRad))
      return fmt::format("the inner cone angle {:.4g}° must be in [0, {:.4g}]° (the outer one)", innerDeg, outerDeg);
  }
  return {};
}

Light makeLight(LightType type, const Aabb& bounds, const Camera& camera, size_t index) {
  const glm::vec3 aim = bounds.empty() ? camera.target : glm::clamp(camera.target, bounds.lo, bounds.hi);
  const float reach = reachOf(bounds, aim, camera);
  const glm::vec3 fromAim = camera.position - aim;
  const float cameraAzimuthRad = std::atan2(fromAim.x, fromAim.z);
  const float azimuthRad = cameraAzimuthRad + glm::radians(kAzimuthStepDeg) * static_cast<float>(index);
  Light l;
  l.type = type;
  l.color = kTints[index % kTints.size()];
  if (type == LightType::Directional) {
    l.size = kNewSunSizeRad;
  } else {
    const float distanceM = reach * (type == LightType::Spot ? kSpotDistanceReach : kPointDistanceReach);
    l.position = aim + glm::vec3(0.0f, distanceM, 0.0f);  // setLightAngles keeps this distance
    l.intensity *= distanceM * distanceM;  // inverse square: as bright at `aim` as the default sun
    l.size = kNewSphereSizeReach * reach;
    l.coneAngleRad = glm::radians(kNewSpotOuterDeg);
    l.innerConeAngleRad = glm::radians(kNewSpotOuterDeg - kDefaultSpotFadeDeg);
  }
  setLightAngles(l, aim, azimuthRad, glm::radians(kNewElevationDeg));
  return l;
}

void changeLightType(Light& l, LightType type, const Aabb& bounds) {
  if (type == l.type) return;
  const glm::vec3 aim = lightAimPoint(l, bounds);
  if (l.type == LightType::Directional) {  // sun → on its line through the aim point
    const float d = stand(bounds);
    l.position = aim - d * glm::normalize(l.direction);
    l.size = std::min(std::tan(l.size) * d, kMaxLightSphereM);
    l.intensity = std::min(l.intensity * d * d, kMaxLightIntensity);
  } else if (type == LightType::Directional) {  // → the sun of its direction to the aim point
    const glm::vec3 toAim = aim - l.position;
    const float d = glm::length(toAim);
    if (d > kMinDirectionLength) {
      l.direction = toAim / d;
      l.size = std::min(std::atan(l.size / d), kMaxSunAngularRadiusRad);
      l.intensity /= d * d;
    }
    l.rangeM = 0.0f;
  } else if (type == LightType::Spot) {  // point → spot: aims at the scene's centre
    const glm::vec3 toCentre = centreOf(bounds) - l.position;
    if (glm::length(toCentre) > kMinDirectionLength) l.direction = glm::normalize(toCentre);
  }
  l.type = type;
  if (type == LightType::Spot) {  // keep the cone one a scene file holds
    l.coneAngleRad = std::clamp(l.coneAngleRad, glm::radians(kMinSpotConeDeg), kMaxSpotConeRad);
    l.innerConeAngleRad = std::clamp(l.innerConeAngleRad, 0.0f, l.coneAngleRad);
  }
}

std::vector<std::string> lightKeys() {
  std::vector<std::string> out;
  for (const Key& k : kKeys) out.emplace_back(k.name);
  return out;
}

void checkLightSetting(std::string_view key, std::span<const std::string> value) { checkForm(findKey(key), value); }

Light setLightField(Light l, std::string_view key, std::span<const std::string> value, const Aabb& bounds) {
  const std::string text = checkForm(findKey(key), value);
  const char* type = lightTypeName(l.type);
  auto require = [&](bool has, const char* what) {
    if (!has) throw usageError(fmt::format("{}: the light is a {}, which has {}", key, type, what));
  };
  if (key == "type") {
    changeLightType(l, parseLightType(text), bounds);
  } else if (key == "position") {
    require(isPositional(l), "a direction, not a position");
    l.position = parseVector(key, text);
  } else if (key == "direction") {
    require(l.type != LightType::Point, "no direction (it shines everywhere)");
    const glm::vec3 d = parseVector(key, text);
    if (glm::length(d) < kMinDirectionLength) throw usageError("direction: must not be zero");
    l.direction = glm::normalize(d);
  } else if (key == "target") {
    require(l.type == LightType::Spot, "no target (only a spot aims)");
    const glm::vec3 d = parseVector(key, text) - l.position;
    if (glm::length(d) < kMinDirectionLength) throw usageError("target: equals the light's position");
    l.direction = glm::normalize(d);
  } else if (key == "size") {
    l.size = parseNumber(key, text);
  } else if (key == "color") {
    l.color = parseVector(key, text);
  } else if (key == "intensity") {
    l.intensity = parseNumber(key, text);
  } else if (key == "outerConeDeg") {
    require(l.type == LightType::Spot, "no cone");
    l.coneAngleRad = glm::radians(parseNumber(key, text));
    l.innerConeAngleRad = std::min(l.innerConeAngleRad, l.coneAngleRad);
  } else if (key == "innerConeDeg") {
    require(l.type == LightType::Spot, "no cone");
    l.innerConeAngleRad = glm::radians(parseNumber(key, text));
  } else if (key == "range") {
    require(isPositional(l), "no range (a sun reaches everywhere)");
    l.rangeM = parseNumber(key, text);
  } else if (key == "castsShadow") {
    l.castsShadow = parseSwitch(key, text);
  } else if (key == "mapSize") {
    l.shadow.mapSize = parseTexels(key, text);
  } else if (key == "updates") {
    l.shadow.updates = parseLightUpdates(text);
  }
  if (const std::string problem = lightProblem(l); !problem.empty()) throw usageError(fmt::format("{}: {}", key, problem));
  return l;
}

}  // namespace penumbra::viewer
