#pragma once
// Light-space helpers shared by the projections: the light's view basis, the visible receiver
// region, and the depth plane that maps distance along the light axis to [0,1].
#include "frame/Projection.h"

#include <array>
#include <string>
#include <span>
#include <vector>

namespace penumbra {

/// Why a one-view (or cascaded) projection cannot shadow `light`: a point light's map is a cube,
/// which only the uniform and virtual projections make. Empty for other lights.
inline std::string pointLightIncompatibility(const Light& light) {
  return light.type == LightType::Point
             ? "a point light shines every way: its shadows are six cube faces, which only the uniform and virtual projections make "
               "(a light's own LightShadowSettings::projection = \"uniform\" gives it one beside the others' technique)"
             : std::string();
}

/// A right-handed view matrix at `eye` looking along `forward` (any up that is not parallel).
glm::mat4 lightViewMatrix(const glm::vec3& eye, const glm::vec3& forward);

/// The 8 corners of the camera frustum between view depths nearM and farM (metres).
std::array<glm::vec3, 8> frustumCorners(const Camera& camera, float aspect, float nearM, float farM);

/// The camera depth range worth shadowing: the near plane up to the farthest scene point (or
/// the camera's far plane, whichever is closer).
float shadowFarDistance(const Camera& camera, const SceneExtent& scene);

/// The camera depths (m along its view axis) that `points` span: (nearest, farthest); (+inf, −inf)
/// for none.
glm::vec2 cameraDepthRange(std::span<const glm::vec3> points, const Camera& camera);

/// Depth plane for a light view: depth = ((-z_view) - nearM) / (farM - nearM).
glm::vec4 linearDepthPlane(const glm::mat4& viewFromWorld, float nearM, float farM);

/// Bounds in light view space of the receivers the camera can see: each object's box clipped to
/// the camera frustum (between its near plane and shadowFarDistance). Empty if nothing is visible.
Aabb visibleReceiversInLightSpace(const glm::mat4& lightFromWorld, const Camera& camera, float aspect,
                                  const SceneExtent& scene);

// ---- Convex bodies for the large-view projections (csm, psm, tsm, lispsm) ---------------------

/// A closed half-space {p : dot(n, p) + d >= 0}. Double precision: vertex enumeration intersects
/// nearly parallel planes (a long thin frustum against a flat ground box).
struct HalfSpace {
  glm::dvec3 n{0.0};
  double d = 0.0;
  double eval(const glm::dvec3& p) const { return glm::dot(n, p) + d; }
};

/// The camera frustum between view depths nearM and farM (metres): 6 half-spaces.
std::vector<HalfSpace> frustumHalfSpaces(const Camera& camera, float aspect, float nearM, float farM);
/// An axis-aligned box: 6 half-spaces.
std::vector<HalfSpace> boxHalfSpaces(const Aabb& box);
/// A spot light's square pyramid of half angle coneAngleRad, beyond nearM from its centre: 5.
std::vector<HalfSpace> spotHalfSpaces(const Light& light, float nearM);

/// Vertices of the bounded convex polyhedron where all half-spaces hold (every triple of planes
/// meeting at a point inside the rest). Empty when the intersection is empty or degenerate.
std::vector<glm::vec3> convexVertices(std::span<const HalfSpace> halfSpaces);

/// Vertices of `box` (world, padded by a millimetre so flat boxes keep a volume) ∩ the convex
/// region `convex`; empty when they do not meet.
std::vector<glm::vec3> clipBoxToConvex(const Aabb& box, std::span<const HalfSpace> convex);

/// The prism lo.x <= x <= hi.x, lo.y <= y <= hi.y of a light view space (unbounded along the
/// light's axis), as 4 world half-spaces: what an orthographic map of that rectangle covers.
std::vector<HalfSpace> lightRectHalfSpaces(const glm::mat4& lightFromWorld, const glm::vec2& lo, const glm::vec2& hi);

/// The square pyramid |x|, |y| <= tanHalf·depth, nearM <= depth <= farM of a perspective light
/// view (depth = -z), as 6 world half-spaces.
std::vector<HalfSpace> lightPyramidHalfSpaces(const glm::mat4& lightFromWorld, float tanHalf, float nearM, float farM);

/// The region whose receivers can show in the image between camera depths nearM and farM: the
/// camera frustum ∩ the scene's bounds (∩ the spot pyramid for a spot light), as the vertices of
/// that convex body. Empty when the slice sees no part of the scene.
std::vector<glm::vec3> receiverBody(const Camera& camera, float aspect, float nearM, float farM, const SceneExtent& scene,
                                    const Light& light);

/// What the one-map warped projections (psm, tsm, lispsm) fit: the receiver body over the camera's
/// whole shadowed depth range (near plane to shadowFarDistance, at least twice the near plane) and
/// the casters that can shadow it (casterExtrusion).
struct ViewRegion {
  std::vector<glm::vec3> body, casters;
  float nearM = 0.0f, farM = 0.0f;
};
ViewRegion wholeViewRegion(const Camera& camera, float aspect, const Light& light, const SceneExtent& scene);

/// Points P such that conv(body ∪ P) holds every point inside `casters` that lies between a point
/// of `body` and the light (the casters that can shadow the body). Sun: each vertex moved toward
/// the light until it leaves the casters' box through one chosen slab plane (exact along the
/// plane, conservative elsewhere). Spot: the body scaled toward the light by one common factor.
std::vector<glm::vec3> casterExtrusion(std::span<const glm::vec3> body, const Light& light, const Aabb& casters);

/// The sun's view for projections that must not move with the camera: centred on the scene,
/// looking along the light, eye 2 bounding radii back (the same basis as `uniform`).
glm::mat4 sunViewMatrix(const SceneExtent& scene, const Light& light);

/// Bounds of points after the affine transform m.
Aabb boundsOf(std::span<const glm::vec3> points, const glm::mat4& m);

/// One unwarped light view fitted to `receivers` (world points, e.g. a receiverBody) with casters
/// `casters` (e.g. a casterExtrusion): sun = orthographic in sunViewMatrix's basis, spot =
/// off-centre perspective from the light clamped to its cone; near/far bracket receivers and
/// casters along the light axis. marginFraction widens xy (texels of margin / map size).
ShadowView fitLightView(const SceneExtent& scene, const Light& light, std::span<const glm::vec3> receivers,
                        std::span<const glm::vec3> casters, float marginFraction);

/// A point light's six cube faces (+X, −X, +Y, −Y, +Z, −Z: the order common/shadow.glsl's cubeFace
/// picks them in), perspective views of 90° widened so that each reaches `guardTexels` texels of a
/// `mapSize`-texel map past its edge (a kernel, blocker search or ray near the edge reads the scene
/// beyond it, what the neighbouring face holds, instead of clamping); near at the light's sphere,
/// far at the scene's farthest point or the light's range.
LightFrusta cubeFaceViews(const Light& light, const SceneExtent& scene, int mapSize, float guardTexels);

}  // namespace penumbra
