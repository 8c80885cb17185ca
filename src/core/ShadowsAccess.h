#pragma once
// Penumbra's own tools' way into a Shadows object (the renderer, the viewer, the lab, the tests):
// what penumbra/ShadowsDebug.h offers an engine's tools, with the internal types (the shader
// library, a light's state and filter, debug images as gl::Texture). Not installed.
#include "core/LightState.h"
#include "frame/Filter.h"
#include "shader/ShaderLibrary.h"

#include <penumbra/Shadows.h>
#include <penumbra/ShadowsDebug.h>

#include <span>
#include <vector>

namespace penumbra {

struct ShadowsAccess {
  /// lights[light]'s state in the last frame; `what` names the call in the error for a light
  /// the last frame did not have.
  static core::LightState& light(const Shadows& shadows, size_t light, const char* what);
  static ShaderLibrary& shaders(Shadows& shadows);
  static std::vector<float> visibilityAt(Shadows& shadows, std::span<const SurfaceSample> points, size_t light);
  static void bindFrameBlocks(const Shadows& shadows, size_t light);
  /// What a pass that reads lights[light]'s views must be built with besides them (a paged
  /// projection's layout: common/shadow.glsl); empty for whole maps or before a frame has it.
  static ShaderDefines viewDefines(const Shadows& shadows, size_t light);
  /// lights[light]'s pages (a paged projection), nullptr for whole maps.
  static const VirtualPages* pages(const Shadows& shadows, size_t light);
  /// lights[light]'s visibility, then its filter's maps (only the visibility, without a texture,
  /// before a frame has the light).
  static std::vector<DebugImage> debugImages(const Shadows& shadows, size_t light);
};

/// The shader library the core compiles with (the renderer builds its own passes in it).
inline ShaderLibrary& shaderLibrary(Shadows& shadows) { return ShadowsAccess::shaders(shadows); }
/// lights[light]'s filter instance (its maps) in the last frame.
inline Filter& filterOf(const Shadows& shadows, size_t light = 0) { return *ShadowsAccess::light(shadows, light, "filterOf").filter; }
/// Every intermediate of the last frame for lights[light], as gl::Textures.
inline std::vector<DebugImage> debugImages(const Shadows& shadows, size_t light = 0) { return ShadowsAccess::debugImages(shadows, light); }

}  // namespace penumbra
