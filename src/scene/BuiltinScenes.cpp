// The built-in scenes: each one isolates a shadowing case that the techniques are judged on.
#include <penumbra/Error.h>
#include <penumbra/SceneIO.h>

#include <fmt/format.h>
#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <functional>

namespace penumbra {
namespace {

const glm::vec3 kFloorColor{0.75f, 0.75f, 0.72f};

glm::mat4 translate(const glm::vec3& t) { return glm::translate(glm::mat4(1.0f), t); }

Light sun(const glm::vec3& towardScene, float angularRadiusRad) {
  Light l;
  l.type = LightType::Directional;
  l.direction = glm::normalize(towardScene);
  l.size = angularRadiusRad;
  l.intensity = 2.0f;
  return l;
}

// A pencil leaning with its tip on the floor under a spherical spot light: the shadow is sharp
// at the contact and widens with the distance between pencil and floor.
Scene makePen() {
  Scene s;
  s.name = "pen";
  addObject(s, "floor", makePlane(8.0f, 8.0f), kFloorColor);
  constexpr float kRadiusM = 0.04f, kBodyM = 1.5f, kTipM = 0.12f;
  constexpr float kLeanRad = 0.45f;  // angle between pencil and floor
  // Pencil axis: from the tip on the floor at the origin, up and toward -X.
  const glm::vec3 axis{-std::cos(kLeanRad), std::sin(kLeanRad), 0.0f};
  // Local +Y of the shapes is mapped onto `axis` by a rotation about +Z.
  const glm::mat4 alignY = glm::rotate(glm::mat4(1.0f), glm::half_pi<float>() - kLeanRad, {0, 0, 1});
  const glm::vec3 tip{0.0f};  // the cone's apex rests on the floor
  // Cone pointing down the axis: base at tip + axis*kTipM, apex at the tip.
  const glm::mat4 flip = glm::rotate(glm::mat4(1.0f), glm::pi<float>(), {0, 0, 1});
  addObject(s, "pencil tip", makeCone(kRadiusM, kTipM, 24), {0.85f, 0.7f, 0.5f},
            translate(tip + axis * kTipM) * alignY * flip);
  addObject(s, "pencil", makeCylinder(kRadiusM, kBodyM, 24), {0.95f, 0.75f, 0.1f},
            translate(tip + axis * kTipM) * alignY);
  Light spot;
  spot.type = LightType::Spot;
  spot.position = {-0.2f, 2.6f, 0.6f};
  spot.direction = glm::normalize(glm::vec3(-0.35f, 0.0f, 0.0f) - spot.position);
  spot.coneAngleRad = 0.75f;
  spot.size = 0.12f;
  spot.intensity = 9.0f;
  s.lights.push_back(spot);
  s.camera.position = {-0.3f, 1.9f, 2.6f};
  s.camera.target = {-0.45f, 0.1f, 0.0f};
  s.camera.fovYRad = 0.75f;
  s.camera.farM = 50.0f;
  return s;
}

// Boxes and spheres on a plane under the sun.
Scene makeBoxes() {
  Scene s;
  s.name = "boxes";
  addObject(s, "floor", makePlane(24.0f, 24.0f), kFloorColor);
  addObject(s, "box A", makeBox({1.0f, 1.0f, 1.0f}), {0.8f, 0.3f, 0.25f}, translate({-1.5f, 0.5f, 0.0f}));
  addObject(s, "box B", makeBox({0.8f, 2.0f, 0.8f}), {0.3f, 0.5f, 0.8f}, translate({1.2f, 1.0f, -1.0f}));
  addObject(s, "box C", makeBox({2.0f, 0.4f, 0.6f}), {0.4f, 0.7f, 0.35f},
            translate({0.4f, 0.2f, 1.6f}) * glm::rotate(glm::mat4(1.0f), 0.5f, {0, 1, 0}));
  addObject(s, "sphere A", makeSphere(0.6f, 48, 24), {0.9f, 0.8f, 0.3f}, translate({0.0f, 0.6f, -0.2f}));
  addObject(s, "sphere B", makeSphere(0.35f, 32, 16), {0.7f, 0.4f, 0.8f}, translate({-2.8f, 1.4f, 1.2f}));
  s.lights.push_back(sun({-0.45f, -1.0f, -0.35f}, 0.02f));
  s.camera.position = {3.5f, 4.0f, 6.5f};
  s.camera.target = {-0.3f, 0.3f, 0.0f};
  s.camera.fovYRad = 0.8f;
  return s;
}

// Rows of thin slats at different depths in front of a wall: overlapping occluders, the case
// where variance-based methods leak light.
Scene makeFence() {
  Scene s;
  s.name = "fence";
  addObject(s, "floor", makePlane(16.0f, 16.0f), kFloorColor);
  addObject(s, "wall", makeBox({8.0f, 3.0f, 0.2f}), {0.8f, 0.78f, 0.7f}, translate({0.0f, 1.5f, -2.5f}));
  constexpr int kRows = 3, kSlatsPerRow = 9;
  constexpr float kSlatWidthM = 0.12f, kSpacingM = 0.4f, kSlatHeightM = 1.6f;
  for (int row = 0; row < kRows; ++row) {
    const float z = -1.6f + 0.7f * static_cast<float>(row);
    const float shift = 0.13f * static_cast<float>(row);
    for (int i = 0; i < kSlatsPerRow; ++i) {
      const float x = (static_cast<float>(i) - 0.5f * (kSlatsPerRow - 1)) * kSpacingM + shift;
      addObject(s, fmt::format("slat {}.{}", row, i), makeBox({kSlatWidthM, kSlatHeightM, 0.05f}),
                {0.55f, 0.4f, 0.3f}, translate({x, 0.5f * kSlatHeightM, z}));
    }
  }
  s.lights.push_back(sun({0.25f, -0.55f, -1.0f}, 0.03f));
  s.camera.position = {1.8f, 2.2f, 4.2f};
  s.camera.target = {0.0f, 0.8f, -1.6f};
  s.camera.fovYRad = 0.85f;
  return s;
}

// A large plane lit at 80 degrees from its normal with a box resting on it: acne and
// peter-panning.
Scene makeGrazing() {
  Scene s;
  s.name = "grazing";
  addObject(s, "floor", makePlane(40.0f, 40.0f), kFloorColor);
  addObject(s, "box", makeBox({1.0f, 1.0f, 1.0f}), {0.8f, 0.35f, 0.3f}, translate({0.0f, 0.5f, 0.0f}));
  constexpr float kElevationDeg = 10.0f;  // 80 degrees from the plane's normal
  const float e = glm::radians(kElevationDeg);
  s.lights.push_back(sun({std::cos(e) * 0.94f, -std::sin(e), std::cos(e) * 0.34f}, 0.0f));
  s.camera.position = {-3.0f, 3.0f, 6.0f};
  s.camera.target = {1.5f, 0.0f, 0.0f};
  s.camera.fovYRad = 0.8f;
  return s;
}

struct Builtin {
  std::string_view name, description;
  std::function<Scene()> make;
};

const std::vector<Builtin>& builtins() {
  static const std::vector<Builtin> list = {
      {"boxes", "boxes and spheres on a plane under the sun (the default)", makeBoxes},
      {"pen", "a pencil leaning on the floor under a spherical spot light: contact-hardening penumbra", makePen},
      {"fence", "rows of thin slats before a wall: overlapping occluders, variance light leaks", makeFence},
      {"grazing", "a plane lit 80 degrees from its normal with a box on it: acne and peter-panning", makeGrazing},
  };
  return list;
}

}  // namespace

std::vector<std::string> builtinSceneNames() {
  std::vector<std::string> names;
  for (const Builtin& b : builtins()) names.emplace_back(b.name);
  return names;
}

std::string_view builtinSceneDescription(std::string_view name) {
  for (const Builtin& b : builtins())
    if (b.name == name) return b.description;
  return {};
}

Scene makeBuiltinScene(std::string_view name) {
  for (const Builtin& b : builtins())
    if (b.name == name) {
      Scene s = b.make();
      s.validate();
      return s;
    }
  std::string known;
  for (const Builtin& b : builtins()) known += (known.empty() ? "" : ", ") + std::string(b.name);
  throw usageError(fmt::format("unknown scene '{}' (built-in scenes: {}; or give a .json file)", name, known));
}

}  // namespace penumbra
