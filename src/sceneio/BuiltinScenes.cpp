// The built-in scenes: each one isolates a shadowing case that the techniques are judged on.
#include <penumbra/Error.h>
#include <penumbra/Params.h>
#include <penumbra/SceneIO.h>

#include "sceneio/BuiltinAnimation.h"
#include "sceneio/LampScenes.h"

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
  s.camera.position = {-0.7f, 2.1f, 2.7f};
  s.camera.target = {-0.85f, 0.1f, -0.1f};
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
  sceneio::animateBoxes(s);
  return s;
}

// Rows of thin slats at different depths in front of a wall: overlapping occluders, the case
// where variance-based methods leak light. The scene's own camera looks at the slats' shadows,
// whose leaks are mostly edge shape; the floor behind the wall, in its umbra under slats and wall
// both, is where two moments bleed (VarianceFilters.FenceBehindTheWallIsLightBleeding).
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

// A large plane (the top of a slab) lit at 80 degrees from its normal with a box resting on it: acne and
// peter-panning.
Scene makeGrazing() {
  Scene s;
  s.name = "grazing";
  // The plane is the top of a 0.2 m slab: a closed mesh, so second-depth has a second layer to
  // take the midpoint with (an open plane leaves it only its one-layer fallback).
  constexpr float kSlabM = 0.2f;
  addObject(s, "floor", makeBox({40.0f, kSlabM, 40.0f}), kFloorColor, translate({0.0f, -0.5f * kSlabM, 0.0f}));
  addObject(s, "box", makeBox({1.0f, 1.0f, 1.0f}), {0.8f, 0.35f, 0.3f}, translate({0.0f, 0.5f, 0.0f}));
  constexpr float kElevationDeg = 10.0f;  // 80 degrees from the plane's normal
  const float e = glm::radians(kElevationDeg);
  s.lights.push_back(sun({std::cos(e) * 0.94f, -std::sin(e), std::cos(e) * 0.34f}, 0.0f));
  s.camera.position = {-3.0f, 3.0f, 6.0f};
  s.camera.target = {1.5f, 0.0f, 0.0f};
  s.camera.fovYRad = 0.8f;
  return s;
}

