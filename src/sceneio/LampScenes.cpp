// Scenes lit by lamps as interiors and streets are: spheres a few centimetres across with a range,
// point lights whose shadows need all six cube faces, spots with an inner and an outer cone, and
// several shadowed lights whose pools overlap. Sizes are of real furniture and streets (metres);
// intensities are chosen so that a lit surface under its lamp reaches about the brightness a
// surface under the other scenes' sun has (the lit pass has no exposure control).
#include "sceneio/LampScenes.h"

#include <fmt/format.h>
#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <array>

namespace penumbra {
namespace {

glm::mat4 at(const glm::vec3& t) { return glm::translate(glm::mat4(1.0f), t); }
glm::mat4 at(const glm::vec3& t, float yawRad) { return glm::rotate(at(t), yawRad, {0.0f, 1.0f, 0.0f}); }

Light pointLight(const glm::vec3& position, float radiusM, float rangeM, float intensity, const glm::vec3& color) {
  Light l;
  l.type = LightType::Point;
  l.position = position;
  l.size = radiusM;
  l.rangeM = rangeM;
  l.intensity = intensity;
  l.color = color;
  return l;
}

Light spotLight(const glm::vec3& position, const glm::vec3& target, float innerRad, float outerRad, float radiusM,
                float rangeM, float intensity, const glm::vec3& color) {
  Light l = pointLight(position, radiusM, rangeM, intensity, color);
  l.type = LightType::Spot;
  l.direction = glm::normalize(target - position);
  l.innerConeAngleRad = innerRad;
  l.coneAngleRad = outerRad;
  return l;
}

// --- room --------------------------------------------------------------------------------------

constexpr float kRoomHalfWidthM = 2.5f;  // the room spans x in [-2.5, 2.5] …
constexpr float kRoomBackZ = -2.5f, kRoomFrontZ = 2.5f;  // … and z from the back wall to the open side
constexpr float kRoomHeightM = 2.6f;
constexpr float kWallM = 0.1f;  // walls and ceiling are slabs (closed meshes, as second-depth wants)
const glm::vec3 kWallColor{0.78f, 0.74f, 0.66f};
const glm::vec3 kWoodColor{0.55f, 0.36f, 0.22f};

// A table standing on the floor: a top (upper face at heightM) on four legs set in from its corners.
void addTable(Scene& s, const glm::vec3& floorCentre, const glm::vec3& topSize, float heightM) {
  constexpr float kLegM = 0.06f, kLegInsetM = 0.05f;
  addObject(s, "table top", makeBox(topSize), kWoodColor, at(floorCentre + glm::vec3(0.0f, heightM - 0.5f * topSize.y, 0.0f)));
  const float legHeightM = heightM - topSize.y;
  const glm::vec2 corner = 0.5f * glm::vec2(topSize.x, topSize.z) - glm::vec2(kLegInsetM + 0.5f * kLegM);
  for (int i = 0; i < 4; ++i) {
    const glm::vec3 offset((i % 2 == 0 ? -1.0f : 1.0f) * corner.x, 0.5f * legHeightM, (i < 2 ? -1.0f : 1.0f) * corner.y);
    addObject(s, fmt::format("table leg {}", i), makeBox({kLegM, legHeightM, kLegM}), kWoodColor, at(floorCentre + offset));
  }
}

// A chair: seat, four legs and a back on the chair's local +Z side, turned by yawRad about +Y.
void addChair(Scene& s, const glm::vec3& floorCentre, float yawRad) {
  constexpr float kSeatM = 0.44f, kSeatHeightM = 0.45f, kSeatThicknessM = 0.04f, kLegM = 0.04f, kBackHeightM = 0.45f;
  const glm::vec3 color{0.35f, 0.45f, 0.6f};
  const glm::mat4 m = at(floorCentre, yawRad);
  addObject(s, "chair seat", makeBox({kSeatM, kSeatThicknessM, kSeatM}), color,
            m * at({0.0f, kSeatHeightM - 0.5f * kSeatThicknessM, 0.0f}));
  const float legHeightM = kSeatHeightM - kSeatThicknessM, corner = 0.5f * (kSeatM - kLegM);
  for (int i = 0; i < 4; ++i)
    addObject(s, fmt::format("chair leg {}", i), makeBox({kLegM, legHeightM, kLegM}), color,
              m * at({(i % 2 == 0 ? -1.0f : 1.0f) * corner, 0.5f * legHeightM, (i < 2 ? -1.0f : 1.0f) * corner}));
  addObject(s, "chair back", makeBox({kSeatM, kBackHeightM, kLegM}), color,
            m * at({0.0f, kSeatHeightM + 0.5f * kBackHeightM, corner}));
}

// Shelves against the back wall: two sides, five boards and a few books (boxes) on them.
void addShelves(Scene& s, const glm::vec3& floorCentre) {
  constexpr float kWidthM = 1.0f, kDepthM = 0.3f, kHeightM = 1.8f, kBoardM = 0.03f;
  constexpr int kBoards = 5;
  const glm::vec3 color{0.7f, 0.62f, 0.5f};
  for (float side : {-1.0f, 1.0f})
    addObject(s, "shelf side", makeBox({kBoardM, kHeightM, kDepthM}), color,
              at(floorCentre + glm::vec3(side * 0.5f * (kWidthM - kBoardM), 0.5f * kHeightM, 0.0f)));
  const float pitchM = (kHeightM - kBoardM) / static_cast<float>(kBoards - 1);
  for (int b = 0; b < kBoards; ++b)
    addObject(s, fmt::format("shelf board {}", b), makeBox({kWidthM - 2.0f * kBoardM, kBoardM, kDepthM}), color,
              at(floorCentre + glm::vec3(0.0f, 0.5f * kBoardM + pitchM * static_cast<float>(b), 0.0f)));
  // Books: (x offset, board, width, height) on the boards' tops.
  struct Book { float x; int board; float width, height; glm::vec3 color; };
  const std::array<Book, 5> books = {{{-0.3f, 1, 0.2f, 0.28f, {0.7f, 0.2f, 0.2f}},
                                      {-0.05f, 1, 0.12f, 0.24f, {0.2f, 0.45f, 0.3f}},
                                      {0.2f, 2, 0.3f, 0.3f, {0.25f, 0.3f, 0.6f}},
                                      {-0.25f, 3, 0.16f, 0.22f, {0.75f, 0.6f, 0.25f}},
                                      {0.25f, 0, 0.35f, 0.33f, {0.45f, 0.3f, 0.5f}}}};
  constexpr float kBookDepthM = 0.22f;
  for (const Book& b : books) {
    const float y = kBoardM + pitchM * static_cast<float>(b.board) + 0.5f * b.height;
    addObject(s, "book", makeBox({b.width, b.height, kBookDepthM}), b.color, at(floorCentre + glm::vec3(b.x, y, 0.0f)));
  }
}

}  // namespace

// A room open toward the camera: the point lamp hangs beside the table's end, low enough that
// light reaches under the top, so the legs throw long shadows across the floor toward the left
// wall, and the top's shadow covers the floor beyond the table's far end and climbs that wall
// (to about 0.5 m); the chair's shadow falls toward the back wall. The spot on the ceiling before
// the shelves lights them: the boards' and books' shadows fall on the boards and the back wall.
Scene makeRoomScene() {
  Scene s;
  s.name = "room";
  const float depthM = kRoomFrontZ - kRoomBackZ, midZ = 0.5f * (kRoomFrontZ + kRoomBackZ);
  addObject(s, "floor", makePlane(2.0f * kRoomHalfWidthM, depthM), {0.7f, 0.68f, 0.64f}, at({0.0f, 0.0f, midZ}));
  const float wideM = 2.0f * (kRoomHalfWidthM + kWallM);
  addObject(s, "back wall", makeBox({wideM, kRoomHeightM, kWallM}), kWallColor,
            at({0.0f, 0.5f * kRoomHeightM, kRoomBackZ - 0.5f * kWallM}));
  for (float side : {-1.0f, 1.0f})
    addObject(s, side < 0.0f ? "left wall" : "right wall", makeBox({kWallM, kRoomHeightM, depthM}), kWallColor,
              at({side * (kRoomHalfWidthM + 0.5f * kWallM), 0.5f * kRoomHeightM, midZ}));
  addObject(s, "ceiling", makeBox({wideM, kWallM, depthM}), kWallColor, at({0.0f, kRoomHeightM + 0.5f * kWallM, midZ}));

  constexpr float kTableHeightM = 0.75f;
  addTable(s, {-0.8f, 0.0f, -0.9f}, {1.4f, 0.05f, 0.8f}, kTableHeightM);
  addChair(s, {0.1f, 0.0f, -1.75f}, glm::pi<float>());
  addShelves(s, {1.75f, 0.0f, kRoomBackZ + 0.16f});

  // Light 0: a bulb (5 cm radius) hanging 0.55 m above the table's height, 0.8 m past its +X end,
  // under a conical shade; its range covers the room (the far corner is 4.5 m away).
  const glm::vec3 warm{1.0f, 0.85f, 0.65f};
  constexpr float kLampRadiusM = 0.05f, kLampRangeM = 6.0f, kLampIntensity = 2.5f;
  const glm::vec3 lamp{0.7f, kTableHeightM + 0.55f, -0.7f};
  s.lights.push_back(pointLight(lamp, kLampRadiusM, kLampRangeM, kLampIntensity, warm));
  // The shade's rim is kShadeGapM above the bulb's centre (clear of its sphere and of the cube
  // maps' near plane, which is at the sphere): it keeps light off the ceiling and the walls' tops,
  // whose shadow edges the +Y face and the side faces' upper halves then carry.
  constexpr float kShadeRadiusM = 0.18f, kShadeHeightM = 0.14f, kShadeGapM = 0.1f;
  addObject(s, "lamp shade", makeCone(kShadeRadiusM, kShadeHeightM, 16), {0.9f, 0.88f, 0.8f},
            at(lamp + glm::vec3(0.0f, kShadeGapM, 0.0f)));
  // The cord the shade hangs from: shown, casting no shadow (it would only shade the ceiling).
  constexpr float kCordRadiusM = 0.006f;
  const float cordBottomY = lamp.y + kShadeGapM + kShadeHeightM;
  addObject(s, "lamp cord", makeCylinder(kCordRadiusM, kRoomHeightM - cordBottomY, 6), {0.1f, 0.1f, 0.1f},
            at({lamp.x, cordBottomY, lamp.z}), false);
  // Light 1: a spot on the ceiling in front of the shelves, aimed down at them: the books' and
  // boards' shadows fall on the boards and the back wall, and its cone's edge crosses the chair.
  constexpr float kSpotInnerDeg = 20.0f, kSpotOuterDeg = 32.0f;
  constexpr float kSpotRadiusM = 0.04f, kSpotRangeM = 5.0f, kSpotIntensity = 4.5f;
  s.lights.push_back(spotLight({1.75f, kRoomHeightM - kSpotRadiusM - 0.1f, -1.2f}, {1.75f, 0.7f, kRoomBackZ},
                               glm::radians(kSpotInnerDeg), glm::radians(kSpotOuterDeg), kSpotRadiusM, kSpotRangeM,
                               kSpotIntensity, {0.85f, 0.9f, 1.0f}));
  s.ambient = glm::vec3(0.04f);
  s.camera.position = {1.7f, 1.55f, 1.2f};
  s.camera.target = {-0.3f, 0.45f, -1.1f};
  s.camera.fovYRad = glm::radians(60.0f);
  s.camera.nearM = 0.05f;
  s.camera.farM = 30.0f;
  s.shadow.filter = "pcss";
  s.shadow.mapSize = 1024;
  return s;
}

// --- night -------------------------------------------------------------------------------------

namespace {

constexpr float kRoadHalfWidthM = 3.5f, kSidewalkM = 3.0f;  // facades stand at |x| = 6.5
constexpr float kKerbM = 0.12f;                               // the sidewalks' height above the road
constexpr float kStreetNearZ = 12.0f, kStreetFarZ = -40.0f;  // the street runs along -Z
constexpr float kLampSpacingM = 9.0f;                          // between lamps on one side
constexpr float kLampHeightM = 4.5f;                           // of the light's centre above the road

// A lamp post on the kerb of side ±1 at z: a pole and an arm reaching over the road, ending in a
// flat head above the light. The head is what makes a street lamp light the street rather than
// the facades' upper floors: it cuts the light above about 30 degrees of elevation.
glm::vec3 addLampPost(Scene& s, float side, float z) {
  constexpr float kPoleRadiusM = 0.08f, kReachM = 0.9f, kArmM = 0.08f;
  constexpr float kHeadGapM = 0.15f;  // from the light's centre to the head: 11 cm clear of the lamp's sphere
  const glm::vec3 kHeadSize{0.5f, 0.06f, 0.3f};
  const glm::vec3 color{0.25f, 0.27f, 0.3f};
  const float poleX = side * (kRoadHalfWidthM + 0.4f), lightX = poleX - side * kReachM;
  const float headY = kLampHeightM + kHeadGapM + 0.5f * kHeadSize.y, topY = headY + 0.5f * kHeadSize.y;
  addObject(s, "lamp pole", makeCylinder(kPoleRadiusM, topY - kKerbM, 8), color, at({poleX, kKerbM, z}));
  addObject(s, "lamp arm", makeBox({kReachM, kArmM, kArmM}), color, at({0.5f * (poleX + lightX), topY - 0.5f * kArmM, z}));
  addObject(s, "lamp head", makeBox(kHeadSize), {0.8f, 0.8f, 0.75f}, at({lightX, headY, z}));
  return {lightX, kLampHeightM, z};
}

void addCar(Scene& s, const glm::vec3& floorCentre, const glm::vec3& color) {
  constexpr float kLengthM = 4.2f, kWidthM = 1.8f, kBodyM = 0.75f, kClearanceM = 0.25f, kCabinM = 0.6f;
  addObject(s, "car body", makeBox({kWidthM, kBodyM, kLengthM}), color, at(floorCentre + glm::vec3(0.0f, kClearanceM + 0.5f * kBodyM, 0.0f)));
  addObject(s, "car cabin", makeBox({0.9f * kWidthM, kCabinM, 0.5f * kLengthM}), 0.7f * color,
            at(floorCentre + glm::vec3(0.0f, kClearanceM + kBodyM + 0.5f * kCabinM, -0.1f * kLengthM)));
  // Wheels stand in for the gap under the body: four blocks at the corners.
  for (int i = 0; i < 4; ++i)
    addObject(s, "car wheel", makeBox({0.25f, 2.0f * kClearanceM, 0.6f}), {0.08f, 0.08f, 0.08f},
              at(floorCentre + glm::vec3((i % 2 == 0 ? -0.4f : 0.4f) * kWidthM, kClearanceM, (i < 2 ? -0.32f : 0.32f) * kLengthM)));
}

void addBench(Scene& s, const glm::vec3& floorCentre) {
  constexpr float kLengthM = 1.8f, kSeatHeightM = 0.45f;
  const glm::vec3 color{0.5f, 0.35f, 0.22f};
  addObject(s, "bench seat", makeBox({0.45f, 0.06f, kLengthM}), color, at(floorCentre + glm::vec3(0.0f, kSeatHeightM, 0.0f)));
  for (float end : {-0.4f, 0.4f})
    addObject(s, "bench leg", makeBox({0.4f, kSeatHeightM, 0.06f}), {0.2f, 0.2f, 0.22f},
              at(floorCentre + glm::vec3(0.0f, 0.5f * kSeatHeightM, end * kLengthM)));
}

void addTree(Scene& s, const glm::vec3& floorCentre) {
  constexpr float kTrunkHeightM = 2.4f, kCrownRadiusM = 1.2f;
  addObject(s, "tree trunk", makeCylinder(0.15f, kTrunkHeightM, 8), {0.35f, 0.25f, 0.18f}, at(floorCentre));
  addObject(s, "tree crown", makeSphere(kCrownRadiusM, 16, 8), {0.22f, 0.4f, 0.2f},
            at(floorCentre + glm::vec3(0.0f, kTrunkHeightM + 0.7f * kCrownRadiusM, 0.0f)));
}

}  // namespace

// Lamps in pairs across the street, from the camera outward; on each side point and spot lamps
// alternate, and each pair is one of each, so every prefix of 2, 4 and 8 lights mixes the kinds.
// Parked cars, benches and trees stand where two pools meet and cast two shadows each.
Scene makeNightScene() {
  Scene s;
  s.name = "night";
  const float lengthM = kStreetNearZ - kStreetFarZ, midZ = 0.5f * (kStreetNearZ + kStreetFarZ);
  const float streetHalfM = kRoadHalfWidthM + kSidewalkM;
  addObject(s, "road", makePlane(2.0f * kRoadHalfWidthM, lengthM), {0.33f, 0.33f, 0.35f}, at({0.0f, 0.0f, midZ}));
  for (float side : {-1.0f, 1.0f})
    addObject(s, "sidewalk", makeBox({kSidewalkM, kKerbM, lengthM}), {0.55f, 0.54f, 0.5f},
              at({side * (kRoadHalfWidthM + 0.5f * kSidewalkM), 0.5f * kKerbM, midZ}));
  // Facades: a row of buildings of varied height on each side, and one across the far end.
  constexpr int kBuildings = 5;
  constexpr float kBuildingDepthM = 4.0f;
  constexpr std::array<float, kBuildings> kHeightsM = {12.0f, 9.0f, 15.0f, 10.0f, 13.0f};
  const float buildingM = lengthM / static_cast<float>(kBuildings);
  for (float side : {-1.0f, 1.0f})
    for (int b = 0; b < kBuildings; ++b) {
      const float h = kHeightsM[static_cast<size_t>((b + (side > 0.0f ? 2 : 0)) % kBuildings)];
      const float tone = 0.4f + 0.05f * static_cast<float>(b % 3);
      addObject(s, fmt::format("building {}", b), makeBox({kBuildingDepthM, h, buildingM - 0.3f}), {tone, tone * 0.92f, tone * 0.85f},
                at({side * (streetHalfM + 0.5f * kBuildingDepthM), 0.5f * h, kStreetNearZ - buildingM * (static_cast<float>(b) + 0.5f)}));
    }
  const float endWidthM = 2.0f * (streetHalfM + kBuildingDepthM);
  addObject(s, "building across", makeBox({endWidthM, kHeightsM[0], kBuildingDepthM}), {0.42f, 0.4f, 0.38f},
            at({0.0f, 0.5f * kHeightsM[0], kStreetFarZ - 0.5f * kBuildingDepthM}));

  const glm::vec3 sodium{1.0f, 0.78f, 0.5f}, led{0.85f, 0.92f, 1.0f};
  constexpr int kPairs = 4;
  constexpr float kFirstLampZ = 4.0f;
  // A 4 cm sphere: with 10 cm the head, 5 cm above it, hid part of the sphere from every facade
  // point above the lamp, a penumbra tens of degrees wide that no filter draws (pcf's RMSE of the
  // far point lamps was 0.13-0.16 against 0.08-0.09 now).
  constexpr float kLampRadiusM = 0.04f, kPointRangeM = 11.0f, kSpotRangeM = 12.0f;
  constexpr float kPointIntensity = 20.0f, kSpotIntensity = 30.0f;
  constexpr float kSpotInnerDeg = 35.0f, kSpotOuterDeg = 55.0f;
  for (int pair = 0; pair < kPairs; ++pair)
    for (float side : {-1.0f, 1.0f}) {
      // Left lamps are points at even pairs, right lamps at odd ones: the kinds alternate both
      // along each side and across the street. The right side is staggered by half a spacing.
      const float z = kFirstLampZ - kLampSpacingM * static_cast<float>(pair) - (side > 0.0f ? 0.5f * kLampSpacingM : 0.0f);
      const glm::vec3 p = addLampPost(s, side, z);
      if ((pair % 2 == 0) == (side < 0.0f)) {
        s.lights.push_back(pointLight(p, kLampRadiusM, kPointRangeM, kPointIntensity, sodium));
      } else {
        // Aimed down and a little toward the road's centre line.
        const glm::vec3 target(p.x - side * 1.5f, 0.0f, p.z);
        s.lights.push_back(spotLight(p, target, glm::radians(kSpotInnerDeg), glm::radians(kSpotOuterDeg), kLampRadiusM,
                                     kSpotRangeM, kSpotIntensity, led));
      }
    }

  const float parkX = kRoadHalfWidthM - 1.3f;
  addCar(s, {-parkX, 0.0f, 0.5f}, {0.6f, 0.15f, 0.12f});
  addCar(s, {parkX, 0.0f, -5.5f}, {0.2f, 0.35f, 0.6f});
  addCar(s, {-parkX, 0.0f, -13.0f}, {0.75f, 0.75f, 0.72f});
  addCar(s, {parkX, 0.0f, -22.0f}, {0.25f, 0.45f, 0.3f});
  const float benchX = streetHalfM - 0.8f;
  addBench(s, {-benchX, kKerbM, -0.5f});
  addBench(s, {benchX, kKerbM, -9.5f});
  addBench(s, {-benchX, kKerbM, -18.5f});
  const float treeX = kRoadHalfWidthM + 1.4f;
  for (float z : {-4.0f, -22.0f}) addTree(s, {-treeX, kKerbM, z});
  for (float z : {0.5f, -17.5f}) addTree(s, {treeX, kKerbM, z});

  s.ambient = {0.02f, 0.025f, 0.04f};  // a moonless night: the sky's faint blue
  s.camera.position = {0.8f, 2.2f, 11.0f};
  s.camera.target = {-0.6f, 0.6f, -12.0f};
  s.camera.fovYRad = glm::radians(55.0f);
  s.camera.nearM = 0.1f;
  s.camera.farM = 200.0f;
  s.shadow.filter = "pcss";
  s.shadow.mapSize = 1024;
  return s;
}

}  // namespace penumbra
