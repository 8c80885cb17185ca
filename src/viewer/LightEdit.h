#pragma once
// The viewer's light edits as plain data (unit-tested without GL): a new light placed where it
// shows in the view, a light turned into another type without changing the picture much,
// `light set N KEY VALUE` with the scene file's keys (docs/scenes.md), and the check that keeps
// every edited light one that a scene file can hold, so that "save" always loads back.
#include <penumbra/Scene.h>
#include <penumbra/ShadowViews.h>

#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace penumbra::viewer {

/// Parses one of lightTypeName()'s names (Scene.h: sun, spot, point); throws a usage Error
/// naming the choices.
LightType parseLightType(std::string_view name);

/// "light 2 (point)": how the panels, the labels over the views and the messages name a light.
std::string lightLabel(const Light& light, size_t index);

/// The name of a point light's map layer (cube face, kCubeFaces in penumbra/ShadowViews.h):
/// +X, -X, +Y, -Y, +Z, -Z.
const char* cubeFaceName(int face);

/// "" when the light is one a scene file can hold; otherwise what is wrong (a spot's inner cone
/// wider than its outer, a range inside the light's sphere, a sun larger than
/// kMaxSunAngularRadiusRad, a map size other than 0 or kMinMapSizeTexels..kMaxMapSizeTexels,
/// a value out of Scene.h's limits or not finite).
std::string lightProblem(const Light& light);

/// A new light of `type` for the `index`-th place in the scene's list, where it shows: aimed at the
/// camera's target (kept inside the scene's bounds), from the side of the camera (each index
/// another azimuth), above the scene; spot and point lights as bright there as the default sun.
/// Each index gets another tint so that the lights can be told apart.
Light makeLight(LightType type, const Aabb& sceneBounds, const Camera& camera, size_t index);

/// Turns `light` into a `type` light that lights the scene from about where it did: a sun becomes
/// a spot or point light on its line through the point it lights (size and intensity converted
/// at that distance), a spot or point light becomes the sun of its direction to that point.
void changeLightType(Light& light, LightType type, const Aabb& sceneBounds);

/// The keys of `light set` (the scene file's names, docs/scenes.md): type, position, direction,
/// target, size, color, intensity, outerConeDeg, innerConeDeg, range, castsShadow, mapSize.
std::vector<std::string> lightKeys();
/// Checks `light set N KEY VALUE` without a light: the key is known and the value has its form
/// (a number; a vector as X Y Z or X,Y,Z; a type name; on/off; a whole number of texels).
/// Throws a usage Error saying what is wrong.
void checkLightSetting(std::string_view key, std::span<const std::string> value);
/// Returns `light` with KEY set to VALUE: `type` turns it as changeLightType() does; a new outer
/// cone narrower than the inner one narrows the inner one too. Throws a usage Error for a key
/// the light's type has not (a sun's position), a bad value, or a result that lightProblem()
/// refuses.
Light setLightField(Light light, std::string_view key, std::span<const std::string> value, const Aabb& sceneBounds);

}  // namespace penumbra::viewer