// A city for large views (csm/psm/tsm/lispsm and the aliasing measure): a 640 m ground with a grid of
// buildings, street poles and trees, a plaza of trees and poles in front of the camera, which
// stands at eye height looking down an avenue toward the horizon under a low sun from the side.
Scene makeCity() {
  Scene s;
  s.name = "city";
  constexpr float kHalfM = 320.0f;               // the ground is 640 m on a side
  constexpr float kPitchM = 40.0f, kStreetM = 12.0f;  // block grid: 28 m blocks, 12 m streets
  constexpr float kPlazaStartZ = 240.0f;         // no buildings beyond: the plaza by the camera
  // Deterministic per-cell numbers in [0,1) (a hash: the same city on every platform).
  auto hash01 = [](uint32_t a, uint32_t b) {
    uint32_t h = a * 0x9E3779B1u ^ (b + 0x7F4A7C15u) * 0x85EBCA77u;
    h ^= h >> 15; h *= 0x2C1B3C6Du; h ^= h >> 12; h *= 0x297A2D39u; h ^= h >> 15;
    return static_cast<float>(h & 0xFFFFFFu) / 16777216.0f;
  };
  addObject(s, "ground", makePlane(2.0f * kHalfM, 2.0f * kHalfM), kFloorColor);
  const Mesh pole = makeCylinder(0.12f, 6.0f, 8), trunk = makeCylinder(0.25f, 3.0f, 8), crown = makeSphere(2.0f, 12, 8);
  auto addTree = [&](const glm::vec3& at, int id) {
    addObject(s, fmt::format("trunk {}", id), trunk, {0.4f, 0.3f, 0.2f}, translate(at));
    addObject(s, fmt::format("crown {}", id), crown, {0.3f, 0.55f, 0.25f}, translate(at + glm::vec3(0.0f, 4.5f, 0.0f)));
  };
  int trees = 0, poles = 0;
  const int cells = static_cast<int>(2.0f * kHalfM / kPitchM);
  for (int i = 0; i < cells; ++i)
    for (int j = 0; j < cells; ++j) {
      const float x = -kHalfM + kPitchM * (static_cast<float>(i) + 0.5f), z = -kHalfM + kPitchM * (static_cast<float>(j) + 0.5f);
      const auto ui = static_cast<uint32_t>(i), uj = static_cast<uint32_t>(j);
      // A pole at every crossing corner of the block.
      addObject(s, fmt::format("pole {}", poles++), pole, {0.3f, 0.3f, 0.32f},
                translate({x - 0.5f * kPitchM + 1.5f, 0.0f, z - 0.5f * kPitchM + 1.5f}));
      if (z > kPlazaStartZ) continue;
      const float block = kPitchM - kStreetM;
      if (hash01(ui, uj) < 0.15f) {  // a park: four trees
        for (int t = 0; t < 4; ++t)
          addTree({x + (t % 2 == 0 ? -0.25f : 0.25f) * block, 0.0f, z + (t < 2 ? -0.25f : 0.25f) * block}, trees++);
        continue;
      }
      const glm::vec3 size(block * (0.55f + 0.45f * hash01(ui + 101u, uj)), 8.0f + 37.0f * hash01(ui, uj + 211u),
                           block * (0.55f + 0.45f * hash01(ui + 307u, uj + 13u)));
      const float tone = 0.55f + 0.3f * hash01(ui + 17u, uj + 19u);
      addObject(s, fmt::format("building {}.{}", i, j), makeBox(size), {tone, tone * 0.95f, tone * 0.88f},
                translate({x, 0.5f * size.y, z}));
    }
  // The plaza in front of the camera: rows of trees and poles on open ground.
  for (int r = 0; r < 5; ++r)
    for (int c = -3; c <= 3; ++c) {
      const glm::vec3 at(7.0f * static_cast<float>(c) + 3.5f * static_cast<float>(r % 2), 0.0f, 302.0f - 12.0f * static_cast<float>(r));
      if (std::abs(at.x) < 2.0f) continue;  // keep the view down the avenue open
      if (c % 2 == 0) addTree(at, trees++);
      else addObject(s, fmt::format("pole {}", poles++), pole, {0.3f, 0.3f, 0.32f}, translate(at));
    }
  for (float x : {-4.0f, 4.0f})  // benches a few metres ahead: shadows right by the camera
    addObject(s, "bench", makeBox({2.0f, 0.5f, 0.6f}), {0.5f, 0.35f, 0.25f}, translate({x, 0.25f, 306.0f}));
  constexpr float kSunElevationDeg = 20.0f;
  const float e = glm::radians(kSunElevationDeg);
  // From the left and a little behind the camera: shadows fall across the avenue.
  const glm::vec3 horizontal = glm::normalize(glm::vec3(1.0f, 0.0f, -0.25f));
  s.lights.push_back(sun(horizontal * std::cos(e) + glm::vec3(0.0f, -std::sin(e), 0.0f), 0.005f));
  s.camera.position = {0.0f, 1.7f, 312.0f};
  s.camera.target = {0.0f, -2.0f, 212.0f};
  s.camera.fovYRad = 0.8f;
  s.camera.nearM = 0.1f;
  s.camera.farM = 2000.0f;
  s.shadow.projection = "csm";
  sceneio::animateCity(s);
  return s;
}

