#pragma once
// Wavefront OBJ through tinyobjloader: positions, normals, texture coordinates, polygons
// (fan-triangulated) and the diffuse colour (Kd) and shininess (Ns) of `mtllib` materials.
// Each (shape, material) pair becomes one mesh. docs/scenes.md lists what is ignored.
#include "sceneio/loaders/ModelImport.h"

#include <filesystem>
#include <string>

namespace penumbra::loaders {

/// Loads an .obj file; `mtllib` files resolve against its folder. Throws Error on bad input.
Model loadObj(const std::filesystem::path& path, ProgressReport& progress);

/// The same from text in memory; `name` names the file in errors, `mtllib` files resolve
/// against `baseDir`. Reports the bytes parsed to `progress` when given.
Model loadObjFromMemory(const std::string& text, const std::string& name, const std::filesystem::path& baseDir,
                        ProgressReport* progress = nullptr);

}  // namespace penumbra::loaders
