#pragma once
// Light-space helpers shared by the projections: the light's view basis, the visible receiver
// region, and the depth plane that maps distance along the light axis to [0,1].
#include <penumbra/Projection.h>

#include <array>
#include <vector>

namespace penumbra {

/// A right-handed view matrix at `eye` looking along `forward` (any up that is not parallel).
glm::mat4 lightViewMatrix(const glm::vec3& eye, const glm::vec3& forward);

/// The 8 corners of the camera frustum between view depths nearM and farM (metres).
std::array<glm::vec3, 8> frustumCorners(const Camera& camera, float aspect, float nearM, float farM);

/// The camera depth range worth shadowing: the near plane up to the farthest scene point (or
/// the camera's far plane, whichever is closer).
float shadowFarDistance(const Camera& camera, const Scene& scene);

/// World bounds of each object (index-aligned with scene.objects).
std::vector<Aabb> objectBounds(const Scene& scene);

/// Depth plane for a light view: depth = ((-z_view) - nearM) / (farM - nearM).
glm::vec4 linearDepthPlane(const glm::mat4& viewFromWorld, float nearM, float farM);

/// Bounds in light view space of the receivers the camera can see: each object's box clipped to
/// the camera frustum's box (both in light space). Empty if nothing is visible.
Aabb visibleReceiversInLightSpace(const glm::mat4& lightFromWorld, const Camera& camera, float aspect,
                                  const Scene& scene);

}  // namespace penumbra