// Translucent casters under the sun: a stained-glass canopy (four coloured panes in opaque leading)
// and a tinted pane below it, on a floor. Their shadows are coloured: each pane's transmittance
// tints the light behind it, and where the light crosses a canopy pane and the tinted pane both,
// it keeps the product of the two; the leading and a box cast ordinary shadows beside them. The
// tinted pane's shadow is one large patch of one known hue (its red/green ratio is the test of a
// coloured shadow); the canopy's lie side by side, each bounded by opaque lines.
Scene makeGlass() {
  Scene s;
  s.name = "glass";
  addObject(s, "floor", makePlane(12.0f, 12.0f), kFloorColor);
  constexpr float kCanopyM = 1.6f, kPaneM = 0.8f, kLeadM = 0.05f;  // height, pane side, leading width
  const glm::vec3 canopy{0.0f, kCanopyM, 0.0f};
  struct Pane {
    const char* name;
    glm::vec3 transmittance;
  };
  const Pane panes[] = {{"red", {0.9f, 0.2f, 0.15f}},
                        {"green", {0.2f, 0.85f, 0.25f}},
                        {"blue", {0.2f, 0.35f, 0.9f}},
                        {"amber", {0.95f, 0.7f, 0.15f}}};
  for (int i = 0; i < 4; ++i) {
    const glm::vec3 centre = canopy + glm::vec3((i % 2 == 0 ? -0.5f : 0.5f) * kPaneM, 0.0f, (i < 2 ? -0.5f : 0.5f) * kPaneM);
    const uint32_t o = addObject(s, fmt::format("{} glass", panes[i].name), makePlane(kPaneM, kPaneM),
                                 panes[i].transmittance, translate(centre));
    s.materials[s.objects[o].material].transmittance = panes[i].transmittance;
  }
  for (int i = -1; i <= 1; ++i) {  // the leading: three bars each way, over the panes' edges
    const float offset = static_cast<float>(i) * kPaneM;
    addObject(s, fmt::format("lead x{}", i + 1), makeBox({2.0f * kPaneM + kLeadM, kLeadM, kLeadM}), {0.2f, 0.2f, 0.22f},
              translate(canopy + glm::vec3(0.0f, 0.0f, offset)));
    addObject(s, fmt::format("lead z{}", i + 1), makeBox({kLeadM, kLeadM, 2.0f * kPaneM + kLeadM}), {0.2f, 0.2f, 0.22f},
              translate(canopy + glm::vec3(offset, 0.0f, 0.0f)));
  }
  const glm::vec3 tint{0.85f, 0.45f, 0.3f};
  const uint32_t pane = addObject(s, "tinted pane", makePlane(1.2f, 1.0f), tint, translate({0.6f, 0.7f, -0.4f}));
  s.materials[s.objects[pane].material].transmittance = tint;
  addObject(s, "box", makeBox({0.6f, 0.6f, 0.6f}), {0.8f, 0.3f, 0.25f}, translate({-2.2f, 0.3f, -0.6f}));
  s.lights.push_back(sun({-0.5f, -1.0f, 0.6f}, 0.01f));
  s.camera.position = {1.5f, 3.8f, 5.0f};
  s.camera.target = {-0.4f, 0.2f, 0.3f};
  s.camera.fovYRad = 0.8f;
  return s;
}

struct Builtin {
  std::string_view name, description;
  std::function<Scene()> make;
};

const std::vector<Builtin>& builtins() {
  static const std::vector<Builtin> list = {
      {"boxes", "boxes and spheres on a plane under the sun (the default); animated: a ball rolls, the sun sweeps 30 degrees", makeBoxes},
      {"pen", "a pencil leaning on the floor under a spherical spot light: contact-hardening penumbra", makePen},
      {"fence", "rows of thin slats before a wall: overlapping occluders (variance light bleeding behind the wall: --camera 4,3,-6:0,0,-3.5:50)", makeFence},
      {"grazing", "a large plane (a slab's top) lit 80 degrees from its normal with a box on it: acne and peter-panning", makeGrazing},
      {"city", "a 640 m city under a low sun, seen from eye height: perspective aliasing (csm/psm/tsm/lispsm)", makeCity},
      {"room", "a room under a hanging point lamp (light 0, a 5 cm sphere) and a spot on the shelves: the table's shadow on the floor and up the left wall, the chair's, the books'; animated: the lamp swings 12 degrees from its hook",
       [] {
         Scene s = makeRoomScene();
         sceneio::animateRoom(s);
         return s;
       }},
      {"glass", "a stained-glass canopy and a tinted pane over a floor under the sun: coloured shadows through translucent casters, and their product where both overlap", makeGlass},
      {"night", "a street at night under 8 lamps (4 point, 4 spot) whose shadows overlap; lights ordered near to far for sweeps of the first N", makeNightScene},
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
  const std::string known = joinNames(builtinSceneNames());
  throw usageError(fmt::format("unknown scene '{}' (built-in scenes: {}; or give a scene .json file or a .gltf, .glb or .obj model)", name, known));
}

}  // namespace penumbra
