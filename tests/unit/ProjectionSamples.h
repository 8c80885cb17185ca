#pragma once
// Scene samples the projection tests share.
#include <penumbra/Scene.h>

#include <cstdint>
#include <vector>

namespace penumbra::test {

/// Points on the scene's triangles (area-weighted, seeded) that the camera frustum contains
/// between its near plane and the shadowed far distance; hidden ones too (no occlusion test).
std::vector<glm::vec3> visibleSurfaceSamples(const Scene& scene, float aspect, int count, uint32_t seed);

}  // namespace penumbra::test
