#pragma once
// The least shadow map on which the defaults hold (the command line's least --shadow-map).

namespace penumbra {

/// The smallest map side (texels per side) on which the default bias model and filters hold on
/// every built-in scene (acne and detached shadows under 0.1 %, docs/hard.md#map-sizes): below it
/// a texel grows wider than the scenes' casters and pcf's kernel, a fixed count of texels, blurs
/// an edge over many pixels. The command line's --shadow-map starts here; the library, a scene
/// file's mapSize and a map budget still take sizes down to kMinMapSizeTexels (Light.h), where
/// the texel, not the bias, decides.
inline constexpr int kMinDefaultsMapSizeTexels = 1024;

}  // namespace penumbra
