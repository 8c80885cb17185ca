#pragma once
// One headless OpenGL 4.5 context (llvmpipe here) for the whole GL test binary, plus helpers
// that render a scene with a technique and read the visibility back.
#include "platform/Context.h"

#include "techniques/Registry.h"
#include "core/ShadowsAccess.h"
#include <penumbra/Renderer.h>
#include <penumbra/SceneIO.h>

#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace penumbra::test {

gl::HeadlessContext& glContext();

struct RenderResult {
  std::vector<float> visibility;  ///< row 0 = bottom
  GBufferData gbuffer;
  LightFrusta frusta;
  PassTimings timings;
  int width = 0, height = 0;
  float at(int x, int y) const { return visibility[static_cast<size_t>(y) * static_cast<size_t>(width) + static_cast<size_t>(x)]; }
};

/// "key=value" settings of a projection, a filter or the scene (light.size).
using Params = std::vector<std::pair<std::string, std::string>>;

/// A renderer holding `scene` (with the scene-level settings applied) and the technique, ready
/// to render: for tests that need more than renderScene reads back.
std::unique_ptr<Renderer> makeTestRenderer(const Scene& scene, const std::string& projection, const std::string& filter,
                                           const Params& params = {}, int mapSize = kDefaultMapSize);
/// Gives the renderer's technique maps of `mapSize` texels per side.
void setMapSize(Renderer& renderer, int mapSize);

/// Renders `scene` with the given technique and "key=value" settings.
RenderResult renderScene(const Scene& scene, const std::string& projection, const std::string& filter,
                         const Params& params, int width, int height, int mapSize);

/// Projects a world point to pixel coordinates (x right, y up) of a width × height image.
glm::ivec2 projectToPixel(const Scene& scene, const glm::vec3& ws, int width, int height);

}  // namespace penumbra::test
