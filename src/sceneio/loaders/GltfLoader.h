#pragma once
// glTF 2.0 (.gltf and .glb) through tinygltf: the default scene's node hierarchy, meshes
// (triangles, strips and fans; indexed or not), base colour factor and texture, alpha-mask
// materials, KHR_lights_punctual lights (size from the light's `extras.size`) and the first
// perspective camera. docs/scenes.md lists what is read, what is ignored and the limits.
#include "sceneio/loaders/ModelImport.h"

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>

namespace penumbra::loaders {

/// Loads a .gltf or .glb file (told apart by the GLB magic, not the extension).
Model loadGltf(const std::filesystem::path& path, ProgressReport& progress);

/// The same from bytes in memory; `name` names the file in errors and external URIs resolve
/// against `baseDir`. Throws Error on any bad input (the fuzz target's entry point).
Model loadGltfFromMemory(std::span<const uint8_t> bytes, const std::string& name,
                         const std::filesystem::path& baseDir, ProgressReport* progress = nullptr);

}  // namespace penumbra::loaders
