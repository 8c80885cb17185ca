#pragma once
// What tools need of a Shadows object besides what an engine does (penumbra/Shadows.h): each
// light's views and intermediate images, V at world points, the frame blocks for a debug pass of
// their own, shader reloads while running, and the work a filter did once. Penumbra's viewer,
// bench and tests are built on the same calls.
#include <penumbra/ShadowViews.h>
#include <penumbra/Shadows.h>
#include <penumbra/Timings.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace penumbra {

/// The last frame's views of lights[light] as its maps were drawn (with MapUpdates::Budget, a
/// kept map's view is the one an earlier frame drew it with). Valid until the next render().
const LightFrusta& frusta(const Shadows& shadows, size_t light = 0);

/// An intermediate of the last frame: a GL texture Penumbra owns.
struct DebugTexture {
  std::string name;          ///< file-name friendly: "visibility", "shadow-map", "moments"
  uint32_t texture = 0;      ///< GL name: GL_TEXTURE_2D, GL_TEXTURE_2D_ARRAY (a layer per view) or GL_TEXTURE_3D
  uint32_t target = 0;       ///< which of those
  int width = 0, height = 0, layers = 1;
  std::string_view meaning;  ///< what a value is, with its unit
};
/// lights[light]'s visibility, then its filter's maps. The names live until the next render()
/// (a map is remade when its size, view count or format changes) or until the light leaves.
std::vector<DebugTexture> debugTextures(const Shadows& shadows, size_t light = 0);

/// A world point at which to evaluate a light's visibility (visibilityAt).
struct SurfaceSample {
  glm::vec3 position{0.0f};               ///< world (m)
  glm::vec3 geoNormal{0.0f, 1.0f, 0.0f};  ///< unit geometric normal (decides N·L and biases)
  glm::ivec2 pixel{0};                    ///< the pixel it was seen at (filters' per-pixel noise)
};
/// V of lights[light] at world points with the last frame's maps (the visibility pass over a
/// point list). With temporal accumulation on, V as accumulated instead: the last frame's
/// visibility layer, bilinear at the point's position on screen (points off screen read the
/// pass's V). Sets and restores the GL state as render() does.
std::vector<float> visibilityAt(Shadows& shadows, std::span<const SurfaceSample> points, size_t light = 0);

/// Binds Penumbra's frame and shadow-view blocks (PN_UBO_FRAME, PN_UBO_SHADOW of
/// shaders/shared/Bindings.h) for lights[light] as the last render() filled them, for a pass of
/// the caller's that includes shaders/common/shadow.glsl (a debug view of the cascades, say).
void bindFrameBlocks(const Shadows& shadows, size_t light = 0);

/// Reads shader sources from this source tree (its shaders/ and src/) before the embedded
/// copies; reloadShaders() then recompiles every program from them. A program that fails keeps
/// its last good version; the messages say why (empty: all compiled).
void setShaderSourceTree(Shadows& shadows, const std::filesystem::path& root);
std::vector<std::string> reloadShaders(Shadows& shadows);

/// What lights[light]'s filter made once for the current casters (a baked distance field).
std::vector<OneOffCost> oneOffCosts(const Shadows& shadows, size_t light = 0);

}  // namespace penumbra
